#include "SimFixtures.h"

#include "sim/groom/Groom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace wisp;
using wisp::test::defaultHead;

namespace {

GroomSettings settingsWith(std::initializer_list<std::pair<Param, double>> changes)
{
    ParameterValues v;
    for (const auto& [id, value] : changes)
        EXPECT_TRUE(v.set(id, value).empty()) << parameterInfo(id).key;
    return groomSettingsFrom(v);
}

GroomResult groomDefaultHead(const GroomSettings& s)
{
    return buildGroom(defaultHead().mesh, defaultHead().growthWeights, s);
}

} // namespace

TEST(Groom, DensityMatchesTheRequestedStrandsPerSquareCentimetre)
{
    const TriangleMesh& mesh = defaultHead().mesh;
    const std::vector<float>& w = defaultHead().growthWeights;
    double weightedAreaCm2 = 0.0; // area times the mean weight of each triangle
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        weightedAreaCm2 += triangleArea(mesh, t) * 1e4 * (w[tri.x] + w[tri.y] + w[tri.z]) / 3.0;
    }
    for (double density : { 2.0, 8.0 }) {
        const GroomResult r = groomDefaultHead(settingsWith({ { Param::Density, density } }));
        ASSERT_TRUE(r.ok()) << r.error;
        const double measured = static_cast<double>(r.groom.strandCount()) / weightedAreaCm2;
        EXPECT_NEAR(measured, density, 0.15 * density) << "strands " << r.groom.strandCount();
    }
}

TEST(Groom, RootsAreBlueNoiseNotClustered)
{
    const GroomResult r = groomDefaultHead(settingsWith({ { Param::Density, 8.0 } }));
    ASSERT_TRUE(r.ok()) << r.error;
    // Poisson-disk spacing: no two roots closer than the thinning radius sqrt(0.52 / density).
    const float radius = std::sqrt(0.52f / 8.0e4f);
    std::vector<glm::vec3> p;
    for (const SurfacePoint& sp : r.groom.roots)
        p.push_back(pointOn(defaultHead().mesh, sp));
    float closest = INFINITY;
    for (std::size_t i = 0; i < p.size(); ++i)
        for (std::size_t j = i + 1; j < p.size(); ++j)
            closest = std::min(closest, glm::distance(p[i], p[j]));
    EXPECT_GE(closest, radius * 0.999f);
}

TEST(Groom, SameSeedSameGroomOtherSeedOtherGroom)
{
    const GroomResult a = groomDefaultHead(settingsWith({}));
    const GroomResult b = groomDefaultHead(settingsWith({}));
    const GroomResult c = groomDefaultHead(settingsWith({ { Param::Seed, 99 } }));
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    EXPECT_EQ(a.groom.rest.positions, b.groom.rest.positions);
    EXPECT_EQ(a.groom.wispOf, b.groom.wispOf);
    EXPECT_NE(a.groom.rest.positions, c.groom.rest.positions);
}

TEST(Groom, RootsLieOnTheScalpWhereTheGrowthMapAllows)
{
    const GroomResult r = groomDefaultHead(settingsWith({}));
    ASSERT_TRUE(r.ok()) << r.error;
    for (std::size_t i = 0; i < r.groom.strandCount(); ++i) {
        EXPECT_GT(interpolate(defaultHead().mesh, defaultHead().growthWeights, r.groom.roots[i]), 0.0f);
        EXPECT_LT(glm::distance(r.groom.rest.strand(i)[0], pointOn(defaultHead().mesh, r.groom.roots[i])), 1e-6f);
    }
}

TEST(Groom, ZeroWeightRemovesRootsThereAndOnlyThere)
{
    const TriangleMesh& mesh = defaultHead().mesh;
    std::vector<float> weights = defaultHead().growthWeights;
    const GroomSettings s = settingsWith({});
    const GroomResult before = buildGroom(mesh, weights, s);
    ASSERT_TRUE(before.ok()) << before.error;

    // Erase the right side of the scalp (x > 2 cm).
    std::vector<bool> erased(mesh.vertexCount(), false);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.positions[v].x > 0.02f && weights[v] > 0.0f) {
            weights[v] = 0.0f;
            erased[v] = true;
        }
    const GroomResult after = buildGroom(mesh, weights, s);
    ASSERT_TRUE(after.ok()) << after.error;

    auto touched = [&](const SurfacePoint& sp, bool all) {
        const glm::uvec3 t = mesh.triangles[sp.triangle];
        return all ? (erased[t.x] && erased[t.y] && erased[t.z]) : (erased[t.x] || erased[t.y] || erased[t.z]);
    };
    std::map<std::uint32_t, SurfacePoint> beforeOutside, afterOutside;
    std::size_t removed = 0;
    for (std::size_t i = 0; i < before.groom.strandCount(); ++i) {
        if (!touched(before.groom.roots[i], false))
            beforeOutside[before.groom.rootIds[i]] = before.groom.roots[i];
        else if (touched(before.groom.roots[i], true))
            ++removed;
    }
    for (std::size_t i = 0; i < after.groom.strandCount(); ++i) {
        EXPECT_FALSE(touched(after.groom.roots[i], true)) << "a root survived in the erased area";
        if (!touched(after.groom.roots[i], false))
            afterOutside[after.groom.rootIds[i]] = after.groom.roots[i];
    }
    EXPECT_GT(removed, 50u);
    ASSERT_EQ(beforeOutside.size(), afterOutside.size());
    for (const auto& [id, sp] : beforeOutside) {
        ASSERT_TRUE(afterOutside.count(id)) << "root " << id << " outside the erased area disappeared";
        EXPECT_EQ(afterOutside[id].triangle, sp.triangle);
        EXPECT_EQ(afterOutside[id].barycentric, sp.barycentric);
    }
}

