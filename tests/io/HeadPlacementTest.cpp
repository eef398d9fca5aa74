#include "io/HeadPlacement.h"
#include "IoTestSupport.h"
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
    mesh.triangles = { { 0, 2, 1 }, { 1, 2, 3 }, { 4, 5, 6 }, { 5, 7, 6 }, { 0, 1, 4 }, { 1, 5, 4 }, { 2, 6, 3 },
        { 3, 6, 7 }, { 0, 4, 2 }, { 2, 4, 6 }, { 1, 3, 5 }, { 3, 7, 5 } };
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
    TriangleMesh mesh = cube(250.0f, { 100.0f, -40.0f, 7.0f });
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Millimetres);
    EXPECT_FLOAT_EQ(placed.scale, 0.001f);
    EXPECT_FALSE(placed.scaledToFit);
    EXPECT_FALSE(placed.turned());
    EXPECT_EQ(placed.note.find("units wide"), std::string::npos) << placed.note;
    // A cube has no face: its axes are kept, and the note says so.
    EXPECT_NE(placed.note.find("could not tell which way is up"), std::string::npos) << placed.note;
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    EXPECT_EQ(describePlacement(placed), "imported at \u00D70.001 (millimetres)");
}

TEST(HeadPlacement, TwentyFiveUnitsAreCentimetres)
{
    TriangleMesh mesh = cube(25.0f, { -3.0f, 2.0f, 1.0f });
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Centimetres);
    EXPECT_FLOAT_EQ(placed.scale, 0.01f);
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    EXPECT_EQ(describePlacement(placed), "imported at \u00D70.01 (centimetres)");
}

TEST(HeadPlacement, AQuarterUnitIsMetres)
{
    TriangleMesh mesh = cube(0.25f, { 1.0f, 1.0f, 1.0f });
    const HeadPlacement placed = placeHead(mesh);
    EXPECT_EQ(placed.unit, LengthUnit::Metres);
    EXPECT_FLOAT_EQ(placed.scale, 1.0f);
    EXPECT_NEAR(boundsOf(mesh).size().y, 0.25f, 1e-6f);
    expectCentred(mesh);
    // The offset says where the file's box went: its centre (1.125, 1.125, 1.125) to the origin.
    EXPECT_NEAR(placed.offset.x, -1.125f, 1e-6f);
}

