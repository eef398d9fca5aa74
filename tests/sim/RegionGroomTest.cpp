// Growth regions and live regrooms: what painting and wisp sliders do to the groom and to the
// running simulation.
#include "SimFixtures.h"

#include "sim/geometry/MeshBvh.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/groom/ScalpBrush.h"
#include "sim/solver/HairSimulation.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

using namespace wisp;
using wisp::test::defaultHead;
using wisp::test::testParameters;

namespace {

GrowthRegion regionNamed(std::uint32_t id, const std::string& name, std::vector<float> weights)
{
    GrowthRegion r;
    r.id = id;
    r.name = name;
    r.weights = std::move(weights);
    r.values = testParameters();
    return r;
}

// The default growth map split at the mid-plane: left (x < centre) and right halves.
std::pair<std::vector<float>, std::vector<float>> halves()
{
    const TriangleMesh& head = defaultHead().mesh;
    const float mid = boundsOf(head).center().x;
    std::vector<float> left = defaultHead().growthWeights, right = left;
    for (std::size_t i = 0; i < head.positions.size(); ++i)
        (head.positions[i].x < mid ? right[i] : left[i]) = 0.0f;
    return { left, right };
}

std::map<std::uint64_t, std::vector<glm::vec3>> strandsByIdentity(const Groom& groom, const HairCurves& curves)
{
    std::map<std::uint64_t, std::vector<glm::vec3>> out;
    for (std::size_t i = 0; i < groom.strandCount(); ++i) {
        const auto s = curves.strand(i);
        out[groom.strandIdentity(i)] = { s.begin(), s.end() };
    }
    return out;
}

} // namespace

TEST(RegionGroom, EachRegionGrowsWithItsOwnWispSettingsAndOnlyWhereItIsPainted)
{
    auto [left, right] = halves();
    std::vector<GrowthRegion> regions{ regionNamed(0, "Left", left), regionNamed(1, "Right", right) };
    regions[1].values.set(Param::Length, 0.10);
    regions[1].values.set(Param::LengthVariation, 0.0);
    regions[0].values.set(Param::Length, 0.30);
    regions[0].values.set(Param::LengthVariation, 0.0);
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, kNoSolo, testParameters()), "");
    const Groom& g = sim.groom();
    ASSERT_EQ(g.regionIds.size(), 2u);
    const float mid = boundsOf(defaultHead().mesh).center().x;
    std::size_t perRegion[2] = { 0, 0 };
    for (std::size_t i = 0; i < g.strandCount(); ++i) {
        const int r = g.regionOfStrand[i];
        ++perRegion[r];
        EXPECT_FLOAT_EQ(g.lengths[i], r == 0 ? 0.30f : 0.10f);
        // Roots lie where their own region is painted (a triangle straddling the mid-plane may
        // reach a little across it).
        if (r == 0)
            EXPECT_LT(g.rootPositions[i].x, mid + 0.01f);
        else
            EXPECT_GT(g.rootPositions[i].x, mid - 0.01f);
        EXPECT_EQ(g.regionOfStrand[g.keyStrand[g.wispOf[i]]], r) << "a wisp never mixes regions";
    }
    EXPECT_GT(perRegion[0], 50u);
    EXPECT_GT(perRegion[1], 50u);
}

TEST(RegionGroom, HiddenAndSoloDecideWhichRegionsGrow)
{
    auto [left, right] = halves();
    std::vector<GrowthRegion> regions{ regionNamed(0, "Left", left), regionNamed(7, "Right", right) };
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, 7, testParameters()), "");
    EXPECT_EQ(sim.groom().regionIds, std::vector<std::uint32_t>{ 7 });
    regions[1].visible = false;
    ASSERT_EQ(sim.regroom(regions, kNoSolo, testParameters()), "");
    EXPECT_EQ(sim.groom().regionIds, std::vector<std::uint32_t>{ 0 });
    regions[0].visible = false;
    ASSERT_EQ(sim.regroom(regions, kNoSolo, testParameters()), ""); // nothing grows: allowed, empty
    EXPECT_EQ(sim.groom().strandCount(), 0u);
    sim.step();
    HairCurves frame;
    sim.buildFrame(frame);
    EXPECT_EQ(frame.strandCount(), 0u);
}