TEST(Groom, WispsHoldAboutWispSizeStrandsAroundOneKeyHair)
{
    for (int wispSize : { 4, 16 }) {
        const GroomResult r = groomDefaultHead(settingsWith({ { Param::WispSize, wispSize } }));
        ASSERT_TRUE(r.ok()) << r.error;
        const double mean = static_cast<double>(r.groom.strandCount()) / static_cast<double>(r.groom.wispCount());
        EXPECT_NEAR(mean, wispSize, 0.4 * wispSize);
        for (std::size_t w = 0; w < r.groom.wispCount(); ++w)
            EXPECT_EQ(r.groom.wispOf[r.groom.keyStrand[w]], w);
    }
}

namespace {
// Mean distance between members' points at fraction u of their length and their key's point there.
struct Spread {
    double atRoot = 0, atTip = 0, beforeClump = 0;
};
Spread memberSpread(const Groom& g, float clumpRate)
{
    Spread s;
    std::size_t n = 0;
    const std::size_t last = static_cast<std::size_t>(g.settings.segments);
    const auto early = static_cast<std::size_t>(std::floor(clumpRate * static_cast<float>(last)));
    for (std::size_t i = 0; i < g.strandCount(); ++i) {
        if (g.isKey(i))
            continue;
        const auto m = g.rest.strand(i);
        const auto k = g.rest.strand(g.keyStrand[g.wispOf[i]]);
        s.atRoot += glm::distance(m[0], k[0]);
        s.atTip += glm::distance(m[last], k[last]);
        s.beforeClump += glm::distance(m[early], k[early]);
        ++n;
    }
    s.atRoot /= n;
    s.atTip /= n;
    s.beforeClump /= n;
    return s;
}
} // namespace

TEST(Groom, ClumpDegreeOnePullsMembersOntoTheKeyAndMinusOneSpreadsThem)
{
    const double rate = 0.4;
    const GroomResult one = groomDefaultHead(
        settingsWith({ { Param::ClumpDegree, 1.0 }, { Param::ClumpRate, rate }, { Param::LengthVariation, 0.0 } }));
    const GroomResult zero = groomDefaultHead(
        settingsWith({ { Param::ClumpDegree, 0.0 }, { Param::ClumpRate, rate }, { Param::LengthVariation, 0.0 } }));
    const GroomResult minus = groomDefaultHead(
        settingsWith({ { Param::ClumpDegree, -1.0 }, { Param::ClumpRate, rate }, { Param::LengthVariation, 0.0 } }));
    ASSERT_TRUE(one.ok() && zero.ok() && minus.ok());
    const Spread s1 = memberSpread(one.groom, rate), s0 = memberSpread(zero.groom, rate),
                 sm = memberSpread(minus.groom, rate);
    EXPECT_LT(s1.atTip, 1e-5); // on the key hair
    EXPECT_NEAR(s0.atTip, s0.atRoot, 0.05 * s0.atRoot); // parallel: the root spacing is kept
    EXPECT_NEAR(sm.atTip, 2.0 * sm.atRoot, 0.1 * sm.atRoot); // spread to twice the wisp radius
    // Clump-rate: before that fraction of the length, members have not started to clump.
    EXPECT_NEAR(s1.beforeClump, s1.atRoot, 0.05 * s1.atRoot);
}

TEST(Groom, LengthAndVariationSetStrandLengths)
{
    const GroomResult r = groomDefaultHead(settingsWith({ { Param::Length, 0.3 }, { Param::LengthVariation, 0.2 } }));
    ASSERT_TRUE(r.ok()) << r.error;
    float shortest = INFINITY, longest = 0;
    for (std::size_t w = 0; w < r.groom.wispCount(); ++w) {
        const std::size_t k = r.groom.keyStrand[w];
        const float len = strandLength(r.groom.rest.strand(k));
        EXPECT_NEAR(len, r.groom.lengths[k], 0.01f * r.groom.lengths[k]);
        shortest = std::min(shortest, len);
        longest = std::max(longest, len);
    }
    EXPECT_GE(shortest, 0.3f * 0.8f * 0.99f);
    EXPECT_LE(longest, 0.3f * 1.2f * 1.01f);
    EXPECT_GT(longest - shortest, 0.3f * 0.2f); // the variation is used
}