TEST(HeadPlacement, SkullsThatAreNoHeadInAnyUnitAreScaledTo16CentimetresWide)
{
    // 40 (or 40 of anything) tall, 32 wide: 0.32 m as centimetres is past the open upper end of
    // skull widths, and no other unit makes a skull of it. Likewise 1000 and 0.05.
    for (const float edge : { 40.0f, 1000.0f, 0.05f }) {
        TriangleMesh mesh = box({ edge * 0.8f, edge, edge * 0.6f }, glm::vec3(edge * 0.1f));
        const HeadPlacement placed = placeHead(mesh);
        EXPECT_EQ(placed.unit, LengthUnit::Auto) << edge;
        EXPECT_TRUE(placed.scaledToFit) << edge;
        EXPECT_NEAR(placed.scale, 0.16f / (0.8f * edge), 1e-5f * 0.2f / edge) << edge;
        EXPECT_NEAR(boundsOf(mesh).size().x, 0.16f, 1e-5f) << edge;
        EXPECT_NEAR(placed.skullWidthMetres, 0.16f, 1e-5f) << edge;
        EXPECT_NE(placed.note.find("scaled it to 0.16 m wide"), std::string::npos) << placed.note;
        expectCentred(mesh);
        EXPECT_NE(describePlacement(placed).find("(scaled to a 0.16 m wide skull)"), std::string::npos)
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
    EXPECT_NE(unit.note.find("the skull is 2.5 m wide"), std::string::npos) << unit.note; // said, not undone
    expectCentred(asCentimetres);

    TriangleMesh scaled = cube(250.0f);
    const HeadPlacement factor = placeHead(scaled, LengthUnit::Auto, 0.0011f);
    EXPECT_EQ(factor.unit, LengthUnit::Auto);
    EXPECT_FLOAT_EQ(factor.scale, 0.0011f);
    EXPECT_FALSE(factor.scaledToFit);
    EXPECT_NEAR(boundsOf(scaled).size().y, 0.275f, 1e-6f);
    EXPECT_EQ(factor.note.find("the skull is"), std::string::npos) << factor.note;
    EXPECT_EQ(describePlacement(factor), "imported at \u00D70.0011 (chosen scale)");

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
    TriangleMesh mesh = box({ 0.2f, 0.1f, 0.3f });
    const glm::vec3 topCornerBefore = mesh.positions[7]; // (0.2, 0.1, 0.3)
    HeadPlacementSettings settings;
    settings.up = Axis::PosZ; // the artist's choice (Head Up Axis, --up +z, --z-up)
    const HeadPlacement placed = placeHead(mesh, settings);
    EXPECT_EQ(placed.up, Axis::PosZ);
    EXPECT_EQ(placed.front, Axis::NegY);
    EXPECT_FALSE(placed.upFromShape);
    EXPECT_EQ(placed.note.find("could not tell"), std::string::npos) << "a chosen axis is no guess: " << placed.note;
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
    EXPECT_NE(describePlacement(placed).find("+Z up, face -Y"), std::string::npos) << describePlacement(placed);
}

TEST(HeadPlacement, ApplyPlacementRepeatsWhatPlaceHeadDid)
{
    const TriangleMesh original = box({ 180.0f, 240.0f, 200.0f }, { -20.0f, 300.0f, 4.0f });
    TriangleMesh placedMesh = original;
    HeadPlacementSettings settings;
    settings.up = Axis::PosZ;
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
    point.positions = { { 3, 3, 3 }, { 3, 3, 3 }, { 3, 3, 3 } };
    point.triangles.assign(1, glm::uvec3(0, 1, 2)); // (not a braced list: GCC 12 warns about its temporary)
    const HeadPlacement degenerate = placeHead(point);
    EXPECT_FLOAT_EQ(degenerate.scale, 1.0f);
    EXPECT_NE(degenerate.note.find("no extent"), std::string::npos) << degenerate.note;
    expectCentred(point);

    // A flat sheet (no height) 2 units wide: its width is no skull's in any unit.
    TriangleMesh sheet = box({ 2.0f, 0.0f, 1.0f });
    const HeadPlacement flat = placeHead(sheet);
    EXPECT_TRUE(flat.scaledToFit);
    EXPECT_NEAR(boundsOf(sheet).size().x, 0.16f, 1e-6f);
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
        { "heads/max_planck_decimated.obj", "heads/igea_tristrips.ply", "heads/cy_woman_head.ply" }) {
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

namespace {

TriangleMesh readHead(const fs::path& path)
{
    Result<MeshReadResult> read = readMesh(path.string());
    EXPECT_TRUE(read.ok()) << read.error().toString();
    return read ? std::move(read).value().mesh : TriangleMesh{};
}

// The file turned by a proper rotation that takes +Y to `up` (x, y, z are the file's axes).
TriangleMesh turnedCopy(const TriangleMesh& mesh, glm::vec3 (*turn)(const glm::vec3&))
{
    TriangleMesh copy = mesh;
    for (glm::vec3& p : copy.positions)
        p = turn(p);
    return copy;
}

struct SharedHead {
    const char* name;
    Axis up;
    Axis front;
};

// Up and face of the shared heads, read off their meshes by hand (sagittal and horizontal
// sections; for the CT2Hair head also its hair, which hangs toward -X from roots on the +X side).
constexpr SharedHead kSharedHeads[] = {
    { "heads/max_planck_decimated.obj", Axis::PosY, Axis::NegZ },
    { "heads/igea_tristrips.ply", Axis::PosY, Axis::PosZ },
    { "heads/cy_woman_head.ply", Axis::PosZ, Axis::PosX },
    { "hair/ct2hair_bangs_head.ply", Axis::PosX, Axis::NegY },
};

} // namespace

// Each shared head is turned upright, face toward +Z, whatever axes its file uses; and its skull
// (not its bust) sets its size.
TEST(HeadPlacement, SharedHeadsAreTurnedUprightFromTheirShape)
{
    for (const SharedHead& head : kSharedHeads) {
        const fs::path path = assetPath(head.name);
        REQUIRE_ASSET(path);
        TriangleMesh mesh = readHead(path);
        const HeadPlacement placed = placeHead(mesh);
        EXPECT_TRUE(placed.upFromShape) << head.name << ": " << placed.orientation;
        EXPECT_EQ(axisName(placed.up), std::string(axisName(head.up))) << head.name << ": " << placed.orientation;
        EXPECT_EQ(axisName(placed.front), std::string(axisName(head.front))) << head.name << ": " << placed.orientation;
        // A skull is 0.13 to 0.2 m wide (over the ears); fitted ones are 0.16 m.
        EXPECT_GE(placed.skullWidthMetres, 0.13f) << head.name;
        EXPECT_LE(placed.skullWidthMetres, 0.20f) << head.name;
        EXPECT_NE(describePlacement(placed).find("(from its shape)"), std::string::npos) << describePlacement(placed);
        std::cout << "[          ] " << head.name << ": " << describePlacement(placed) << "; skull "
                  << placed.skullWidthMetres << " m wide; " << placed.orientation << "\n";
    }
}

// Turning a file to another up axis does not change where the head lands: each shared head, turned
// so that its up goes to +Z, -Z, +X and -Y (the last also turning its face), lands where it did.
TEST(HeadPlacement, RotatedCopiesOfAHeadLandTheSame)
{
    const std::pair<const char*, glm::vec3 (*)(const glm::vec3&)> turns[] = {
        { "+Y to +Z", [](const glm::vec3& p) { return glm::vec3(p.x, -p.z, p.y); } },
        { "+Y to -Z", [](const glm::vec3& p) { return glm::vec3(p.x, p.z, -p.y); } },
        { "+Y to +X", [](const glm::vec3& p) { return glm::vec3(p.y, -p.x, p.z); } },
        { "+Y to -Y, +Z to +X", [](const glm::vec3& p) { return glm::vec3(p.z, -p.y, p.x); } },
    };
    for (const SharedHead& head : kSharedHeads) {
        const fs::path path = assetPath(head.name);
        REQUIRE_ASSET(path);
        const TriangleMesh original = readHead(path);
        TriangleMesh reference = original;
        const HeadPlacement referencePlacement = placeHead(reference);
        ASSERT_TRUE(referencePlacement.upFromShape) << head.name;
        const float size = glm::length(boundsOf(reference).size());
        for (const auto& [name, turn] : turns) {
            TriangleMesh copy = turnedCopy(original, turn);
            const HeadPlacement placed = placeHead(copy);
            EXPECT_TRUE(placed.upFromShape) << head.name << ", " << name << ": " << placed.orientation;
            EXPECT_FLOAT_EQ(placed.scale, referencePlacement.scale) << head.name << ", " << name;
            float worst = 0.0f;
            for (std::size_t i = 0; i < copy.positions.size(); ++i)
                worst = std::max(worst, glm::distance(copy.positions[i], reference.positions[i]));
            EXPECT_LT(worst, 1e-5f * size) << head.name << ", " << name << ": " << placed.orientation;
        }
    }
}

// A bust is sized by its skull: the shoulders below do not shrink the head.
TEST(HeadPlacement, ABustIsSizedByItsSkullNotItsHeight)
{
    const fs::path path = assetPath("heads/max_planck_decimated.obj");
    REQUIRE_ASSET(path);
    TriangleMesh bust = readHead(path);
    TriangleMesh alone = bust;
    const HeadPlacement headAlone = placeHead(alone);
    // Shoulders and chest: a box 420 mm wide, 200 mm tall, 200 mm deep under the neck, making the
    // mesh 540 mm tall (past the 400 mm that the whole-mesh rule took for a head).
    const Aabb head = boundsOf(bust);
    const TriangleMesh chest = box(
        { 420.0f, 200.0f, 200.0f }, { head.center().x - 210.0f, head.min.y - 200.0f + 1.0f, head.center().z - 100.0f });
    const auto base = static_cast<std::uint32_t>(bust.positions.size());
    bust.positions.insert(bust.positions.end(), chest.positions.begin(), chest.positions.end());
    for (glm::uvec3 t : chest.triangles)
        bust.triangles.push_back(t + base);
    ASSERT_GT(boundsOf(bust).size().y, 500.0f);

    const HeadPlacement placed = placeHead(bust);
    EXPECT_EQ(placed.unit, LengthUnit::Millimetres) << describePlacement(placed) << "; " << placed.note;
    EXPECT_FALSE(placed.scaledToFit);
    EXPECT_NEAR(placed.skullWidthMetres, headAlone.skullWidthMetres, 1e-4f);
    EXPECT_NEAR(placed.skullWidthMetres, 0.193f, 0.001f);
    EXPECT_NEAR(boundsOf(bust).size().y, 0.54f, 0.01f);
}

// The artist's up axis wins over the shape, on a real head too, and the note says nothing is guessed.
TEST(HeadPlacement, AChosenUpAxisOverridesTheShape)
{
    const fs::path path = assetPath("heads/cy_woman_head.ply");
    REQUIRE_ASSET(path);
    const TriangleMesh asRead = readHead(path);
    TriangleMesh lying = asRead;
    HeadPlacementSettings settings;
    settings.up = Axis::PosY;
    const HeadPlacement kept = placeHead(lying, settings);
    EXPECT_EQ(kept.up, Axis::PosY);
    EXPECT_EQ(kept.front, Axis::PosZ);
    EXPECT_FALSE(kept.turned());
    EXPECT_NE(kept.orientation.find("+Y up as chosen"), std::string::npos) << kept.orientation;
    EXPECT_NEAR(boundsOf(lying).size().y / boundsOf(lying).size().z, 96.31f / 120.0f, 0.01f) << "left lying";

    TriangleMesh upright = asRead;
    settings.up = Axis::PosZ;
    const HeadPlacement zUp = placeHead(upright, settings);
    EXPECT_EQ(zUp.front, Axis::NegY) << "the smallest turn from +Z up";
    EXPECT_NEAR(boundsOf(upright).size().y / boundsOf(upright).size().x, 120.0f / 85.94f, 0.01f);
}

// Shapes that are no head keep their axes and say why; nothing odd in them trips the detector.
TEST(HeadPlacement, ShapesThatAreNoHeadKeepTheirAxesAndSayWhy)
{
    const TriangleMesh cube = box({ 1.0f, 1.0f, 1.0f });
    const HeadOrientation symmetric = detectHeadOrientation(cube.positions);
    EXPECT_FALSE(symmetric.found);
    EXPECT_NE(symmetric.reason.find("mirror symmetry"), std::string::npos) << symmetric.reason;

    std::vector<glm::vec3> odd = cube.positions;
    odd.push_back({ std::nanf(""), 0.0f, 0.0f });
    EXPECT_EQ(detectHeadOrientation(odd).reason, "a vertex is not a finite point");
    const TriangleMesh sheet = box({ 2.0f, 0.0f, 1.0f });
    EXPECT_EQ(detectHeadOrientation(sheet.positions).reason, "the mesh is flat or has no finite extent");
    std::vector<glm::vec3> huge = { { -3e38f, 0, 0 }, { 3e38f, 1, 0 }, { 0, 0, 1 }, { 0, 1, 1 } };
    EXPECT_FALSE(detectHeadOrientation(huge).found);
    EXPECT_EQ(detectHeadOrientation(std::vector<glm::vec3>{}).reason, "too few vertices to tell which way is up");

    EXPECT_EQ(parseAxis("+x"), Axis::PosX);
    EXPECT_EQ(parseAxis("Z"), Axis::PosZ);
    EXPECT_EQ(parseAxis("-y"), Axis::NegY);
    EXPECT_FALSE(parseAxis("up"));
    EXPECT_FALSE(parseAxis("+"));
    EXPECT_FALSE(parseAxis("-w"));
}

// Issue 12: a nearly flat head (a subnormal extent on one axis) crashed the BVH build, and one
// stray vertex 16,372 units away made the groom's work absurd. Both are refused once placed.
TEST(HeadPlacement, CheckPlacedHeadRefusesFlatAndHugeHeads)
{
    TriangleMesh head = cube(0.2f, { -0.1f, -0.1f, -0.1f });
    EXPECT_EQ(checkPlacedHead(head), "");

    TriangleMesh flat = box({ 0.19f, 0.19f, 1e-42f });
    placeHead(flat);
    EXPECT_EQ(checkPlacedHead(flat).rfind("the placed head is 0.19 x 0.19 x 1.001e-42 m: flat along z (less than "
                                          "0.01 m)",
                  0),
        0u)
        << checkPlacedHead(flat);

    // A 0.3 m head with one vertex 16,372 units away, placed as the editor places it.
    TriangleMesh stray = cube(0.3f);
    stray.positions.push_back({ 16372.0f, 0.0f, 0.0f });
    stray.triangles.push_back({ 1, 8, 3 });
    const HeadPlacement placed = placeHead(stray);
    EXPECT_TRUE(placed.scaledToFit);
    const std::string problem = checkPlacedHead(stray);
    // Fitted by its "skull", the stray vertex's span becomes the width and the rest collapses:
    // refused either way, before any groom is built.
    EXPECT_EQ(problem.rfind("the placed head is ", 0), 0u) << problem;
    TriangleMesh unplaced = cube(0.3f);
    unplaced.positions.push_back({ 16372.0f, 0.0f, 0.0f });
    unplaced.triangles.push_back({ 1, 8, 3 });
    EXPECT_NE(checkPlacedHead(unplaced).find("more than 3 m at its largest"), std::string::npos)
        << checkPlacedHead(unplaced);

    // Just inside both bounds is a head.
    TriangleMesh wide = box({ 2.99f, 0.011f, 0.5f });
    EXPECT_EQ(checkPlacedHead(wide), "");

    TriangleMesh broken = cube(0.2f);
    broken.positions[3].y = INFINITY;
    EXPECT_EQ(checkPlacedHead(broken), "vertex 3 has a non-finite coordinate");
}
