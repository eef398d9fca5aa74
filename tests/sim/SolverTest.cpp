// The solver on its own, without a head: curls, spheres and capsules, and input checks.
#include "sim/solver/Solver.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace wisp;

namespace {

// A helix hanging from the origin along -Y: radius r, `turns` per metre of axis, equal segments.
HairCurves helix(float radius, float turnsPerMetre, float axialLength, int segments)
{
    HairCurves c;
    const std::size_t s = c.addStrand(static_cast<std::uint32_t>(segments + 1));
    auto p = c.strandForWrite(s);
    for (int j = 0; j <= segments; ++j) {
        const float z = axialLength * static_cast<float>(j) / static_cast<float>(segments);
        const float theta = glm::two_pi<float>() * turnsPerMetre * z;
        p[j] = { radius * std::cos(theta) - radius, -z, radius * std::sin(theta) };
    }
    return c;
}

// The curl's period in points: where the tangent's autocorrelation comes back to its first maximum.
double curlPeriodInPoints(std::span<const glm::vec3> p)
{
    std::vector<glm::vec3> t;
    for (std::size_t j = 1; j < p.size(); ++j)
        t.push_back(glm::normalize(p[j] - p[j - 1]));
    auto correlation = [&](std::size_t lag) {
        double sum = 0;
        for (std::size_t j = 0; j + lag < t.size(); ++j)
            sum += glm::dot(t[j], t[j + lag]);
        return sum / static_cast<double>(t.size() - lag);
    };
    std::size_t lag = 1;
    while (lag + 1 < t.size() / 2 && correlation(lag + 1) < correlation(lag))
        ++lag; // down to the first minimum (half a turn)
    while (lag + 1 < t.size() / 2 && correlation(lag + 1) > correlation(lag))
        ++lag; // up to the next maximum (a full turn)
    // Refine between samples with a parabola through the peak.
    const double a = correlation(lag - 1), b = correlation(lag), c = correlation(lag + 1);
    const double denom = a - 2 * b + c;
    return static_cast<double>(lag) + (std::abs(denom) > 1e-12 ? 0.5 * (a - c) / denom : 0.0);
}

SolverSettings calm()
{
    SolverSettings s;
    s.timeStepSeconds = 1.0f / 60.0f;
    s.substeps = 4;
    s.gravity = { 0.0f, -9.81f, 0.0f };
    s.dampingPerSecond = 1.0f;
    s.stiffness = 0.5f;
    return s;
}

// The strands on a sphere collider of radius 0.1 m at the origin (the bench's), with settings `s`.
void putOnSphere(Solver& solver, const HairCurves& strands, const SolverSettings& s)
{
    ASSERT_EQ(solver.setStrands(strands), "");
    solver.setCapsules({ Capsule{ { 0, 0, 0 }, { 0, 0, 0 }, 0.1f } });
    ASSERT_EQ(solver.setSettings(s), "");
}

} // namespace

TEST(Solver, CurlsKeepTheirPeriodAfterSettling)
{
    // 6 turns of 1 cm radius, 12 segments a turn (about 5 mm each).
    const HairCurves rest = helix(0.01f, 20.0f, 0.3f, 72);
    const double restPeriod = curlPeriodInPoints(rest.strand(0));
    ASSERT_NEAR(restPeriod, 12.0, 0.5);

    Solver solver(1);
    ASSERT_EQ(solver.setStrands(rest), "");
    SolverSettings s = calm();
    s.wind = { 3.0f, 0.0f, 0.0f };
    s.dragPerSecond = 1.0f;
    ASSERT_EQ(solver.setSettings(s), "");
    for (int i = 0; i < 600; ++i)
        solver.step();
    std::vector<glm::vec3> p;
    solver.copyPositions(p);
    EXPECT_NEAR(curlPeriodInPoints(p), restPeriod, 0.05 * restPeriod);
    // It did move: gravity and wind displaced the tip, the curl held.
    EXPECT_GT(glm::distance(p.back(), rest.positions.back()), 0.005f);
    // And it is still a curl: the helix hangs no longer than its rest extent (0.63 of its arc
    // length here) plus a little; pulled straight it would be 1.
    EXPECT_LT(glm::distance(p.front(), p.back()), 0.7f * strandLength(p));
}

