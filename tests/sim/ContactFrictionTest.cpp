// Coulomb friction on the head's distance field (sim/solver/SolverContact.h): a strand lying on a
// slope gentler than its static friction stays where it lies, and slides without friction.
#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/Solver.h"

#include "MeshFixtures.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

using namespace wisp;

namespace {

constexpr float kSphereRadius = 0.1f;
constexpr float kOffset = 0.002f;
constexpr float kSegment = 0.01f;
constexpr int kStrands = 24;

// Two-particle strands rooted on a ring 35 degrees from the top of the sphere, each lying 1 cm
// along the ring (level, across the slope) at the hair offset, free to swing down the slope about
// its root; returns the mean distance (m) their free ends moved in `steps` steps of 1/60 s with
// Coulomb coefficient `friction` (static 1.25 times it).
double meanSlideMetres(const std::shared_ptr<const SignedDistanceField>& field, float friction, int steps)
{
    const float polar = glm::radians(35.0f), along = kSegment / ((kSphereRadius + kOffset) * std::sin(polar));
    HairCurves c;
    for (int i = 0; i < kStrands; ++i) {
        const float az = glm::two_pi<float>() * static_cast<float>(i) / kStrands;
        auto onSphere = [&](float azimuth) {
            return (kSphereRadius + kOffset)
                * glm::vec3(std::sin(polar) * std::cos(azimuth), std::cos(polar), std::sin(polar) * std::sin(azimuth));
        };
        auto p = c.strandForWrite(c.addStrand(2));
        p[0] = onSphere(az);
        p[1] = onSphere(az + along); // along the ring: level, across the slope
    }
    Solver solver(1);
    EXPECT_EQ(solver.setStrands(c), "");
    solver.setCollider(field);
    SolverSettings s;
    s.timeStepSeconds = 1.0f / 60.0f;
    s.substeps = 1;
    s.gravity = { 0.0f, -9.81f, 0.0f };
    s.stiffness = 0.0f; // a free hinge: only contact and friction hold the free end
    s.dampingPerSecond = 0.0f;
    s.friction = friction;
    s.hairOffsetMetres = kOffset;
    EXPECT_EQ(solver.setSettings(s), "");
    std::vector<glm::vec3> start, end;
    solver.copyPositions(start);
    for (int step = 0; step < steps; ++step)
        solver.step();
    solver.copyPositions(end);
    double slide = 0.0;
    for (int i = 0; i < kStrands; ++i)
        slide += glm::distance(start[2 * i + 1], end[2 * i + 1]);
    return slide / kStrands;
}

} // namespace

// The slope is tan(35 degrees) = 0.70 where the free ends lie. Friction 0.8 (static 1.0, above the
// slope) holds them; friction 0.5 (static 0.625, below it) lets them slide, but slower than without
// friction (the kinetic part: g (sin 35° - 0.5 cos 35°) = 0.16 g down the slope instead of 0.57 g).
// Regression: the contact's turn kept the predicted slide and friction only edited the velocity
// (the previous position), so hair on this slope with friction 0.8 moved 14.6 mm in 120 steps, as
// far as without friction.
TEST(ContactFriction, StaticFrictionHoldsHairOnASlopeItsCoefficientCanHold)
{
    std::string error;
    auto field = std::make_shared<SignedDistanceField>(
        SignedDistanceField::bake(test::makeIcosphere(kSphereRadius, 4), 0.0025f, 0.03f, &error));
    ASSERT_EQ(error, "");
    const double held = meanSlideMetres(field, 0.8f, 120);
    const double free = meanSlideMetres(field, 0.0f, 120);
    const double kineticLong = meanSlideMetres(field, 0.5f, 120);
    std::printf("in 120 steps free ends moved %.2f mm with friction 0.8, %.2f mm with 0.5, %.2f mm without\n",
        held * 1000.0, kineticLong * 1000.0, free * 1000.0);
    EXPECT_GT(free, 0.005); // without friction they swing down the slope
    EXPECT_LT(held, 0.001); // static friction above the slope holds them within a millimetre
    EXPECT_GT(kineticLong, 0.005); // static friction below the slope cannot hold them
    // Early in the slide (before the 1 cm hinge reaches the bottom of its swing) kinetic friction
    // slows it.
    const double kineticEarly = meanSlideMetres(field, 0.5f, 3);
    const double freeEarly = meanSlideMetres(field, 0.0f, 3);
    std::printf("in 3 steps %.2f mm with friction 0.5, %.2f mm without\n", kineticEarly * 1000.0, freeEarly * 1000.0);
    EXPECT_GT(kineticEarly, 0.001);
    EXPECT_LT(kineticEarly, 0.6 * freeEarly);
}
