// The one shortest-arc rotation (sim/geometry/ShortestArc.h): generic, parallel and antiparallel inputs.
#include "sim/geometry/ShortestArc.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>

using namespace wisp;

namespace {

void expectNear(const glm::vec3& got, const glm::vec3& want, float tolerance = 1e-5f)
{
    EXPECT_NEAR(got.x, want.x, tolerance);
    EXPECT_NEAR(got.y, want.y, tolerance);
    EXPECT_NEAR(got.z, want.z, tolerance);
}

} // namespace

TEST(ShortestArc, TakesAOntoBAndTurnsOtherVectorsRigidly)
{
    const glm::vec3 a = glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f));
    const glm::vec3 b = glm::normalize(glm::vec3(-0.3f, 0.4f, 1.0f));
    expectNear(rotateShortestArc(a, b, a), b);
    // The axis a x b stays put; lengths and angles are kept; the matrix is a proper rotation.
    const glm::vec3 k = glm::normalize(glm::cross(a, b));
    expectNear(rotateShortestArc(a, b, k), k);
    const glm::vec3 v(0.2f, -1.5f, 0.7f), w(1.0f, 0.0f, 0.3f);
    EXPECT_NEAR(glm::length(rotateShortestArc(a, b, v)), glm::length(v), 1e-5f);
    EXPECT_NEAR(glm::dot(rotateShortestArc(a, b, v), rotateShortestArc(a, b, w)), glm::dot(v, w), 1e-5f);
    const glm::mat3 r = shortestArcMatrix(a, b);
    EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f);
    expectNear(r * v, rotateShortestArc(a, b, v));
}

TEST(ShortestArc, ParallelInputsTurnNothing)
{
    const glm::vec3 a = glm::normalize(glm::vec3(0.0f, -1.0f, 0.2f));
    const glm::vec3 v(0.3f, 0.1f, -2.0f);
    expectNear(rotateShortestArc(a, a, v), v);
    expectNear(turnShortestArc(a, a, v, 0.5f), v);
    const glm::mat3 identity = shortestArcMatrix(a, a);
    for (int column = 0; column < 3; ++column)
        expectNear(identity[column], glm::mat3(1.0f)[column]);
}

TEST(ShortestArc, AntiparallelInputsTakeTheHalfTurnAboutAFixedPerpendicular)
{
    for (const glm::vec3& a :
        { glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)) }) {
        const glm::vec3 axis = anyPerpendicular(a);
        EXPECT_NEAR(glm::dot(axis, a), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(axis), 1.0f, 1e-6f);
        expectNear(rotateShortestArc(a, -a, a), -a); // a still lands on b
        expectNear(rotateShortestArc(a, -a, axis), axis); // about that axis
        const glm::vec3 across = glm::cross(a, axis);
        expectNear(rotateShortestArc(a, -a, across), -across);
        EXPECT_NEAR(glm::determinant(shortestArcMatrix(a, -a)), 1.0f, 1e-5f) << "a rotation, not a reflection";
        // Part of the way has no unique direction: v is left as it is.
        expectNear(turnShortestArc(a, -a, across, 0.5f), across);
    }
    // Nearly antiparallel (within the 1e-4 band) is treated the same way, and stays a unit map.
    const glm::vec3 a(0.0f, 0.0f, 1.0f);
    const glm::vec3 b = glm::normalize(glm::vec3(0.005f, 0.0f, -1.0f));
    EXPECT_NEAR(glm::length(rotateShortestArc(a, b, glm::vec3(0.0f, 1.0f, 0.0f))), 1.0f, 1e-5f);
}

TEST(ShortestArc, TurnsAShareOfTheAngleUpToTheLimit)
{
    const glm::vec3 x(1, 0, 0), y(0, 1, 0);
    const float h = std::sqrt(0.5f);
    expectNear(turnShortestArc(x, y, x, 0.5f), glm::vec3(h, h, 0.0f)); // half of 90 degrees
    expectNear(turnShortestArc(x, y, x, 1.0f), y);
    const glm::vec3 limited = turnShortestArc(x, y, x, 1.0f, 0.3f);
    EXPECT_NEAR(std::acos(glm::dot(limited, x)), 0.3f, 1e-5f);
}
