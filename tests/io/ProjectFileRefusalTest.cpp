// Projects: damaged and inconsistent files are refused with the key path, never a crash.
#include "ProjectFileTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::project;

TEST_F(ProjectFileTest, TruncatedProjectsAreRefusedAtEveryLength)
{
    const std::string path = (m_dir / "p.wisp").string();
    ASSERT_TRUE(writeProject(path, smallProject()));
    const std::string text = readText(path);
    const std::size_t end = text.find_last_not_of(" \n") + 1;
    for (std::size_t length = 0; length < end; ++length) {
        const Result<ProjectReadResult> result = parseProject(std::string_view(text).substr(0, length), path);
        ASSERT_FALSE(result) << "length " << length;
        EXPECT_FALSE(result.error().message.empty());
        EXPECT_LT(result.error().toString().size(), 600u) << "length " << length; // no kilobytes of quoted text
    }
    EXPECT_TRUE(parseProject(std::string_view(text).substr(0, end), path));
    // And through files, at a few lengths (writing a file per length is slow on a busy disk).
    const std::string cutPath = (m_dir / "cut.wisp").string();
    for (std::size_t length : { std::size_t(0), std::size_t(1), end / 3, end / 2, end - 1 }) {
        writeText(cutPath, text.substr(0, length));
        EXPECT_FALSE(readProject(cutPath)) << "length " << length;
    }
}

TEST_F(ProjectFileTest, InconsistentProjectsAreRefusedWithTheKeyPath)
{
    const nlohmann::json valid = validJson();
    auto damaged = [&](auto edit) {
        nlohmann::json json = valid;
        edit(json);
        return errorOf(json.dump());
    };
    EXPECT_EQ(errorOf(valid.dump()), "");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][0]["weights"] = encodeFloat32Array(std::vector<float>(5, 0.5f));
    }),
        "regions[0].weights: 5 weights for a head of 6 vertices");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][1]["weights"] = encodeFloat32Array(std::vector<float>{ 0, 0, 1.5f, 0, 0, 0 });
    }),
        "regions[1].weights: the weight of vertex 2 is 1.500000; weights are 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][0]["weights"] = encodeFloat32Array(std::vector<float>{ 0, 0, 0, std::nanf(""), 0, 0 });
    }),
        "regions[0].weights: the weight of vertex 3 is nan; weights are 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["weights"] = "not base64!"; }),
        "regions[0].weights: not valid base64 of little-endian 32-bit floats");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["head"]["triangles"] = encodeUint32Array(std::vector<std::uint32_t>(24, 9));
    }),
        "head.triangles: triangle 0 refers to vertex 9; the head has 6");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"]["vertex_count"] = 7; }),
        "head.positions: 18 numbers where the 7 vertices need 21");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"]["vertex_count"] = 1e12; }),
        "head.vertex_count: 1000000000000.0 is not a whole number 0..4294967295");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][1]["id"] = 0; }),
        "regions[1].id: 0 is already the id of regions[0]");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][1]["id"] = 4294967295u; }),
        "regions[1].id: 4294967295 is reserved (it means \"no region\")");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["solo_region"] = 3; }), "solo_region: 3 is the id of no region");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["wisp"]["clump_degree"] = 3.0; }),
        "regions[0].wisp.clump_degree: 3.0 is outside -1..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["parameters"]["gravity"] = "strong"; }),
        "parameters.gravity: \"strong\" is not a number");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][1]["root_colour"] = { 0.5, 2, 0 };
    }),
        "regions[1].root_colour: expected 3 numbers 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["visible"] = 1; }),
        "regions[0].visible: 1 is not true or false");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["camera"]["distance_metres"] = 0; }),
        "camera.distance_metres: the distance must be a positive number");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["camera"]["pivot"] = { 0, 1e300, 0 };
    }),
        "camera.pivot: expected 3 finite numbers");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"].erase("positions"); }), "head.positions: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0].erase("id"); }), "regions[0].id: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j.erase("head"); }), "head: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["head"]["embedded"] = false;
        j["head"]["source"] = "";
    }),
        "head.source: a head that is not stored in the project needs the file it comes from");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["version"] = 2; }), ": version 2 is newer than this Wisp reads (1)");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["format"] = "wisp-preset"; }),
        "format: this is a Wisp preset, not a project");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"] = nlohmann::json::array();
        for (int i = 0; i < 300; ++i)
            j["regions"].push_back(nlohmann::json::object());
    }),
        "regions: 300 regions; at most 256 are allowed");
}

TEST_F(ProjectFileTest, UnknownKeysWarnAndMissingOptionalKeysTakeDefaults)
{
    nlohmann::json json = validJson();
    json["thumbnail"] = "png";
    json["camera"]["roll_radians"] = 0.1;
    json["regions"][0]["wisp"]["sheen"] = 1;
    json["regions"][0].erase("name");
    json["regions"][0].erase("tip_colour");
    json.erase("solo_region");
    const fs::path path = m_dir / "extra.wisp";
    writeText(path, json.dump());
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().warnings,
        (std::vector<std::string>{ "thumbnail: unknown key, ignored", "regions[0].wisp.sheen: unknown key, ignored",
            "camera.roll_radians: unknown key, ignored" }));
    EXPECT_EQ(read.value().project.regions[0].name, "Region 1");
    expectSameBits(read.value().project.regions[0].tipColour, GrowthRegion{}.tipColour, "tip");
    EXPECT_EQ(read.value().project.soloRegion, kNoSolo);
}

TEST_F(ProjectFileTest, MalformedAndEmptyFilesAreRefused)
{
    EXPECT_EQ(errorOf(""), ": the file is empty");
    EXPECT_EQ(errorOf("{\"format\": \"wisp-project\",\n \"version\": 1,,}"),
        "line 2, column 15: syntax error while parsing object key - unexpected ','; expected string literal");
    const Result<ProjectReadResult> missing = readProject((m_dir / "none.wisp").string());
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message, "the file does not exist");
}

TEST_F(ProjectFileTest, NumberOverflowNamesTheLineAndColumn)
{
    EXPECT_EQ(errorOf("{\"format\": \"wisp-project\",\n \"version\": 1e400}"),
        "line 2, column 13: the number 1e400 is too large to hold (it overflows a double)");
}

// Issue 12: a project is a way to bring a head in too; a flat one (which crashed the BVH build)
// is refused at load, with the same words as Open Head.
TEST_F(ProjectFileTest, FlatEmbeddedHeadIsRefused)
{
    TriangleMesh flat = octahedron(0.1f);
    for (glm::vec3& p : flat.positions)
        p.z *= 1e-40f;
    const fs::path path = m_dir / "flat.wisp";
    ASSERT_TRUE(writeProject(path.string(), makeProject(flat, std::vector<float>(flat.vertexCount(), 0.5f))));
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().location, "head");
    EXPECT_NE(read.error().message.find("flat along z"), std::string::npos) << read.error().toString();
}