TEST(RegionGroom, ChangingOneRegionsWispSettingsChangesOnlyItsStrands)
{
    auto [left, right] = halves();
    std::vector<GrowthRegion> regions{ regionNamed(0, "Left", left), regionNamed(1, "Right", right) };
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, kNoSolo, testParameters()), "");
    const Groom before = sim.groom();
    regions[1].values.set(Param::ClumpDegree, 1.0);
    regions[1].values.set(Param::WispSize, 9);
    ASSERT_EQ(sim.regroom(regions, kNoSolo, testParameters()), "");
    const Groom& after = sim.groom();
    const auto a = strandsByIdentity(before, before.rest);
    const auto b = strandsByIdentity(after, after.rest);
    std::size_t leftSame = 0, rightChanged = 0;
    for (const auto& [id, points] : a) {
        const bool isLeft = (id >> 32) == 0;
        const auto it = b.find(id);
        ASSERT_NE(it, b.end()) << "wisp settings do not add or remove roots";
        if (isLeft) {
            EXPECT_EQ(it->second, points); // bit-identical rest shapes
            ++leftSame;
        } else if (it->second != points) {
            ++rightChanged;
        }
    }
    EXPECT_GT(leftSame, 50u);
    EXPECT_GT(rightChanged, 50u);
    EXPECT_GT(sim.groomBuilder().reusedWisps(), 0u);
}

TEST(RegionGroom, ADabAddsRootsOnlyNearItAndReusesEveryOtherWisp)
{
    const TriangleMesh& head = defaultHead().mesh;
    std::vector<GrowthRegion> regions{ regionNamed(0, "Scalp", defaultHead().growthWeights) };
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(head, regions, kNoSolo, testParameters()), "");
    const Groom before = sim.groom();

    // Paint on the cheek, where the default map grows nothing.
    const Aabb box = boundsOf(head);
    const glm::vec3 cheek = sim.bvh().closestPoint({ box.max.x, box.center().y - 0.02f, box.center().z + 0.03f }).point;
    BrushSettings brush;
    brush.radiusMetres = 0.02f;
    brush.strength = 1.0f;
    brush.falloff = 0.0f;
    brush.mirrorX = false;
    ScalpBrush scalp(head);
    ASSERT_FALSE(scalp.dab(cheek, brush, regions[0].weights.forWrite()).empty());
    ASSERT_EQ(sim.regroom(regions, kNoSolo, testParameters()), "");
    const Groom& after = sim.groom();
    EXPECT_GT(after.strandCount(), before.strandCount());
    std::set<std::uint64_t> old;
    for (std::size_t i = 0; i < before.strandCount(); ++i)
        old.insert(before.strandIdentity(i));
    for (std::size_t i = 0; i < after.strandCount(); ++i) {
        if (!old.count(after.strandIdentity(i))) {
            EXPECT_LT(glm::distance(after.rootPositions[i], cheek), brush.radiusMetres + 1e-3f);
        }
    }
    EXPECT_GT(sim.groomBuilder().reusedWisps(), 10 * sim.groomBuilder().builtWisps());
}

TEST(RegionGroom, RegroomKeepsTheMotionOfStrandsThatStayAndStartsNewOnesAtRest)
{
    std::vector<GrowthRegion> regions{ regionNamed(0, "Scalp", defaultHead().growthWeights) };
    ParameterValues v = testParameters();
    v.set(Param::WindSpeed, 10.0);
    v.set(Param::WindAzimuth, 0.0);
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, kNoSolo, v), "");
    for (int i = 0; i < 60; ++i)
        sim.step();
    HairCurves moving;
    sim.buildFrame(moving);
    const auto before = strandsByIdentity(sim.groom(), moving);

    // A second region: its strands are new; the first region's keep moving from where they were.
    auto [left, right] = halves();
    regions.push_back(regionNamed(1, "Right", right));
    ASSERT_EQ(sim.regroom(regions, kNoSolo, v), "");
    EXPECT_GT(sim.carriedStrands(), 0u);
    EXPECT_GT(sim.startedStrands(), 0u);
    HairCurves now;
    sim.buildFrame(now);
    const auto after = strandsByIdentity(sim.groom(), now);
    std::size_t kept = 0;
    for (const auto& [id, points] : before) {
        const auto it = after.find(id);
        ASSERT_NE(it, after.end());
        ASSERT_EQ(it->second.size(), points.size());
        for (std::size_t j = 0; j < points.size(); ++j)
            ASSERT_LT(glm::distance(it->second[j], points[j]), 1e-6f) << "strand " << id << " jumped";
        ++kept;
    }
    EXPECT_EQ(kept, before.size());
    // New strands start at their rest shape.
    const Groom& g = sim.groom();
    for (std::size_t i = 0; i < g.strandCount(); ++i) {
        if (!before.count(g.strandIdentity(i)) && g.isKey(i)) {
            for (std::size_t j = 0; j < g.rest.pointsIn(i); ++j)
                ASSERT_LT(glm::distance(now.strand(i)[j], g.rest.strand(i)[j]), 1e-6f);
        }
    }
}

