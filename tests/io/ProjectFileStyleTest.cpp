// Projects: the salon edits (per-strand style) come back exactly; broken entries are refused.
#include "ProjectFileTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::project;

// An identity above 2^53 (a double would round it) with the top bit set: region 7 | pore 123456789 | 2^63.
constexpr std::uint64_t kHighStrand = (std::uint64_t(7) << 32 | 123456789u) | (std::uint64_t(1) << 63);

// Salon edits with awkward numbers: every field set, one shape only, one wetness only.
StyleEdits sampleStyle()
{
    StyleEdits edits;
    StrandStyle& all = edits[kHighStrand];
    all.lengthMetres = 0.2f;
    all.curlRadiusMetres = 0.01f;
    all.curlTurnsPerMetre = 6.0f;
    all.stiffnessScale = 3.0f;
    all.wetness = 0.5f;
    // (push_back, not a braced list: GCC 12 warns about the list's temporaries)
    all.shape.push_back(glm::vec3(0.0f, 1.6f, 0.1f));
    all.shape.push_back(glm::vec3(0.01f, 1.5f, 1.0f / 3.0f));
    all.shape.push_back(glm::vec3(-0.0f, 1.4f, 1e-30f));
    StrandStyle& combed = edits[5];
    combed.lengthMetres = 0.123456789f;
    combed.curlRadiusMetres = 0.0f; // straightened: 0 differs from the default -1
    combed.shape = { glm::vec3(0.1f, 1.7f, 0.0f), glm::vec3(0.1f, 1.6f, 0.0f), glm::vec3(0.11f, 1.5f, 0.01f),
        glm::vec3(0.12f, 1.4f, 2.0f / 3.0f) };
    edits[4294967298u].wetness = 1.0f / 3.0f;
    return edits;
}

TEST_F(ProjectFileTest, StyleEditsComeBackExactly)
{
    Project project = smallProject();
    project.style = sampleStyle();
    project.style[9] = StrandStyle{}; // nothing changed: not saved
    const std::string path = (m_dir / "styled.wisp").string();
    const Result<void> written = writeProject(path, project);
    ASSERT_TRUE(written) << written.error().toString();
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    Project expected = project;
    expected.style.erase(9);
    EXPECT_TRUE(read.value().project.style == expected.style);
    expectBitIdentical(read.value().project, expected);
    EXPECT_EQ(projectToJson(read.value().project, path), readText(path));

    // In identity order; identities as decimal text; only the changed fields.
    const nlohmann::json json = nlohmann::json::parse(readText(path));
    ASSERT_TRUE(json.contains("style"));
    ASSERT_EQ(json["style"].size(), 3u);
    EXPECT_EQ(json["style"][0]["strand"], "5");
    EXPECT_EQ(json["style"][1].size(), 2u);
    EXPECT_EQ(json["style"][1]["strand"], "4294967298");
    EXPECT_EQ(json["style"][1]["wetness"].dump(), "0.33333334");
    EXPECT_EQ(json["style"][2]["strand"], std::to_string(kHighStrand));
    EXPECT_EQ(json["style"][2]["strand"], "9223372067043003669");
    EXPECT_EQ(json["style"][2]["curl_turns"], 6);
    EXPECT_EQ(json["style"][2]["length"].dump(), "0.2"); // the shortest text that gives 0.2f back
    EXPECT_FALSE(json["style"][0].contains("wetness"));
    EXPECT_FALSE(json["style"][0].contains("stiffness_scale"));
    EXPECT_EQ(json["style"][0]["curl_radius"], 0);
    const auto shape = decodeFloat32Array(json["style"][0]["shape"].get<std::string>());
    ASSERT_TRUE(shape);
    EXPECT_EQ(shape->size(), 12u);

    // Without edits there is no "style" at all.
    project.style.clear();
    project.style[3] = StrandStyle{};
    EXPECT_FALSE(nlohmann::json::parse(projectToJson(project, path)).contains("style"));
}

TEST_F(ProjectFileTest, ProjectsWithoutStyleLoadWithNoEdits)
{
    nlohmann::json json = validJson();
    EXPECT_FALSE(json.contains("style"));
    const Result<ProjectReadResult> old = parseProject(json.dump(), (m_dir / "old.wisp").string());
    ASSERT_TRUE(old) << old.error().toString();
    EXPECT_TRUE(old.value().project.style.empty());
    EXPECT_TRUE(old.value().warnings.empty());

    json["style"] = nlohmann::json::array();
    const Result<ProjectReadResult> empty = parseProject(json.dump(), (m_dir / "empty.wisp").string());
    ASSERT_TRUE(empty) << empty.error().toString();
    EXPECT_TRUE(empty.value().project.style.empty());

    // An entry that changes nothing is no edit; an unknown key in an entry is a warning.
    json["style"] = nlohmann::json::array({ nlohmann::json{ { "strand", "12" } },
        nlohmann::json{ { "strand", "13" }, { "wetness", 0.25 }, { "comb", "left" } } });
    const Result<ProjectReadResult> read = parseProject(json.dump(), (m_dir / "warn.wisp").string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().warnings, (std::vector<std::string>{ "style[1].comb: unknown key, ignored" }));
    ASSERT_EQ(read.value().project.style.size(), 1u);
    EXPECT_EQ(read.value().project.style.at(13).wetness, 0.25f);
}