TEST(Solver, GravityPullsAStraightStrandDownToItsFullLength)
{
    HairCurves c;
    auto p = c.strandForWrite(c.addStrand(11));
    for (int j = 0; j <= 10; ++j)
        p[j] = { 0.02f * static_cast<float>(j), 0.0f, 0.0f }; // sticking out sideways, 0.2 m
    Solver solver(1);
    ASSERT_EQ(solver.setStrands(c), "");
    SolverSettings s = calm();
    s.stiffness = 0.0f;
    s.dampingPerSecond = 3.0f;
    ASSERT_EQ(solver.setSettings(s), "");
    for (int i = 0; i < 600; ++i)
        solver.step();
    std::vector<glm::vec3> out;
    solver.copyPositions(out);
    EXPECT_NEAR(out.back().y, -0.2f, 0.004f);
    EXPECT_NEAR(out.back().x, 0.0f, 0.01f);
}

TEST(Solver, StrandsDrapeOverASphereColliderWithoutEnteringIt)
{
    // Strands rooted around the top of a sphere (radius 0.1 m), hanging under gravity, with friction
    // and without (where contact keeps only its normal response).
    HairCurves c;
    for (int i = 0; i < 24; ++i) {
        const float az = glm::two_pi<float>() * static_cast<float>(i) / 24.0f;
        const glm::vec3 n(0.5f * std::cos(az), 0.866f, 0.5f * std::sin(az));
        auto p = c.strandForWrite(c.addStrand(15));
        for (int j = 0; j < 15; ++j)
            p[j] = n * (0.1f + 0.3f * static_cast<float>(j) / 14.0f);
    }
    for (const float friction : { 0.3f, 0.0f }) {
        SCOPED_TRACE(friction);
        Solver solver(2);
        SolverSettings s = calm();
        s.stiffness = 0.0f;
        s.friction = friction;
        s.hairOffsetMetres = 0.002f;
        putOnSphere(solver, c, s);
        std::vector<glm::vec3> before, out;
        for (int i = 0; i < 400; ++i) {
            if (i == 399)
                solver.copyPositions(before);
            solver.step();
        }
        solver.copyPositions(out);
        float lowest = 1.0f;
        double fastest = 0.0; // m/s over the last step
        for (std::size_t k = 0; k < out.size(); ++k) {
            EXPECT_GT(glm::length(out[k]), 0.1f - 1e-4f);
            lowest = std::min(lowest, out[k].y);
            fastest = std::max(fastest, static_cast<double>(glm::distance(out[k], before[k])) * 60.0);
        }
        EXPECT_LT(lowest, -0.05f); // they fell around the sphere, not through it
        EXPECT_LT(fastest, 0.05); // and came to rest on it (m/s), neither bouncing nor sinking
    }
}

// Contact is inelastic along the normal, with friction and without: the step a particle lands on a
// sphere leaves it no velocity into it (its previous position follows it along the normal), so it
// neither keeps pressing in nor bounces. A one-segment strand swings down about its root onto the
// sphere's shoulder at about 0.7 m/s.
TEST(Solver, ALandingParticleKeepsNoVelocityIntoTheCollider)
{
    HairCurves c;
    auto p = c.strandForWrite(c.addStrand(2));
    p[0] = { -0.05f, 0.115f, 0.0f };
    p[1] = { 0.0f, 0.13f, 0.0f };
    for (const float friction : { 0.0f, 0.3f }) {
        SCOPED_TRACE(friction);
        Solver solver(1);
        SolverSettings s = calm();
        s.substeps = 1;
        s.stiffness = 0.0f;
        s.dampingPerSecond = 0.0f;
        s.friction = friction;
        putOnSphere(solver, c, s);
        int landed = -1;
        for (int i = 0; i < 60 && landed < 0; ++i) {
            solver.step();
            std::vector<glm::vec3> x, previous;
            solver.copyState(x, previous);
            const glm::vec3 normal = glm::normalize(x[1]);
            if (glm::length(x[1]) < 0.1f + 1e-5f) {
                landed = i;
                EXPECT_GT(glm::dot(x[1] - previous[1], normal), -1e-6f);
                EXPECT_GT(glm::length(x[1]), 0.1f - 1e-5f);
            }
        }
        EXPECT_GT(landed, 1); // it fell for a few steps first
    }
}

