#include "IoTestSupport.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

using namespace wisp;
using namespace wisp::io;
namespace fs = std::filesystem;
using wisp::test::assetPath;
using wisp::test::slurp;

namespace {

// A closed box of the given size with its lower corner at `corner`, wound outward.
TriangleMesh box(const glm::vec3& size, const glm::vec3& corner = glm::vec3(0.0f))
{
    TriangleMesh mesh;
    for (int i = 0; i < 8; ++i)
        mesh.positions.push_back(corner + size * glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    return mesh;
}

TriangleMesh cube(float edge, const glm::vec3& corner = glm::vec3(0.0f))
{
    return box(glm::vec3(edge), corner);
}

void expectCentred(const TriangleMesh& mesh)
{
    const glm::vec3 centre = boundsOf(mesh).center();
    const float size = std::max(1e-3f, glm::length(boundsOf(mesh).size()));
    EXPECT_NEAR(centre.x, 0.0f, 1e-5f * size);
    EXPECT_NEAR(centre.y, 0.0f, 1e-5f * size);
    EXPECT_NEAR(centre.z, 0.0f, 1e-5f * size);
}

} // namespace

TEST(HeadPlacement, TwoHundredFiftyUnitsAreMillimetres)
{
    TriangleMesh mesh = cube(250.0f, {100.0f, -40.0f, 7.0f});
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Millimetres);
    EXPECT_FLOAT_EQ(placed.scale, 0.001f);
    EXPECT_FALSE(placed.scaledToFit);
    EXPECT_FALSE(placed.rotatedUpright);
    EXPECT_TRUE(placed.note.empty()) << placed.note;
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    EXPECT_EQ(describePlacement(placed), "imported at \u00D70.001 (millimetres)");
}

TEST(HeadPlacement, TwentyFiveUnitsAreCentimetres)
{
    TriangleMesh mesh = cube(25.0f, {-3.0f, 2.0f, 1.0f});
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Centimetres);
    EXPECT_FLOAT_EQ(placed.scale, 0.01f);
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    EXPECT_EQ(describePlacement(placed), "imported at \u00D70.01 (centimetres)");
}

TEST(HeadPlacement, AQuarterUnitIsMetres)
{
    TriangleMesh mesh = cube(0.25f, {1.0f, 1.0f, 1.0f});
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Metres);
    EXPECT_FLOAT_EQ(placed.scale, 1.0f);
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    // The offset says where the file's box went: its centre (1.125, 1.125, 1.125) to the origin.
    EXPECT_NEAR(placed.offset.x, -1.125f, 1e-6f);
}

TEST(HeadPlacement, SizesThatAreNoHeadInAnyUnitAreScaledToAQuarterMetreTall)
{
    // 40 m (or 40 of anything): 0.4 m as centimetres is past the open upper end, and no other
    // unit makes a head of it. Likewise 1000 and 0.05.
    for (const float edge : {40.0f, 1000.0f, 0.05f}) {
        TriangleMesh mesh = box({edge * 0.8f, edge, edge * 0.6f}, glm::vec3(edge * 0.1f));
        const HeadPlacement placed = placeHead(mesh);
        EXPECT_EQ(placed.unit, LengthUnit::Auto) << edge;
        EXPECT_TRUE(placed.scaledToFit) << edge;
        EXPECT_NEAR(placed.scale, 0.25f / edge, 1e-5f * 0.25f / edge) << edge;
        EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-5f) << edge;
        EXPECT_NE(placed.note.find("scaled it to 0.25 m tall"), std::string::npos) << placed.note;
        expectCentred(mesh);
        EXPECT_NE(describePlacement(placed).find("(scaled to 0.25 m tall)"), std::string::npos)
            << describePlacement(placed);
    }
}

