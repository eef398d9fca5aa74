// Curls counted per metre of hair: the groom's curly key hairs keep their period along their own
// arc length, and their arc length is their Length.

#include "SimFixtures.h"

#include "sim/groom/Groom.h"
#include "sim/solver/SolverSettings.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace wisp;
using namespace wisp::test;

namespace {

float arcLength(std::span<const glm::vec3> p)
{
    float l = 0.0f;
    for (std::size_t j = 1; j < p.size(); ++j)
        l += glm::distance(p[j - 1], p[j]);
    return l;
}

// Turns per metre of hair of a curl along `p`, measured independently of how it was built: the
// centreline is the mean of the points over one period (`window` points), the curl's offset from
// it is followed around that centreline's parallel-transported frame, and its angle unwrapped.
// Counted from `fromMetres` of hair to the last point with a full window.
double measuredTurnsPerMetre(std::span<const glm::vec3> p, int window, float fromMetres)
{
    const int n = static_cast<int>(p.size()), half = window / 2;
    std::vector<glm::vec3> centre(p.size());
    for (int j = half; j + half < n; ++j) {
        glm::vec3 sum(0.0f);
        for (int k = j - half; k < j - half + window; ++k)
            sum += p[static_cast<std::size_t>(k)];
        centre[static_cast<std::size_t>(j)] = sum / static_cast<float>(window);
    }
    std::vector<float> along(p.size(), 0.0f);
    for (int j = 1; j < n; ++j)
        along[j] = along[j - 1] + glm::distance(p[j - 1], p[j]);
    int first = half + 1;
    while (first < n && along[first] < fromMetres)
        ++first;
    const int last = n - half - 2;
    glm::vec3 e(0.0f);
    double angle = 0.0, previous = 0.0;
    for (int j = first; j <= last; ++j) {
        const glm::vec3 t = glm::normalize(centre[j + 1] - centre[j - 1]);
        if (j == first) {
            e = glm::normalize(glm::cross(t, std::abs(t.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
        } else { // parallel transport: remove the new tangent's part, keep unit length
            e = glm::normalize(e - t * glm::dot(e, t));
        }
        const glm::vec3 o = p[j] - centre[j];
        const double a = std::atan2(glm::dot(o, glm::cross(t, e)), glm::dot(o, e));
        if (j > first) {
            double d = a - previous;
            while (d > glm::pi<double>())
                d -= glm::two_pi<double>();
            while (d < -glm::pi<double>())
                d += glm::two_pi<double>();
            angle += d;
        }
        previous = a;
    }
    return std::abs(angle) / glm::two_pi<double>() / (along[last] - along[first]);
}

Groom curlyGroom(double radius, double turns)
{
    ParameterValues v = testParameters();
    v.set(Param::Density, 0.5);
    v.set(Param::Length, 0.5);
    v.set(Param::LengthVariation, 0.0);
    v.set(Param::Segments, 120); // 4.2 mm segments
    v.set(Param::CurlRadius, radius);
    v.set(Param::CurlTurns, turns);
    GroomResult groom = buildGroom(defaultHead().mesh, defaultHead().growthWeights, groomSettingsFrom(v));
    EXPECT_TRUE(groom.ok()) << groom.error;
    return std::move(groom.groom);
}

} // namespace

TEST(Curl, TurnsAreCountedPerMetreOfHairAndTheArcLengthIsTheLength)
{
    // 1 cm radius, 10 turns per metre of hair: a turn is 0.1 m of hair, 24 segments. Counted per
    // metre of the helix's axis instead, the hair would make 10 / sqrt(1 + (2 pi 0.01 10)^2) = 8.5.
    const Groom groom = curlyGroom(0.01, 10.0);
    ASSERT_GT(groom.wispCount(), 20u);
    for (std::uint32_t k : groom.keyStrand) {
        const std::span<const glm::vec3> key = groom.rest.strand(k);
        EXPECT_NEAR(arcLength(key), groom.lengths[k], 0.01f * groom.lengths[k]) << "strand " << k;
        EXPECT_NEAR(measuredTurnsPerMetre(key, 24, 0.06f), 10.0, 0.2) << "strand " << k;
    }
}

TEST(Curl, TurnsBeyondTheTightestCoilOfTheRadiusAreClampedToIt)
{
    // A 2 cm radius goes around in 0.126 m of hair: at most 0.95 / 0.126 = 7.56 turns per metre.
    const CurlHelix h = curlHelix(0.5f, 120, 0.02f, 10.0f);
    EXPECT_TRUE(h.clamped);
    EXPECT_NEAR(h.turnsPerMetre, kMaxCurlWrap / (glm::two_pi<float>() * 0.02f), 1e-4f);
    EXPECT_NEAR(h.pitchMetres,
        std::sqrt(1.0f / (h.turnsPerMetre * h.turnsPerMetre) - std::pow(0.04f * glm::pi<float>(), 2.0f)), 1e-5f);
    const CurlHelix loose = curlHelix(0.5f, 120, 0.01f, 6.0f);
    EXPECT_FALSE(loose.clamped);
    EXPECT_FLOAT_EQ(loose.turnsPerMetre, 6.0f);

    const Groom groom = curlyGroom(0.02, 10.0);
    for (std::uint32_t k : groom.keyStrand) {
        const std::span<const glm::vec3> key = groom.rest.strand(k);
        EXPECT_NEAR(arcLength(key), groom.lengths[k], 0.01f * groom.lengths[k]) << "strand " << k;
        // 31.7 segments a turn: a 32-point window.
        EXPECT_NEAR(measuredTurnsPerMetre(key, 32, 0.06f), h.turnsPerMetre, 0.3) << "strand " << k;
    }
}

TEST(Curl, StraightHairKeepsItsLength)
{
    const Groom groom = curlyGroom(0.0, 0.0);
    for (std::uint32_t k : groom.keyStrand)
        EXPECT_NEAR(arcLength(groom.rest.strand(k)), groom.lengths[k], 1e-4f * groom.lengths[k]);
}