// A block whose strands are all limp (stiffness 0) skips the bend and its frames (they would move
// nothing); a block with one stiff strand bends. Limp strands land on the same bits either way, and
// the stiff strand in a block of limp ones still holds its shape.
TEST(Solver, LimpStrandsMoveAlikeWithAndWithoutAStiffStrandInTheirBlock)
{
    // 16 strands of 11 points (one block): 0.2 m sticking out sideways at different headings,
    // with wind and collision so that every term of a step is at work.
    HairCurves c;
    for (int i = 0; i < 16; ++i) {
        const float az = glm::two_pi<float>() * static_cast<float>(i) / 16.0f;
        const glm::vec3 out(std::cos(az), 0.3f, std::sin(az));
        auto p = c.strandForWrite(c.addStrand(11));
        for (int j = 0; j <= 10; ++j)
            p[j] = out * (0.1f + 0.02f * static_cast<float>(j));
    }
    auto run = [&](float firstStrandStiffness) {
        Solver solver(1);
        SolverSettings s = calm();
        s.stiffness = 0.6f;
        s.wind = { 2.0f, 0.0f, 0.5f };
        s.dragPerSecond = 0.5f;
        s.friction = 0.3f;
        putOnSphere(solver, c, s);
        std::vector<float> scales(16, 0.0f);
        scales[0] = firstStrandStiffness;
        EXPECT_EQ(solver.setStiffnessScales(scales), "");
        for (int i = 0; i < 120; ++i)
            solver.step();
        std::vector<glm::vec3> out;
        solver.copyPositions(out);
        return out;
    };
    const std::vector<glm::vec3> mixed = run(1.0f), limp = run(0.0f);
    ASSERT_EQ(mixed.size(), limp.size());
    for (std::size_t k = 11; k < mixed.size(); ++k) { // strands 1..15
        EXPECT_EQ(mixed[k].x, limp[k].x) << k;
        EXPECT_EQ(mixed[k].y, limp[k].y) << k;
        EXPECT_EQ(mixed[k].z, limp[k].z) << k;
    }
    // Strand 0's tip: limp it hangs about its length below the root, stiff it stands out.
    const glm::vec3 root = c.strand(0).front();
    EXPECT_LT(limp[10].y - root.y, -0.15f);
    EXPECT_GT(mixed[10].y - root.y, -0.1f);
}

// A particle gone non-finite puts its strand back at rest at the end of the step, wherever it is on
// the strand (the kernel looks at each row as the step's last substep finishes it) and at any
// substep count; the strands beside it in its block do not change by a bit.
// Whether the solver bends any strand (what `wisp-cli bench` reports it stepped with): the scene's
// stiffness and the strands' scales, as the step's bend shares say once a step has set them.
TEST(Solver, SaysWhetherAnyStrandBends)
{
    HairCurves c;
    for (int i = 0; i < 20; ++i) { // two blocks, the second with padding lanes
        auto p = c.strandForWrite(c.addStrand(6));
        for (int j = 0; j < 6; ++j)
            p[j] = { 0.01f * static_cast<float>(i), -0.02f * static_cast<float>(j), 0.0f };
    }
    Solver solver(1);
    ASSERT_EQ(solver.setStrands(c), "");
    SolverSettings s = calm();
    s.stiffness = 0.4f;
    ASSERT_EQ(solver.setSettings(s), "");
    EXPECT_TRUE(solver.anyStrandBends()); // (asked for, before a step)
    solver.step();
    EXPECT_TRUE(solver.anyStrandBends());

    std::vector<float> scales(20, 0.0f);
    ASSERT_EQ(solver.setStiffnessScales(scales), "");
    EXPECT_FALSE(solver.anyStrandBends());
    solver.step();
    EXPECT_FALSE(solver.anyStrandBends());
    scales[19] = 0.5f; // one strand, in the block with padding
    ASSERT_EQ(solver.setStiffnessScales(scales), "");
    EXPECT_TRUE(solver.anyStrandBends());
    solver.step();
    EXPECT_TRUE(solver.anyStrandBends());

    s.stiffness = 0.0f;
    ASSERT_EQ(solver.setSettings(s), "");
    EXPECT_FALSE(solver.anyStrandBends());
    solver.step();
    EXPECT_FALSE(solver.anyStrandBends());
}

TEST(Solver, ANonFiniteParticleAnywhereOnAStrandPutsThatStrandAloneBackAtRest)
{
    HairCurves c; // 20 strands of 11 points: a full block and part of another
    for (int i = 0; i < 20; ++i) {
        const float az = glm::two_pi<float>() * static_cast<float>(i) / 20.0f;
        const glm::vec3 out(std::cos(az), 0.2f, std::sin(az));
        auto p = c.strandForWrite(c.addStrand(11));
        for (int j = 0; j <= 10; ++j)
            p[j] = out * (0.1f + 0.02f * static_cast<float>(j));
    }
    for (const int substeps : { 1, 3 }) {
        for (const std::size_t point : { std::size_t{ 1 }, std::size_t{ 6 }, std::size_t{ 10 } }) {
            SCOPED_TRACE("substeps " + std::to_string(substeps) + ", point " + std::to_string(point));
            SolverSettings s = calm();
            s.substeps = substeps;
            s.wind = { 2.0f, 0.0f, 0.5f };
            s.dragPerSecond = 0.5f;
            Solver broken(1), reference(1);
            putOnSphere(broken, c, s);
            putOnSphere(reference, c, s);
            for (int i = 0; i < 10; ++i) {
                broken.step();
                reference.step();
            }
            constexpr std::size_t kBrokenStrand = 3;
            broken.moveParticle(kBrokenStrand, point, glm::vec3(NAN));
            broken.step();
            reference.step();
            EXPECT_EQ(broken.strandsReset(), 1u);
            EXPECT_EQ(reference.strandsReset(), 0u);
            std::vector<glm::vec3> a, b;
            broken.copyPositions(a);
            reference.copyPositions(b);
            ASSERT_EQ(a.size(), b.size());
            for (std::size_t k = 0; k < a.size(); ++k) {
                ASSERT_TRUE(std::isfinite(a[k].x + a[k].y + a[k].z)) << k;
                if (k / 11 == kBrokenStrand) // back at rest: where the rest strand is
                    EXPECT_LT(glm::distance(a[k], c.positions[k]), 1e-5f) << k;
                else
                    EXPECT_TRUE(a[k] == b[k]) << k;
            }
        }
    }
}

