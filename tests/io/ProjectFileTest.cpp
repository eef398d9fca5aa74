// Projects: a saved project reopens bit for bit, in a versioned JSON with base64 arrays.
#include "ProjectFileTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::project;

TEST_F(ProjectFileTest, RoundTripOfTheDefaultHeadIsBitIdentical)
{
    const Project project = defaultHeadProject();
    const std::string path = (m_dir / "scene.wisp").string();
    const Result<void> written = writeProject(path, project);
    ASSERT_TRUE(written) << written.error().toString();
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    expectBitIdentical(read.value().project, project);
    // Saving what was opened writes the same text.
    EXPECT_EQ(projectToJson(read.value().project, path), readText(path));
}

TEST_F(ProjectFileTest, TheBodyToggleRoundTrips)
{
    for (bool on : { false, true }) {
        Project project = smallProject();
        ASSERT_EQ(project.parameters.set(Param::Body, on ? 1 : 0), "");
        const std::string path = (m_dir / "body.wisp").string();
        ASSERT_TRUE(writeProject(path, project));
        const Result<ProjectReadResult> read = readProject(path);
        ASSERT_TRUE(read) << read.error().toString();
        EXPECT_EQ(read.value().project.parameters.get(Param::Body), on ? 1.0 : 0.0);
        EXPECT_EQ(nlohmann::json::parse(readText(path))["parameters"]["body"], on);
    }
}

TEST_F(ProjectFileTest, ImportedStrandsComeBackBitIdentical)
{
    Project project = defaultHeadProject();
    auto strands = std::make_shared<HairCurves>();
    for (int s = 0; s < 3; ++s) {
        const auto points = strands->strandForWrite(strands->addStrand(static_cast<std::uint32_t>(4 + s)));
        for (std::size_t j = 0; j < points.size(); ++j)
            points[j] = glm::vec3(0.1f * s, 0.3f - 0.017f * j, 1.0f / 3.0f);
    }
    project.regions.back().importedStrands = strands;
    const std::string path = (m_dir / "imported.wisp").string();
    ASSERT_TRUE(writeProject(path, project));
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    const auto& back = read.value().project.regions.back().importedStrands;
    ASSERT_TRUE(back);
    EXPECT_EQ(back->offsets, strands->offsets);
    EXPECT_EQ(back->positions, strands->positions); // exact: floats travel as their bits

    // Offsets that do not describe the points are refused with their key path.
    std::string text = readText(path);
    const std::string good = "\"offsets\": \"";
    const std::size_t at = text.find(good);
    ASSERT_NE(at, std::string::npos);
    text.replace(at + good.size(), 4, "AQAA"); // first offset 1 instead of 0
    const Result<ProjectReadResult> broken = parseProject(text, path);
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().toString().find("imported_strands.offsets"), std::string::npos)
        << broken.error().toString();
}

TEST_F(ProjectFileTest, FileIsVersionedJsonWithBase64Arrays)
{
    const Project project = smallProject();
    const nlohmann::json json = nlohmann::json::parse(projectToJson(project, (m_dir / "p.wisp").string()));
    EXPECT_EQ(json["format"], "wisp-project");
    EXPECT_EQ(json["version"], 1);
    EXPECT_EQ(json["head"]["vertex_count"], 6);
    EXPECT_EQ(json["head"]["triangle_count"], 8);
    // Little-endian float32: 0.1f is 0x3DCCCCCD, stored CD CC CC 3D.
    const auto positions = base64Decode(json["head"]["positions"].get<std::string>());
    ASSERT_TRUE(positions);
    ASSERT_EQ(positions->size(), 6u * 3u * 4u);
    EXPECT_EQ((std::vector<std::uint8_t>(positions->begin(), positions->begin() + 4)),
        (std::vector<std::uint8_t>{ 0xCD, 0xCC, 0xCC, 0x3D }));
    EXPECT_EQ(json["regions"][1]["id"], 7);
    EXPECT_EQ(json["regions"][1]["visible"], false);
    EXPECT_EQ(json["regions"][1]["wisp"]["wisp_size"], 3);
    EXPECT_FALSE(json["regions"][1]["wisp"].contains("gravity"));
    EXPECT_EQ(json["parameters"].size(), kParamCount);
    EXPECT_EQ(json["solo_region"], 7);
    EXPECT_EQ(json["camera"]["fov_y_degrees"], 37.5);
    EXPECT_EQ(json["regions"][1]["tip_colour"][0].dump(), "0.1"); // shortest text that gives 0.1f back

    Project noSolo = project;
    noSolo.soloRegion = kNoSolo;
    EXPECT_TRUE(nlohmann::json::parse(projectToJson(noSolo, "p.wisp"))["solo_region"].is_null());
}