TEST_F(ProjectFileTest, BrokenStyleEntriesAreRefusedWithTheKeyPath)
{
    const nlohmann::json valid = validJson();
    const nlohmann::json good = { { "strand", "4294967298" }, { "wetness", 0.5 } };
    // The error of a project whose style is a good entry then `entry`.
    auto errorWith = [&](const nlohmann::json& entry) {
        nlohmann::json json = valid;
        json["style"] = nlohmann::json::array({ good, entry });
        const Result<ProjectReadResult> result = parseProject(json.dump(), (m_dir / "broken.wisp").string());
        return result ? std::string() : result.error().location + ": " + result.error().message;
    };
    auto contains
        = [](const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; };
    auto shapeOf = [](std::vector<float> xyz) { return encodeFloat32Array(xyz); };

    EXPECT_EQ(errorWith({ { "strand", "77" }, { "stiffness_scale", 2 } }), "");

    std::string error = errorWith({ { "strand", 77 }, { "wetness", 0.5 } });
    EXPECT_TRUE(contains(error, "style[1].strand: 77 is not a strand identity")) << error;
    error = errorWith({ { "strand", 4294967298.0 } });
    EXPECT_TRUE(contains(error, "style[1].strand: ")) << error;
    EXPECT_EQ(errorWith({ { "strand", "abc" }, { "wetness", 0.5 } }),
        "style[1].strand: \"abc\" is not a strand identity (a decimal number)");
    for (const char* text : { "", "-5", "+5", "12x", " 12", "1e9", "0x10" }) {
        error = errorWith({ { "strand", text }, { "wetness", 0.5 } });
        EXPECT_TRUE(contains(error, "style[1].strand: ") && contains(error, "is not a strand identity"))
            << text << ": " << error;
    }
    error = errorWith({ { "strand", "18446744073709551616" }, { "wetness", 0.5 } }); // 2^64
    EXPECT_TRUE(contains(error, "style[1].strand: \"18446744073709551616\" is too large for a strand identity"))
        << error;
    EXPECT_EQ(errorWith({ { "strand", "18446744073709551615" }, { "wetness", 0.5 } }), "");
    EXPECT_EQ(errorWith({ { "wetness", 0.5 } }), "style[1].strand: missing");

    EXPECT_EQ(errorWith({ { "strand", "9" }, { "wetness", 3 } }), "style[1]: strand 9: wetness 3 is outside 0..1");
    error = errorWith({ { "strand", "9" }, { "length", -0.1 } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: length -0.1 is outside")) << error;
    error = errorWith({ { "strand", "9" }, { "stiffness_scale", 0.5 } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: stiffness scale 0.5 is outside 1..50")) << error;
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "wetness", "wet" } }), "style[1].wetness: \"wet\" is not a number");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "curl_radius", 1e300 } }), "style[1].curl_radius: 1e+300 is too large");

    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0, 0, 2, 0, 1 }) } }),
        "style[1].shape: 7 numbers are not whole points");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0, 0, std::nanf(""), 0 }) } }),
        "style[1].shape: point 1 is not finite");
    EXPECT_EQ(errorWith({ { "strand", "9" },
                  { "shape", shapeOf({ 0, 1, 0, std::numeric_limits<float>::infinity(), 2, 0 }) } }),
        "style[1].shape: point 1 is not finite");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", "not base64!" } }),
        "style[1].shape: not valid base64 of little-endian 32-bit floats");
    error = errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0 }) } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: shape has 1 points")) << error;

    EXPECT_EQ(errorWith({ { "strand", "4294967298" }, { "wetness", 0.25 } }),
        "style[1].strand: 4294967298 is already the strand of style[0]");
    EXPECT_EQ(errorWith({ { "strand", "04294967298" }, { "wetness", 0.25 } }),
        "style[1].strand: 4294967298 is already the strand of style[0]");

    error = errorWith(nlohmann::json::array({ 1, 2 }));
    EXPECT_TRUE(contains(error, "style[1]: ")) << error;
    nlohmann::json json = valid;
    json["style"] = good;
    const Result<ProjectReadResult> notAList = parseProject(json.dump(), (m_dir / "broken.wisp").string());
    ASSERT_FALSE(notAList);
    EXPECT_EQ(notAList.error().location, "style");
    EXPECT_TRUE(contains(notAList.error().message, "expected a list")) << notAList.error().message;
}

TEST_F(ProjectFileTest, AProjectWithAnInvalidStyleEditIsNotSaved)
{
    const std::string path = (m_dir / "p.wisp").string();
    Project project = smallProject();
    project.style = sampleStyle();
    project.style[4].wetness = 3.0f; // the first entry in the file (identity order)
    const Result<void> result = writeProject(path, project);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().location, "style[0]");
    EXPECT_EQ(result.error().message, "not saved: strand 4: wetness 3 is outside 0..1");

    project.style = sampleStyle();
    project.style[2] = StrandStyle{}; // not written, so not counted
    project.style[kHighStrand].shape.push_back(project.style[kHighStrand].shape.back()); // coincident points
    const Result<void> coincident = writeProject(path, project);
    ASSERT_FALSE(coincident);
    EXPECT_EQ(coincident.error().location, "style[2]");
    EXPECT_EQ(coincident.error().message,
        "not saved: strand " + std::to_string(kHighStrand) + ": shape points 2 and 3 coincide");
    EXPECT_TRUE(fs::is_empty(m_dir));
}