TEST(Groom, BadInputGivesAClearErrorNotACrash)
{
    const TriangleMesh& mesh = defaultHead().mesh;
    const std::vector<float>& weights = defaultHead().growthWeights;
    const GroomSettings ok = settingsWith({});

    const std::vector<float> bare(mesh.vertexCount(), 0.0f);
    EXPECT_NE(buildGroom(mesh, bare, ok).error.find("growth map"), std::string::npos);
    EXPECT_NE(buildGroom(mesh, std::vector<float>{}, ok).error.find("growth map"), std::string::npos);
    std::vector<float> nanWeights = weights;
    nanWeights[3] = NAN;
    EXPECT_NE(buildGroom(mesh, nanWeights, ok).error.find("not a finite"), std::string::npos);

    GroomSettings s = ok;
    s.lengthMetres = 0.0f;
    EXPECT_NE(buildGroom(mesh, weights, s).error.find("length"), std::string::npos);
    for (int segments : { 0, 1 }) {
        s = ok;
        s.segments = segments;
        EXPECT_NE(buildGroom(mesh, weights, s).error.find("segments"), std::string::npos);
    }
    s = ok;
    s.densityPerCm2 = NAN;
    EXPECT_NE(buildGroom(mesh, weights, s).error.find("density"), std::string::npos);
    s = ok;
    s.densityPerCm2 = 1e9f;
    EXPECT_FALSE(buildGroom(mesh, weights, s).ok());

    TriangleMesh empty;
    empty.positions = mesh.positions;
    EXPECT_EQ(buildGroom(empty, weights, ok).error, "head: the mesh has no triangles");
    TriangleMesh broken = mesh;
    broken.positions[0].x = NAN;
    EXPECT_NE(buildGroom(broken, weights, ok).error.find("non-finite"), std::string::npos);
}

// Issue 12: pore candidates scaled with the whole mesh's area with no cap (a stray vertex far
// away: 12-34 s and 266 MB for two steps). Past the cap the layout is made evenly sparser, and
// the result says so. Work is counted, not timed: the cap is lowered so the test stays cheap.
TEST(Groom, PoreCandidatesAreCappedWithAWarning)
{
    // A closed 2 x 2 x 1 m box: 16 m², at 8 strands/cm² and 4 candidates a strand, 5.1 million.
    TriangleMesh box;
    for (int i = 0; i < 8; ++i)
        box.positions.push_back(glm::vec3(2.0f * (i & 1), 2.0f * ((i >> 1) & 1), 1.0f * ((i >> 2) & 1)));
    box.triangles = { { 0, 2, 1 }, { 1, 2, 3 }, { 4, 5, 6 }, { 5, 7, 6 }, { 0, 1, 4 }, { 1, 5, 4 }, { 2, 6, 3 },
        { 3, 6, 7 }, { 0, 4, 2 }, { 2, 4, 6 }, { 1, 3, 5 }, { 3, 7, 5 } };
    const GroomSettings settings = settingsWith({ { Param::Density, 8.0 } });
    const std::vector<float> weights(box.positions.size(), 1.0f);
    const GroomRegionInput region{ 0, weights, settings, 1.0f };
    GroomBuilder builder;
    EXPECT_EQ(builder.maxPoreCandidates(), kMaxPoreCandidates);
    builder.setMaxPoreCandidates(20'000);
    const GroomResult capped = builder.build(box, std::span(&region, 1), settings, nullptr);
    ASSERT_TRUE(capped.ok()) << capped.error;
    EXPECT_LE(builder.poreCandidates(), 20'000u);
    EXPECT_GT(builder.poreCandidates(), 19'000u);
    ASSERT_EQ(capped.warnings.size(), 1u);
    EXPECT_NE(capped.warnings[0].find("on the head's 160000 cm² needs 5120000 pore candidates; capped at 20000"),
        std::string::npos)
        << capped.warnings[0];
    // Sparser, evenly: about 20,000 / 4 pores' worth of strands over the whole box, not a corner.
    EXPECT_GT(capped.groom.strandCount(), 3000u);
    EXPECT_LT(capped.groom.strandCount(), 6000u);

    // The real cap leaves the built-in head room at the highest density (200 strands/cm²).
    double headAreaM2 = 0.0;
    for (std::uint32_t t = 0; t < defaultHead().mesh.triangleCount(); ++t)
        headAreaM2 += triangleArea(defaultHead().mesh, t);
    EXPECT_LT(headAreaM2 * 200.0 * 1e4 * 4.0, static_cast<double>(kMaxPoreCandidates));
    GroomBuilder normal;
    const GroomRegionInput head{ 0, defaultHead().growthWeights, settings, 1.0f };
    const GroomResult r = normal.build(defaultHead().mesh, std::span(&head, 1), settings, nullptr);
    ASSERT_TRUE(r.ok()) << r.error;
    EXPECT_TRUE(r.warnings.empty());
    EXPECT_NEAR(
        static_cast<double>(normal.poreCandidates()), headAreaM2 * 8.0 * 1e4 * 4.0, 0.02 * headAreaM2 * 8e4 * 4.0);
}