TEST(HeadPlacement, ExplicitUnitOrScaleOverridesTheGuess)
{
    TriangleMesh asCentimetres = cube(250.0f);
    const HeadPlacement unit = placeHead(asCentimetres, LengthUnit::Centimetres);
    EXPECT_EQ(unit.unit, LengthUnit::Centimetres);
    EXPECT_FLOAT_EQ(unit.scale, 0.01f);
    EXPECT_NEAR(boundsOf(asCentimetres).size().y, 2.5f, 1e-5f);
    EXPECT_NE(unit.note.find("2.5 m at its largest"), std::string::npos) << unit.note; // said, not undone
    expectCentred(asCentimetres);

    TriangleMesh scaled = cube(250.0f);
    const HeadPlacement factor = placeHead(scaled, LengthUnit::Auto, 0.0012f);
    EXPECT_EQ(factor.unit, LengthUnit::Auto);
    EXPECT_FLOAT_EQ(factor.scale, 0.0012f);
    EXPECT_FALSE(factor.scaledToFit);
    EXPECT_NEAR(boundsOf(scaled).size().y, 0.3f, 1e-6f);
    EXPECT_TRUE(factor.note.empty()) << factor.note;
    EXPECT_EQ(describePlacement(factor), "imported at \u00D70.0012 (chosen scale)");

    // A factor that is a unit is reported as that unit; the factor wins over the unit argument.
    TriangleMesh both = cube(250.0f);
    const HeadPlacement millimetres = placeHead(both, LengthUnit::Metres, 0.001f);
    EXPECT_EQ(millimetres.unit, LengthUnit::Millimetres);
    EXPECT_NEAR(boundsOf(both).size().y, 0.25f, 1e-6f);

    // A nonsense factor is ignored, and the note says so.
    TriangleMesh negative = cube(250.0f);
    const HeadPlacement ignored = placeHead(negative, LengthUnit::Auto, -2.0f);
    EXPECT_EQ(ignored.unit, LengthUnit::Millimetres);
    EXPECT_NE(ignored.note.find("ignored the scale -2"), std::string::npos) << ignored.note;
}

TEST(HeadPlacement, ZUpIsTurnedToYUpKeepingTheWinding)
{
    // 0.2 wide, 0.1 deep, 0.3 tall along +Z, in metres.
    TriangleMesh mesh = box({0.2f, 0.1f, 0.3f});
    const glm::vec3 topCornerBefore = mesh.positions[7]; // (0.2, 0.1, 0.3)
    HeadPlacementSettings settings;
    settings.zUp = true;
    const HeadPlacement placed = placeHead(mesh, settings);
    EXPECT_TRUE(placed.rotatedUpright);
    EXPECT_EQ(placed.unit, LengthUnit::Metres);
    const glm::vec3 size = boundsOf(mesh).size();
    EXPECT_NEAR(size.x, 0.2f, 1e-6f);
    EXPECT_NEAR(size.y, 0.3f, 1e-6f);
    EXPECT_NEAR(size.z, 0.1f, 1e-6f);
    expectCentred(mesh);
    // (x, y, z) -> (x, z, -y), then centred: the top corner is up (+Y) and at the front-most -Z.
    const glm::vec3 expected = glm::vec3(topCornerBefore.x, topCornerBefore.z, -topCornerBefore.y) + placed.offset;
    EXPECT_NEAR(glm::length(mesh.positions[7] - expected), 0.0f, 1e-6f);
    EXPECT_NEAR(mesh.positions[7].y, 0.15f, 1e-6f);
    // The turn is a rotation: the triangle on the old +Z face (the top) now faces +Y.
    EXPECT_NEAR(glm::dot(faceNormal(mesh, 2), glm::vec3(0, 1, 0)), 1.0f, 1e-6f);
    EXPECT_NE(describePlacement(placed).find("turned Z-up to Y-up"), std::string::npos);
}

TEST(HeadPlacement, ApplyPlacementRepeatsWhatPlaceHeadDid)
{
    const TriangleMesh original = box({180.0f, 240.0f, 200.0f}, {-20.0f, 300.0f, 4.0f});
    TriangleMesh placedMesh = original;
    HeadPlacementSettings settings;
    settings.zUp = true;
    const HeadPlacement placed = placeHead(placedMesh, settings);
    TriangleMesh again = original;
    applyPlacement(again, placed);
    for (std::size_t i = 0; i < original.positions.size(); ++i)
        EXPECT_EQ(again.positions[i], placedMesh.positions[i]) << i;
}