TEST(RegionGroom, StiffnessScaleMakesARegionHoldItsShapeAgainstGravity)
{
    auto [left, right] = halves();
    std::vector<GrowthRegion> regions{ regionNamed(0, "Left", left), regionNamed(1, "Right", right) };
    regions[0].values.set(Param::StiffnessScale, 0.0);
    regions[1].values.set(Param::StiffnessScale, 4.0);
    ParameterValues v = testParameters();
    v.set(Param::Stiffness, 0.2);
    v.set(Param::Gravity, 30.0);
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, kNoSolo, v), "");
    for (int i = 0; i < 200; ++i)
        sim.step();
    HairCurves frame;
    sim.buildFrame(frame);
    const Groom& g = sim.groom();
    double sag[2] = { 0, 0 };
    int count[2] = { 0, 0 };
    for (std::size_t w = 0; w < g.wispCount(); ++w) {
        const std::uint32_t k = g.keyStrand[w];
        const int r = g.regionOfStrand[k];
        sag[r] += glm::distance(frame.strand(k).back(), g.rest.strand(k).back());
        ++count[r];
    }
    ASSERT_GT(count[0], 5);
    ASSERT_GT(count[1], 5);
    EXPECT_LT(sag[1] / count[1], 0.5 * sag[0] / count[0]) << "the stiff region moved as much as the limp one";
}

TEST(RegionGroom, BadRegionsAreRefusedByName)
{
    std::vector<GrowthRegion> regions{ regionNamed(0, "Fringe", defaultHead().growthWeights) };
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(defaultHead().mesh, regions, kNoSolo, testParameters()), "");
    const std::size_t strands = sim.groom().strandCount();
    std::vector<GrowthRegion> bad = regions;
    bad[0].weights.forWrite()[12] = NAN;
    EXPECT_EQ(sim.regroom(bad, kNoSolo, testParameters()), "region 'Fringe': weight 12 is not a finite number");
    bad = regions;
    bad[0].weights.forWrite().pop_back();
    EXPECT_NE(sim.regroom(bad, kNoSolo, testParameters()).find("region 'Fringe'"), std::string::npos);
    bad = regions;
    bad[0].tipColour.y = 2.0f;
    EXPECT_EQ(
        sim.regroom(bad, kNoSolo, testParameters()), "region 'Fringe': colour component 2.000000 is outside 0..1");
    EXPECT_EQ(sim.groom().strandCount(), strands) << "a refused regroom keeps the running groom";
    EXPECT_EQ(validateRegion(regions[0], defaultHead().mesh.positions.size()), "");
}

