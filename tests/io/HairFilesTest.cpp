// Hair files: cyHair .hair and USC .data in and out, OBJ and glTF export parsed back independently.
#include "HairFilesTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::hair;

// ---- the real samples ------------------------------------------------------------------------------

TEST_F(HairFiles, SamplesLoadAsTheSameHundredStrands)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    const HairCurves fromHair = readOk(kBangsHair);
    const HairCurves fromData = readOk(kBangsData);
    EXPECT_EQ(100u, fromHair.strandCount());
    EXPECT_EQ(1165u, fromHair.pointCount());
    for (std::size_t s = 0; s < fromHair.strandCount(); ++s) { // the README: 4-20 segments a strand
        EXPECT_GE(fromHair.pointsIn(s), 5u);
        EXPECT_LE(fromHair.pointsIn(s), 21u);
    }
    expectBitIdentical(fromHair, fromData);

    // Checked against the raw bytes: the .data file's first strand and its first point.
    const std::string raw = slurp(kBangsData);
    EXPECT_EQ(fromData.pointsIn(0), getU32(raw, 4));
    EXPECT_EQ(0, std::memcmp(raw.data() + 8, &fromData.positions[0], 12));
}

TEST_F(HairFiles, CyHairAndUscRoundTripExactly)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    for (const fs::path& sample : { kBangsHair, kBangsData }) {
        SCOPED_TRACE(sample.string());
        const HairCurves original = readOk(sample);
        for (const char* name : { "out.hair", "out.data", "OUT.HAIR", "Out.Data" }) {
            SCOPED_TRACE(name);
            ASSERT_TRUE(writeHair((dir / name).string(), original));
            expectBitIdentical(original, readOk(dir / name));
        }
    }
    // The .data format has no free fields: the written file is the sample, byte for byte. The
    // .hair file differs only in its info string ("Wisp").
    const HairCurves bangs = readOk(kBangsHair);
    ASSERT_TRUE(writeHair((dir / "bangs.data").string(), bangs));
    EXPECT_EQ(slurp(kBangsData), slurp(dir / "bangs.data"));
    ASSERT_TRUE(writeHair((dir / "bangs.hair").string(), bangs));
    const std::string ours = slurp(dir / "bangs.hair"), theirs = slurp(kBangsHair);
    ASSERT_EQ(theirs.size(), ours.size());
    EXPECT_EQ(theirs.substr(0, 40), ours.substr(0, 40));
    EXPECT_EQ(std::string("Wisp\0\0", 6), ours.substr(40, 6));
    EXPECT_EQ(theirs.substr(128), ours.substr(128));
    EXPECT_EQ(0x3u, getU32(ours, 12));
    EXPECT_EQ(6u, filesInDir().size()); // and no temporary files left behind
}

TEST_F(HairFiles, ObjPolylinesParseBack)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    const fs::path path = dir / "bangs.obj";
    ASSERT_TRUE(writeHair(path.string(), bangs));
    const ObjFile obj = parseObj(slurp(path));
    ASSERT_FALSE(obj.comments.empty());
    EXPECT_NE(std::string::npos, obj.comments[0].find("100 strands, 1165 points")) << obj.comments[0];
    ASSERT_EQ(bangs.pointCount(), obj.vertices.size());
    for (std::size_t i = 0; i < obj.vertices.size(); ++i) {
        ASSERT_NEAR(bangs.positions[i].x, obj.vertices[i].x, 1e-6f);
        ASSERT_NEAR(bangs.positions[i].y, obj.vertices[i].y, 1e-6f);
        ASSERT_NEAR(bangs.positions[i].z, obj.vertices[i].z, 1e-6f);
        ASSERT_EQ(bangs.positions[i], obj.vertices[i]); // %.9g round-trips a float
    }
    ASSERT_EQ(bangs.strandCount(), obj.lines.size());
    for (std::size_t s = 0; s < bangs.strandCount(); ++s) {
        ASSERT_EQ(bangs.pointsIn(s), obj.lines[s].size());
        for (std::size_t i = 0; i < obj.lines[s].size(); ++i)
            ASSERT_EQ(bangs.offsets[s] + i + 1, obj.lines[s][i]);
    }
    EXPECT_TRUE(obj.faces.empty());

    // With a head: a second object whose faces index past the strands' points.
    const TriangleMesh head = tetrahedron();
    HairExportOptions options;
    options.head = &head;
    ASSERT_TRUE(writeHair((dir / "with_head.OBJ").string(), bangs, options));
    const ObjFile both = parseObj(slurp(dir / "with_head.OBJ"));
    ASSERT_EQ(bangs.pointCount() + head.positions.size(), both.vertices.size());
    ASSERT_EQ(head.triangles.size(), both.faces.size());
    EXPECT_EQ(bangs.pointCount() + 1 + head.triangles[3].y, both.faces[3][1]);
    EXPECT_EQ(head.positions[2], both.vertices[bangs.pointCount() + 2]);
}

TEST_F(HairFiles, GltfAndGlbParseBack)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    const TriangleMesh head = tetrahedron();
    HairExportOptions withHead;
    withHead.head = &head;

    ASSERT_TRUE(writeHair((dir / "bangs.gltf").string(), bangs));
    {
        SCOPED_TRACE("gltf");
        expectGltfHolds(parseGltf(slurp(dir / "bangs.gltf")), bangs, nullptr);
    }
    ASSERT_TRUE(writeHair((dir / "bangs.glb").string(), bangs));
    {
        SCOPED_TRACE("glb");
        expectGltfHolds(parseGlb(slurp(dir / "bangs.glb")), bangs, nullptr);
    }
    ASSERT_TRUE(writeHair((dir / "head.GLTF").string(), bangs, withHead));
    {
        SCOPED_TRACE("gltf with head");
        expectGltfHolds(parseGltf(slurp(dir / "head.GLTF")), bangs, &head);
    }
    ASSERT_TRUE(writeHair((dir / "head.glb").string(), smallGroom(), withHead));
    {
        SCOPED_TRACE("glb with head");
        expectGltfHolds(parseGlb(slurp(dir / "head.glb")), smallGroom(), &head);
    }
}

TEST_F(HairFiles, GltfWidthsFollowTheOptions)
{
    HairExportOptions options;
    options.rootWidthMetres = 100e-6f;
    options.tipWidthMetres = 0.0f;
    const HairCurves groom = smallGroom();
    ASSERT_TRUE(writeHair((dir / "w.gltf").string(), groom, options));
    const Gltf g = parseGltf(slurp(dir / "w.gltf"));
    const std::size_t width = g.json["meshes"][0]["primitives"][0]["attributes"]["_WIDTH"];
    const std::vector<float> w = g.read<float>(width, 1);
    // Strand 1 has five points: 100, 75, 50, 25, 0 micrometres.
    for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(100e-6f * (1.0f - 0.25f * float(i)), w[2 + i], 1e-9f);

    options.rootWidthMetres = std::numeric_limits<float>::quiet_NaN();
    const Result<void> error = writeHair((dir / "nan.gltf").string(), groom, options);
    ASSERT_FALSE(error.ok());
    EXPECT_NE(std::string::npos, error.error().message.find("width")) << error.error().toString();
    EXPECT_FALSE(fs::exists(dir / "nan.gltf"));
}
