// Coulomb friction on the head's distance field (sim/solver/SolverContact.h): a strand lying on a
// slope gentler than its static friction stays where it lies, on a still head and on one that
// moves (friction takes the slide relative to the head), and slides without friction.
#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/Solver.h"

#include "MeshFixtures.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

using namespace wisp;

namespace {

constexpr float kSphereRadius = 0.1f;
constexpr float kOffset = 0.002f;
constexpr float kSegment = 0.01f;
constexpr int kStrands = 24;

constexpr float kStepSeconds = 1.0f / 60.0f;

// The head's pose (head to world) after `step` steps.
using HeadPath = std::function<glm::mat4(int step)>;
glm::mat4 stillHead(int)
{
    return glm::mat4(1.0f);
}

// Two-particle strands rooted on a ring 35 degrees from the top of the sphere, each lying 1 cm
// along the ring (level, across the slope) at the hair offset, free to swing down the slope about
// its root; returns the mean distance (m) their free ends moved relative to the head (in head
// space) in `steps` steps of 1/60 s with Coulomb coefficient `friction` (static 1.25 times it)
// while the head follows `head`.
double meanSlideMetres(const std::shared_ptr<const SignedDistanceField>& field, float friction, int steps,
    const HeadPath& head = stillHead)
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
    s.timeStepSeconds = kStepSeconds;
    s.substeps = 1;
    s.gravity = { 0.0f, -9.81f, 0.0f };
    s.stiffness = 0.0f; // a free hinge: only contact and friction hold the free end
    s.dampingPerSecond = 0.0f;
    s.friction = friction;
    s.hairOffsetMetres = kOffset;
    EXPECT_EQ(solver.setSettings(s), "");
    std::vector<glm::vec3> start, end;
    solver.copyPositions(start); // the head starts at the identity: head space
    for (int step = 0; step < steps; ++step) {
        solver.setHeadTransform(head(step + 1));
        solver.step();
    }
    solver.copyPositions(end);
    const glm::mat4 worldToHead = glm::inverse(head(steps));
    double slide = 0.0;
    for (int i = 0; i < kStrands; ++i)
        slide += glm::distance(start[2 * i + 1], glm::vec3(worldToHead * glm::vec4(end[2 * i + 1], 1.0f)));
    return slide / kStrands;
}

std::shared_ptr<const SignedDistanceField> sphereField()
{
    std::string error;
    auto field = std::make_shared<SignedDistanceField>(
        SignedDistanceField::bake(test::makeIcosphere(kSphereRadius, 4), 0.0025f, 0.03f, &error));
    EXPECT_EQ(error, "");
    return field;
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
    const auto field = sphereField();
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

// A head that moves steadily carries the hair lying on it: static friction holds the hair where it
// lies on the head, so relative to the head it stays as on a still one, whether the head moves
// sideways (0.1 m/s), shakes (45 degrees a second about its vertical axis) or nods (4 degrees a
// second about a level axis). Each motion is reached by a constant acceleration over half a
// second: a head that jumps to 0.1 m/s at once asks more of the hair's friction than its weight
// gives (6 m/s² on top of the slope's 5.6 against μs g cos 35° = 8), and it slips, as it should.
// Without friction the ends still swing down the slope.
// Regression: friction took the slide in world space, so static friction held the hair still in
// the world while the head moved on under it: the free ends slid 13.3 mm (sideways), 0.76 mm
// (shaking; its slide is mostly along the strands, which their length takes) and 6.9 mm (nodding)
// on the head in 120 steps with friction 0.8; now 0.05, 0.38 and 0.18 mm.
TEST(ContactFriction, HairOnAMovingHeadKeepsItsPlaceOnTheHead)
{
    const auto field = sphereField();
    constexpr int kSteps = 120;
    // Steady motion, reached by a constant acceleration over the first half second: time after
    // `step` steps times the steady speed.
    auto travelSeconds = [](int step) {
        constexpr float kRampSeconds = 0.5f;
        const float t = kStepSeconds * static_cast<float>(step);
        return t < kRampSeconds ? t * t / (2.0f * kRampSeconds) : t - 0.5f * kRampSeconds;
    };
    const HeadPath sideways
        = [&](int step) { return glm::translate(glm::mat4(1.0f), glm::vec3(0.1f * travelSeconds(step), 0.0f, 0.0f)); };
    const HeadPath shaking = [&](int step) { // about its vertical axis
        return glm::rotate(glm::mat4(1.0f), glm::radians(45.0f) * travelSeconds(step), glm::vec3(0.0f, 1.0f, 0.0f));
    };
    const HeadPath nodding = [&](int step) { // about a level axis, 7 degrees in all (the slopes stay below 45)
        return glm::rotate(glm::mat4(1.0f), glm::radians(4.0f) * travelSeconds(step), glm::vec3(1.0f, 0.0f, 0.0f));
    };
    for (const auto& [name, head] : { std::pair{ "moving sideways", sideways }, std::pair{ "shaking", shaking },
             std::pair{ "nodding", nodding } }) {
        const double held = meanSlideMetres(field, 0.8f, kSteps, head);
        const double free = meanSlideMetres(field, 0.0f, kSteps, head);
        std::printf("head %s: in %d steps free ends slid %.2f mm on the head with friction 0.8, %.2f mm without\n",
            name, kSteps, held * 1000.0, free * 1000.0);
        EXPECT_LT(held, 0.001) << name; // static friction holds them on the head within a millimetre
        EXPECT_GT(free, 0.005) << name; // without friction they swing down the slope
    }
}