TEST(HeadPlacement, EmptyAndFlatMeshesAreHandled)
{
    TriangleMesh empty;
    const HeadPlacement none = placeHead(empty);
    EXPECT_FLOAT_EQ(none.scale, 1.0f);
    EXPECT_FALSE(none.note.empty());

    TriangleMesh point;
    point.positions = {{3, 3, 3}, {3, 3, 3}, {3, 3, 3}};
    point.triangles.assign(1, glm::uvec3(0, 1, 2));  // (not a braced list: GCC 12 warns about its temporary)
    const HeadPlacement degenerate = placeHead(point);
    EXPECT_FLOAT_EQ(degenerate.scale, 1.0f);
    EXPECT_NE(degenerate.note.find("no extent"), std::string::npos) << degenerate.note;
    expectCentred(point);

    // A flat sheet (no height) 2 units wide: scaled by its largest extent instead.
    TriangleMesh sheet = box({2.0f, 0.0f, 1.0f});
    const HeadPlacement flat = placeHead(sheet);
    EXPECT_TRUE(flat.scaledToFit);
    EXPECT_NEAR(boundsOf(sheet).size().x, 0.25f, 1e-6f);
}

TEST(HeadPlacement, GltfFixesTheUpAxis)
{
    EXPECT_TRUE(formatFixesUpAxis("head.glb"));
    EXPECT_TRUE(formatFixesUpAxis("/x/Head.GLTF"));
    EXPECT_FALSE(formatFixesUpAxis("head.obj"));
    EXPECT_FALSE(formatFixesUpAxis("head.stl"));
}

// Real heads land at a head's size whatever unit they were saved in.
TEST(HeadPlacement, SharedHeadsLandAtHeadSize)
{
    for (const char* name :
        {"heads/max_planck_decimated.obj", "heads/igea_tristrips.ply", "heads/cy_woman_head.ply"}) {
        const fs::path path = assetPath(name);
        REQUIRE_ASSET(path);
        Result<MeshReadResult> read = readMesh(path.string());
        ASSERT_TRUE(read.ok()) << read.error().toString();
        TriangleMesh mesh = std::move(read).value().mesh;
        const HeadPlacement placed = placeHead(mesh);
        const glm::vec3 size = boundsOf(mesh).size();
        EXPECT_GE(size.y, 0.15f) << name << ": " << describePlacement(placed) << " " << placed.note;
        EXPECT_LE(size.y, 0.40f) << name << ": " << describePlacement(placed) << " " << placed.note;
        expectCentred(mesh);
        EXPECT_TRUE(validateMesh(mesh).empty()) << name;
        std::cout << "[          ] " << name << ": " << describePlacement(placed) << (placed.note.empty() ? "" : "; ")
                  << placed.note << "; size " << size.x << " x " << size.y << " x " << size.z << " m\n";
    }
}

// Issue 12: a nearly flat head (a subnormal extent on one axis) crashed the BVH build, and one
// stray vertex 16,372 units away made the groom's work absurd. Both are refused once placed.
TEST(HeadPlacement, CheckPlacedHeadRefusesFlatAndHugeHeads)
{
    TriangleMesh head = cube(0.2f, {-0.1f, -0.1f, -0.1f});
    EXPECT_EQ(checkPlacedHead(head), "");

    TriangleMesh flat = box({0.19f, 0.19f, 1e-42f});
    placeHead(flat);
    EXPECT_EQ(checkPlacedHead(flat).rfind("the placed head is 0.19 x 0.19 x 1.001e-42 m: flat along z (less than "
                                          "0.01 m)",
                                          0),
              0u)
        << checkPlacedHead(flat);

    // A 0.3 m head with one vertex 16,372 units away, placed as the editor places it.
    TriangleMesh stray = cube(0.3f);
    stray.positions.push_back({16372.0f, 0.0f, 0.0f});
    stray.triangles.push_back({1, 8, 3});
    const HeadPlacement placed = placeHead(stray);
    EXPECT_TRUE(placed.scaledToFit);
    const std::string problem = checkPlacedHead(stray);
    EXPECT_NE(problem.find("more than 3 m at its largest"), std::string::npos) << problem;

    // Just inside both bounds is a head.
    TriangleMesh wide = box({2.99f, 0.011f, 0.5f});
    EXPECT_EQ(checkPlacedHead(wide), "");

    TriangleMesh broken = cube(0.2f);
    broken.positions[3].y = INFINITY;
    EXPECT_EQ(checkPlacedHead(broken), "vertex 3 has a non-finite coordinate");
}
