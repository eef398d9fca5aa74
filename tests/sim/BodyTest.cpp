// The neck and shoulders under the head (sim/geometry/Body.h): long hair settles on them without entering
// them, and passes through where they are when the body is off.

#include "SimFixtures.h"

#include "sim/geometry/Body.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

using namespace wisp;
using namespace wisp::test;

namespace {

ParameterValues longHair(bool body)
{
    ParameterValues v = testParameters();
    v.set(Param::Density, 1.0);
    v.set(Param::Length, 0.5);
    v.set(Param::Segments, 30);
    v.set(Param::SimulateAllStrands, 1); // every strand a chain of particles
    v.set(Param::Body, body ? 1 : 0);
    return v;
}

struct Settled {
    std::size_t strands = 0;
    float deepest = 0.0f; // the deepest any particle is inside a capsule, metres (0: none)
    std::size_t inside = 0; // particles more than 1 mm inside a capsule
    std::size_t onShoulders = 0; // strands lying on a shoulder: a particle within 3 mm of its upper surface
    std::size_t tipsBelow = 0; // of those, tips below the shoulders' lower side
    float meanTipY = 0.0f; // metres
};

// Above the capsule's axis, within 60° of straight up from it: where hair lies on a shoulder.
bool onUpperSide(const Capsule& c, const glm::vec3& p)
{
    const glm::vec3 ab = c.b - c.a;
    const float u = std::clamp(glm::dot(p - c.a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    const glm::vec3 away = p - (c.a + u * ab);
    return away.y > 0.5f * glm::length(away);
}

Settled settle(bool bodyOn, const std::vector<Capsule>& body)
{
    auto sim = makeSimulation(longHair(bodyOn));
    run(*sim, 600); // 10 s
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    const HairCurves& layout = sim->groom().rest;
    Settled s;
    s.strands = layout.strandCount();
    const float shoulderBottom
        = std::min(body[kBodyLeftShoulder].b.y, body[kBodyLeftShoulder].a.y) - body[kBodyLeftShoulder].radiusMetres;
    for (std::size_t i = 0; i < layout.strandCount(); ++i) {
        bool touches = false;
        for (std::uint32_t j = layout.offsets[i]; j < layout.offsets[i + 1]; ++j) {
            for (std::size_t c = 0; c < body.size(); ++c) {
                const float d = capsuleDistance(body[c], p[j]);
                s.deepest = std::max(s.deepest, -d);
                s.inside += d < -0.001f;
                if ((c == kBodyLeftShoulder || c == kBodyRightShoulder) && d < 0.003f && onUpperSide(body[c], p[j]))
                    touches = true;
            }
        }
        const glm::vec3 tip = p[layout.offsets[i + 1] - 1];
        s.meanTipY += tip.y / static_cast<float>(layout.strandCount());
        if (touches) {
            ++s.onShoulders;
            s.tipsBelow += tip.y < shoulderBottom;
        }
    }
    std::printf(
        "body %s: %zu strands; deepest inside a capsule %.4f m, particles inside %zu; strands on the shoulders %zu, "
        "their tips below the shoulders %zu; mean tip height %.3f m (shoulders' lower side %.3f m)\n",
        bodyOn ? "on" : "off", layout.strandCount(), s.deepest, s.inside, s.onShoulders, s.tipsBelow, s.meanTipY,
        shoulderBottom);
    return s;
}

} // namespace

TEST(Body, DefaultBodySitsUnderTheBuiltInHead)
{
    const std::vector<Capsule> body = defaultBody(defaultHead().mesh);
    ASSERT_EQ(body.size(), 4u);
    const Aabb head = boundsOf(defaultHead().mesh);
    // The shoulders are below the chin and wider than the head; the neck is under it.
    for (std::size_t c : { kBodyLeftShoulder, kBodyRightShoulder })
        EXPECT_LT(std::max(body[c].a.y, body[c].b.y) + body[c].radiusMetres, head.min.y + 0.01f);
    EXPECT_LT(body[kBodyLeftShoulder].b.x - body[kBodyLeftShoulder].radiusMetres, head.min.x);
    EXPECT_GT(body[kBodyRightShoulder].b.x + body[kBodyRightShoulder].radiusMetres, head.max.x);
    const float across
        = body[kBodyRightShoulder].b.x - body[kBodyLeftShoulder].b.x + 2.0f * body[kBodyRightShoulder].radiusMetres;
    EXPECT_GT(across, 0.36f);
    EXPECT_LT(across, 0.46f);
}

TEST(Body, LongHairRestsOnTheShouldersWithoutEnteringThemAndPassesThroughWithoutThem)
{
    const std::vector<Capsule> body = defaultBody(defaultHead().mesh);
    const Settled on = settle(true, body);
    const Settled off = settle(false, body);
    EXPECT_EQ(on.inside, 0u) << "deepest " << on.deepest; // none more than 1 mm inside a capsule
    EXPECT_LT(on.deepest, 0.001f);
    // Without the body the same hair falls through where it would be.
    EXPECT_GT(off.inside, 1000u);
    EXPECT_GT(off.deepest, 0.05f);
    // With it, hair lies on the shoulders and hangs higher. (0.5 m hair does not stop there: about
    // half the strands lying on a shoulder drape over it, front or back, their tips below it.)
    // (With the bending that carries a strand's weight to its root the hair hangs straighter:
    // about a sixth of the strands lie on the shoulders, and those sliding off them front or back
    // end lower than hair falling through would, so the mean tip height says nothing here.)
    EXPECT_GT(on.onShoulders, on.strands / 8);
}