// The particles' clearance bounds cover the capsules (a capsule is checked only where a bound ran
// out): hair that rested 20 cm from a capsule within its reach, whose bounds had grown to that,
// must still meet a capsule put into it, on the very next step, and leave it when it goes.
TEST(Solver, ACapsulePutIntoRestingHairPushesItOutOnTheNextStep)
{
    HairCurves c;
    for (int i = 0; i < 20; ++i) {
        auto p = c.strandForWrite(c.addStrand(15));
        for (int j = 0; j < 15; ++j)
            p[j] = { 0.01f * static_cast<float>(i), -0.3f * static_cast<float>(j) / 14.0f, 0.0f };
    }
    Solver solver(2);
    ASSERT_EQ(solver.setStrands(c), "");
    SolverSettings s = calm();
    s.hairOffsetMetres = 0.001f;
    ASSERT_EQ(solver.setSettings(s), "");
    const Capsule far{ { 0.1f, -0.15f, 0.25f }, { 0.1f, -0.15f, 0.25f }, 0.05f };
    solver.setCapsules({ far });
    for (int i = 0; i < 60; ++i)
        solver.step();
    std::vector<glm::vec3> before;
    solver.copyPositions(before);
    // A ball across the middle of the hanging hair, its centre 2 cm behind it.
    const glm::vec3 centre(0.1f, -0.2f, 0.02f);
    const float radius = 0.05f;
    int insideBefore = 0;
    for (const glm::vec3& x : before)
        insideBefore += glm::distance(x, centre) < radius ? 1 : 0;
    ASSERT_GT(insideBefore, 20); // the test means something: the ball is put into the hair
    solver.setCapsules({ far, Capsule{ centre, centre, radius } });
    solver.step();
    std::vector<glm::vec3> after;
    solver.copyPositions(after);
    for (std::size_t k = 0; k < after.size(); ++k)
        ASSERT_GE(glm::distance(after[k], centre), radius + s.hairOffsetMetres - 1e-4f) << "particle " << k;
    // Taken away again: the hair falls back to hanging straight down within a few seconds.
    solver.setCapsules({ far });
    for (int i = 0; i < 300; ++i)
        solver.step();
    std::vector<glm::vec3> back;
    solver.copyPositions(back);
    for (std::size_t k = 0; k < back.size(); ++k)
        EXPECT_NEAR(back[k].z, 0.0f, 0.005f) << "particle " << k;
}

TEST(Solver, RefusesBrokenStrandsAndSettings)
{
    Solver solver(1);
    HairCurves one;
    one.strandForWrite(one.addStrand(1))[0] = { 0, 0, 0 };
    EXPECT_NE(solver.setStrands(one).find("at least 2"), std::string::npos);

    HairCurves nan;
    auto p = nan.strandForWrite(nan.addStrand(3));
    p[0] = { 0, 0, 0 };
    p[1] = { 0, -0.1f, 0 };
    p[2] = { NAN, 0, 0 };
    EXPECT_NE(solver.setStrands(nan).find("not finite"), std::string::npos);

    HairCurves zero;
    auto q = zero.strandForWrite(zero.addStrand(3));
    q[0] = q[1] = { 0, 0, 0 };
    q[2] = { 0, -0.1f, 0 };
    EXPECT_NE(solver.setStrands(zero).find("coincide"), std::string::npos);

    SolverSettings s = calm();
    s.gravity.y = NAN;
    EXPECT_NE(solver.setSettings(s).find("gravity"), std::string::npos);
    s = calm();
    s.substeps = 0;
    EXPECT_NE(solver.setSettings(s).find("substeps"), std::string::npos);
    s = calm();
    s.timeStepSeconds = -1.0f;
    EXPECT_NE(solver.setSettings(s).find("time_step"), std::string::npos);
}