TEST(Base64, KnownVectorsAndStrictDecoding)
{
    auto encode = [](std::string_view s) {
        return base64Encode({ reinterpret_cast<const std::uint8_t*>(s.data()), s.size() });
    };
    // RFC 4648, section 10.
    EXPECT_EQ(encode(""), "");
    EXPECT_EQ(encode("f"), "Zg==");
    EXPECT_EQ(encode("fo"), "Zm8=");
    EXPECT_EQ(encode("foo"), "Zm9v");
    EXPECT_EQ(encode("foob"), "Zm9vYg==");
    EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
    EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i)
        all[i] = static_cast<std::uint8_t>(i);
    for (std::size_t n = 0; n <= all.size(); ++n) {
        const std::span<const std::uint8_t> bytes(all.data(), n);
        const auto decoded = base64Decode(base64Encode(bytes));
        ASSERT_TRUE(decoded) << n;
        EXPECT_TRUE(std::equal(decoded->begin(), decoded->end(), bytes.begin(), bytes.end())) << n;
    }
    std::size_t bad = 0;
    EXPECT_FALSE(base64Decode("Zm9", &bad));
    EXPECT_EQ(bad, 3u);
    EXPECT_FALSE(base64Decode("Zm 9", &bad));
    EXPECT_EQ(bad, 2u);
    EXPECT_FALSE(base64Decode("Zg=A"));
    EXPECT_FALSE(base64Decode("Z==="));
    EXPECT_FALSE(base64Decode("Zh==")); // unused bits set: "Zg==" is the one text for "f"
    EXPECT_FALSE(base64Decode("Zg==Zg=="));
    EXPECT_FALSE(decodeFloat32Array("Zm9v")); // 3 bytes: not whole floats
    const std::vector<float> floats = { 0.0f, -0.0f, 1e-40f, std::numeric_limits<float>::infinity(), 0.1f };
    const auto back = decodeFloat32Array(encodeFloat32Array(floats));
    ASSERT_TRUE(back);
    EXPECT_EQ(std::memcmp(back->data(), floats.data(), sizeof(float) * floats.size()), 0);
}

// The head's up and front axes are stored by name; a project from before them (import_z_up) reads
// as the Z-up turn; a name that is no axis, or a front along the up axis, is refused by key.
TEST_F(ProjectFileTest, TheHeadsImportAxesAreStoredAndOldZUpFilesStillRead)
{
    nlohmann::json json = validJson();
    EXPECT_EQ(json["head"]["import_up"], "+X"); // smallProject's
    EXPECT_EQ(json["head"]["import_front"], "-Y");

    json["head"]["import_up"] = "-Z";
    json["head"]["import_front"] = "+x";
    const fs::path path = m_dir / "axes.wisp";
    writeText(path, json.dump());
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().project.headImportUp, io::Axis::NegZ);
    EXPECT_EQ(read.value().project.headImportFront, io::Axis::PosX);

    nlohmann::json old = validJson();
    old["head"].erase("import_up");
    old["head"].erase("import_front");
    old["head"]["import_z_up"] = true;
    writeText(path, old.dump());
    const Result<ProjectReadResult> oldRead = readProject(path.string());
    ASSERT_TRUE(oldRead) << oldRead.error().toString();
    EXPECT_EQ(oldRead.value().project.headImportUp, io::Axis::PosZ);
    EXPECT_EQ(oldRead.value().project.headImportFront, io::Axis::NegY);

    nlohmann::json bad = validJson();
    bad["head"]["import_up"] = "up";
    EXPECT_EQ(errorOf(bad.dump()), "head.import_up: \"up\" is no axis (+X, -X, +Y, -Y, +Z or -Z)");
    bad = validJson();
    bad["head"]["import_front"] = "-X";
    EXPECT_EQ(errorOf(bad.dump()), "head.import_front: -X is not perpendicular to head.import_up +X");
}

// Issue 12: nlohmann's raw "[json.exception.out_of_range.406]" text, with no place, is translated.