TEST(RegionGroom, ImportedStrandsBecomeWispsRootedOnTheHeadWithTheirShape)
{
    const TriangleMesh& head = defaultHead().mesh;
    const Aabb box = boundsOf(head);
    // Three strands of 5, 9 and 30 points starting a few millimetres off the crown, hanging down.
    auto imported = std::make_shared<HairCurves>();
    const int counts[3] = { 5, 9, 30 };
    for (int s = 0; s < 3; ++s) {
        const glm::vec3 start(box.center().x + 0.02f * static_cast<float>(s - 1), box.max.y + 0.004f, box.center().z);
        const auto points = imported->strandForWrite(imported->addStrand(static_cast<std::uint32_t>(counts[s])));
        for (int j = 0; j < counts[s]; ++j)
            points[j] = start + glm::vec3(0.03f * std::sin(0.3f * j), -0.2f * j / (counts[s] - 1), 0.0f);
    }
    std::vector<GrowthRegion> regions{ regionNamed(0, "Scalp", defaultHead().growthWeights),
        regionNamed(5, "Imported", std::vector<float>(head.positions.size(), 0.0f)) };
    regions[1].importedStrands = imported;
    HairSimulation sim(1);
    ASSERT_EQ(sim.setup(head, regions, 5, testParameters()), ""); // solo: only the imported strands
    const Groom& g = sim.groom();
    ASSERT_EQ(g.strandCount(), 3u);
    ASSERT_EQ(g.wispCount(), 3u);
    const std::size_t points = static_cast<std::size_t>(testParameters().getInt(Param::Segments)) + 1;
    for (std::size_t i = 0; i < 3; ++i) {
        const auto rest = g.rest.strand(i);
        ASSERT_EQ(rest.size(), points);
        // Rooted on the head: the root is the closest surface point, within a hair of the skin.
        EXPECT_LT(sim.bvh().closestPoint(rest.front()).distance, 1e-5f);
        // The shape is the file's, moved by the root's snap: every resampled point lies on the
        // shifted polyline, and the arc length is kept within 1%.
        const auto original = imported->strand(g.rootIds[i]);
        const glm::vec3 shift = rest.front() - original.front();
        float originalLength = 0.0f, restLength = 0.0f;
        for (std::size_t j = 1; j < original.size(); ++j)
            originalLength += glm::distance(original[j], original[j - 1]);
        for (std::size_t j = 1; j < rest.size(); ++j)
            restLength += glm::distance(rest[j], rest[j - 1]);
        EXPECT_NEAR(
            restLength, originalLength, 0.02f * originalLength); // chords of a resampled wave run a little short
        EXPECT_LT(glm::distance(rest.back(), original.back() + shift), 1e-5f);
    }
    for (int i = 0; i < 100; ++i)
        sim.step();
    HairCurves frame;
    sim.buildFrame(frame);
    for (const glm::vec3& p : frame.positions)
        ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
    EXPECT_EQ(sim.solver().strandCount(), 3u) << "imported strands are all simulated (each is a key)";
}

TEST(RegionGroom, ResamplingKeepsEndsAndSpacesPointsEvenly)
{
    const std::vector<glm::vec3> polyline{ { 0, 0, 0 }, { 0, -0.1f, 0 }, { 0.3f, -0.1f, 0 } };
    const std::vector<glm::vec3> r = resampleByArcLength(polyline, 5);
    ASSERT_EQ(r.size(), 5u);
    EXPECT_EQ(r.front(), polyline.front());
    EXPECT_EQ(r.back(), polyline.back());
    for (std::size_t j = 1; j < r.size(); ++j)
        EXPECT_NEAR(glm::distance(r[j], r[j - 1]), 0.1f, 0.02f); // corners cut a chord a little short
    EXPECT_TRUE(resampleByArcLength(std::vector<glm::vec3>{ { 1, 1, 1 } }, 5).empty());
    EXPECT_TRUE(resampleByArcLength(std::vector<glm::vec3>{ { 1, 1, 1 }, { 1, 1, 1 } }, 5).empty());
}

namespace {

// The scalp's tint under the hair: per vertex the root colour of the growing region that grows
// most there, with its weight; hidden regions, solo and weights of another count are respected.
TEST(ScalpCoverage, TakesTheStrongestGrowingRegionPerVertex)
{
    GrowthRegion a;
    a.id = 1;
    a.weights = { 1.0f, 0.2f, 0.0f, 0.5f };
    a.rootColour = { 0.1f, 0.2f, 0.3f };
    GrowthRegion b;
    b.id = 2;
    b.weights = { 0.0f, 0.8f, 0.0f, 0.4f };
    b.rootColour = { 0.9f, 0.8f, 0.7f };
    GrowthRegion imported;
    imported.id = 3; // weights of another count: no tint from it
    imported.weights = { 1.0f };
    const std::vector<GrowthRegion> regions{ a, b, imported };
    const std::vector<glm::vec4> all = scalpCoverage(regions, kNoSolo, 4);
    ASSERT_EQ(all.size(), 4u);
    EXPECT_EQ(all[0], glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    EXPECT_EQ(all[1], glm::vec4(0.9f, 0.8f, 0.7f, 0.8f));
    EXPECT_EQ(all[2], glm::vec4(0.0f));
    EXPECT_EQ(all[3], glm::vec4(0.1f, 0.2f, 0.3f, 0.5f));
    // Solo: the other regions' hair is not there.
    EXPECT_EQ(scalpCoverage(regions, 2, 4)[0], glm::vec4(0.0f));
    std::vector<GrowthRegion> hidden = regions;
    hidden[0].visible = false;
    EXPECT_EQ(scalpCoverage(hidden, kNoSolo, 4)[0], glm::vec4(0.0f));
    EXPECT_EQ(scalpCoverage(hidden, kNoSolo, 4)[3], glm::vec4(0.9f, 0.8f, 0.7f, 0.4f));
}

} // namespace
