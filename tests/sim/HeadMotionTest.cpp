// Head motion: keyframes and procedural motions evaluate smoothly (no jump in the head's velocity,
// which would fling the hair), and a simulated head drags its hair: roots follow, tips lag, then
// catch up.
#include "SimFixtures.h"

#include "sim/motion/HeadMotion.h"

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace wisp;
using namespace wisp::test;

namespace {

HeadPose pose(glm::vec3 t, double yawDegrees)
{
    return { t, glm::angleAxis(static_cast<float>(glm::radians(yawDegrees)), glm::vec3(0, 1, 0)) };
}

glm::dvec3 velocityBefore(const HeadMotion& m, double t, double h)
{
    return (glm::dvec3(m.poseAt(t).translationMetres) - glm::dvec3(m.poseAt(t - h).translationMetres)) / h;
}
glm::dvec3 velocityAfter(const HeadMotion& m, double t, double h)
{
    return (glm::dvec3(m.poseAt(t + h).translationMetres) - glm::dvec3(m.poseAt(t).translationMetres)) / h;
}
// Angular speed (rad/s) over [a, b]: the angle of the relative rotation, from its vector part
// (precise for small angles, where acos of the dot product is not in float).
double angularSpeed(const HeadMotion& m, double a, double b)
{
    const glm::quat r = glm::inverse(m.poseAt(a).rotation) * m.poseAt(b).rotation;
    const double sine = std::min(1.0, static_cast<double>(glm::length(glm::vec3(r.x, r.y, r.z))));
    return 2.0 * std::asin(sine) / (b - a);
}

// Yaw (radians, about +Y) of a point around the pivot, from +Z toward +X.
double yawOf(const glm::vec3& p, const glm::vec3& pivot)
{
    return std::atan2(p.x - pivot.x, p.z - pivot.z);
}

} // namespace

TEST(HeadMotion, KeysAreHitExactlyAndHeldOutsideTheirSpan)
{
    HeadMotion m;
    m.setKey(1.0, pose({ 0.0f, 0.0f, 0.0f }, 0.0));
    m.setKey(2.0, pose({ 0.1f, 0.02f, 0.0f }, 40.0));
    m.setKey(2.5, pose({ 0.05f, 0.0f, -0.03f }, -20.0));
    ASSERT_EQ(m.keys().size(), 3u);
    for (const HeadKey& k : m.keys()) {
        const HeadPose p = m.poseAt(k.timeSeconds);
        EXPECT_LT(glm::distance(p.translationMetres, k.pose.translationMetres), 1e-6f);
        EXPECT_GT(std::abs(glm::dot(p.rotation, k.pose.rotation)), 1.0f - 1e-6f);
    }
    EXPECT_EQ(m.poseAt(-5.0), m.keys().front().pose);
    EXPECT_EQ(m.poseAt(9.0), m.keys().back().pose);
    // Hold means hold: the same pose a second later.
    EXPECT_EQ(m.poseAt(9.0), m.poseAt(10.0));
    // Setting a key at an existing time replaces it.
    m.setKey(2.0, pose({ 0.2f, 0.0f, 0.0f }, 10.0));
    EXPECT_EQ(m.keys().size(), 3u);
    EXPECT_FLOAT_EQ(m.keys()[1].pose.translationMetres.x, 0.2f);
}

TEST(HeadMotion, VelocityIsContinuousAcrossKeys)
{
    HeadMotion m;
    // Unevenly spaced: Catmull-Rom tangents must account for the spacing or the speed jumps.
    m.setKey(0.0, pose({ 0.0f, 0.0f, 0.0f }, 0.0));
    m.setKey(0.4, pose({ 0.1f, 0.0f, 0.0f }, 30.0));
    m.setKey(1.5, pose({ 0.15f, 0.05f, 0.0f }, -30.0));
    m.setKey(1.7, pose({ 0.0f, 0.0f, 0.02f }, 0.0));
    // One-sided differences over h differ by about acceleration x h even where the velocity is
    // continuous (up to ~80 rad/s² here, so 0.008 rad/s); a jump would be of the order of the
    // speed itself (0.3 to 3 m/s or rad/s here).
    const double h = 1e-4;
    for (std::size_t i = 0; i < m.keys().size(); ++i) {
        const double t = m.keys()[i].timeSeconds;
        const glm::dvec3 before = velocityBefore(m, t, h), after = velocityAfter(m, t, h);
        SCOPED_TRACE("key " + std::to_string(i));
        EXPECT_LT(glm::length(before - after), 0.01) << "m/s jump at the key";
        EXPECT_LT(std::abs(angularSpeed(m, t - h, t) - angularSpeed(m, t, t + h)), 0.01) << "rad/s jump at the key";
    }
    // The interior key keeps moving (a linear or eased-to-rest spline would stop there).
    EXPECT_GT(glm::length(velocityAfter(m, 0.4, h)), 0.05);
    // And between keys the head really turns.
    EXPECT_GT(angularSpeed(m, 0.9, 1.0), 0.3);
    // Before the first key and after the last the head holds still; at the ends it eases.
    EXPECT_LT(glm::length(velocityAfter(m, 0.0, 1e-4)), 3e-3);
    EXPECT_LT(glm::length(velocityBefore(m, 1.7, 1e-4)), 3e-3);
    EXPECT_GT(glm::length(velocityAfter(m, 1.6, 1e-4)), 0.3);
}

TEST(HeadMotion, ProceduralMotionsStartAtRestAndReachTheirAmplitude)
{
    for (MotionKind kind : { MotionKind::Turn, MotionKind::Nod, MotionKind::Shake, MotionKind::Walk }) {
        SCOPED_TRACE(std::string(motionName(kind)));
        HeadMotion m;
        ProceduralMotion p = motionPreset(kind);
        p.startSeconds = 0.5;
        m.setProcedural(p);
        EXPECT_FALSE(m.isStill());
        EXPECT_EQ(m.poseAt(0.5), HeadPose{});
        const double h = 1e-4, period = 1.0 / p.frequencyHz;
        // At the start: no jump in velocity (the envelope eases in).
        EXPECT_LT(glm::length(velocityAfter(m, 0.5, h)), 1e-3);
        EXPECT_LT(angularSpeed(m, 0.5, 0.5 + h), 1e-2);
        // After the fade-in the full amplitude is reached.
        double peak = 0.0;
        for (int i = 0; i <= 400; ++i) {
            const double t = 0.5 + period * (1.0 + i / 400.0);
            const HeadPose q = m.poseAt(t);
            const double value = kind == MotionKind::Walk
                ? static_cast<double>(q.translationMetres.y)
                : glm::degrees(2.0 * std::acos(std::min(1.0, std::abs(double(q.rotation.w)))));
            peak = std::max(peak, value);
        }
        EXPECT_NEAR(peak, p.amplitude, 0.01 * p.amplitude);
    }
}

TEST(HeadMotion, WalkBobsTwicePerStrideAndSwaysOnce)
{
    HeadMotion m;
    m.setProcedural({ MotionKind::Walk, 0.04, 1.0, 0.0 });
    // From the second stride on, the envelope is 1: count upward crossings of the mean height and
    // of zero sway over 4 strides.
    int bobs = 0, sways = 0;
    glm::vec3 last = m.poseAt(1.0).translationMetres;
    for (int i = 1; i <= 4000; ++i) {
        const glm::vec3 p = m.poseAt(1.0 + i * 0.001).translationMetres;
        bobs += last.y < 0.02f && p.y >= 0.02f;
        sways += last.x < 0.0f && p.x >= 0.0f;
        EXPECT_GE(p.y, -1e-7f);
        last = p;
    }
    EXPECT_EQ(bobs, 8);
    EXPECT_EQ(sways, 4);
}

TEST(HeadMotion, RotationTurnsAboutThePivot)
{
    const glm::vec3 pivot = pivotOf(defaultHead().mesh);
    // The top of the neck: below the head's centre and inside it.
    EXPECT_LT(pivot.y, 0.0f);
    EXPECT_GT(pivot.y, -0.2f);
    const glm::mat4 m = headToWorld(pose({ 0.0f, 0.1f, 0.0f }, 90.0), pivot);
    const glm::vec3 movedPivot(m * glm::vec4(pivot, 1.0f));
    EXPECT_LT(glm::distance(movedPivot, pivot + glm::vec3(0.0f, 0.1f, 0.0f)), 1e-6f);
    // The nose (+Z) turns toward +X for a positive yaw.
    const glm::vec3 nose(m * glm::vec4(pivot + glm::vec3(0, 0, 0.1f), 1.0f));
    EXPECT_NEAR(nose.x - pivot.x, 0.1f, 1e-5f);
}

TEST(HeadMotion, ValidationAndKeyEditing)
{
    HeadMotion m;
    m.setKey(0.0, {});
    m.setKey(1.0, pose({ 0.1f, 0, 0 }, 10.0));
    EXPECT_EQ(m.validate(), "");
    std::size_t at = 99;
    EXPECT_EQ(m.moveKey(0, 2.0, &at), "");
    EXPECT_EQ(at, 1u);
    EXPECT_DOUBLE_EQ(m.keys()[1].timeSeconds, 2.0);
    EXPECT_NE(m.moveKey(0, 2.0), ""); // a key is there already
    EXPECT_FALSE(m.removeKey(5));
    EXPECT_TRUE(m.removeKey(0));
    EXPECT_EQ(m.keys().size(), 1u);

    m.setProcedural({ MotionKind::Turn, 120.0, 1.0, 0.0 });
    EXPECT_EQ(m.validate(), "motion: amplitude 120 is outside 0..90 degrees");
    m.setProcedural({ MotionKind::Walk, 0.04, std::nan(""), 0.0 });
    EXPECT_EQ(m.validate(), "motion: frequency nan is not a finite number");
    m.setProcedural({ MotionKind::Walk, 0.04, 12.0, 0.0 });
    EXPECT_EQ(m.validate(), "motion: frequency 12 is outside 0.01..10 Hz");
    m.setProcedural({});
    // The limits are the registry's (sim/params/Parameters.h), read by the panel, files and CLI.
    EXPECT_EQ(HeadMotion::validateProcedural(
                  { MotionKind::Walk, motionSettingInfo(MotionSetting::WalkAmplitude).maximum, 1.0, 0.0 }),
        "");
    EXPECT_EQ(HeadMotion::validateProcedural(
                  { MotionKind::Walk, motionSettingInfo(MotionSetting::WalkAmplitude).maximum * 1.01, 1.0, 0.0 }),
        "amplitude 0.202 is outside 0..0.2 m");
    EXPECT_EQ(m.moveKey(0, 2e6), "time 2e+06 is outside -1e+06..1e+06 s");
    {
        HeadMotion far;
        far.setKey(0.0, { glm::vec3(0.0f, 0.0f, -101.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f) });
        EXPECT_EQ(far.validate(), "keys[0]: translation[2] -101 is outside -100..100 m");
    }
    m.setKey(3.0, { glm::vec3(0.0f), glm::quat(2.0f, 0.0f, 0.0f, 0.0f) });
    EXPECT_EQ(m.validate(), "keys[1]: rotation is not a unit quaternion (length 2)");
    EXPECT_EQ(motionFromName("shake"), MotionKind::Shake);
    EXPECT_EQ(motionFromName("spin"), std::nullopt);
}

// Turning the head: the roots go with it at once, the tips lag behind by a measured angle while
// it turns, then swing after it and settle where the head now faces.
TEST(HeadMotion, TurningTheHeadMakesTheTipsLagThenFollow)
{
    ParameterValues v = testParameters();
    v.set(Param::Length, 0.3); // long enough to swing
    auto sim = makeSimulation(v);
    sim->drapeAtRest();
    const glm::vec3 pivot = pivotOf(defaultHead().mesh);
    const std::vector<glm::vec3> restTips = simulatedTips(*sim);

    HeadMotion motion;
    motion.setKey(0.0, {});
    motion.setKey(0.4, pose(glm::vec3(0.0f), 60.0));
    const float dt = sim->solver().settings().timeStepSeconds;
    // Mean yaw of the tips about the pivot, relative to where they hung, in degrees.
    auto tipTurn = [&] {
        const std::vector<glm::vec3> tips = simulatedTips(*sim);
        double sum = 0.0;
        for (std::size_t i = 0; i < tips.size(); ++i) {
            double d = yawOf(tips[i], pivot) - yawOf(restTips[i], pivot);
            d = std::remainder(d, 2.0 * glm::pi<double>());
            sum += d;
        }
        return glm::degrees(sum / static_cast<double>(tips.size()));
    };

    int step = 0;
    for (; (step + 1) * dt <= 0.4 + 1e-6; ++step) {
        sim->solver().setHeadTransform(motion.headToWorldAt((step + 1) * dt, pivot));
        sim->step();
    }
    // The head has turned 60 degrees; roots went with it.
    const double lagAtEnd = 60.0 - tipTurn();
    EXPECT_GT(lagAtEnd, 10.0) << "the tips should trail the turning head";
    EXPECT_LT(lagAtEnd, 60.0);
    // Roots: on the turned head.
    std::vector<glm::vec3> p;
    sim->copySimulated(p);
    const HairCurves keys = keyRestCurves(sim->groom());
    const glm::mat4 head = motion.headToWorldAt(0.4, pivot);
    for (std::size_t s = 0; s < keys.strandCount(); ++s)
        ASSERT_LT(glm::distance(p[keys.offsets[s]], glm::vec3(head * glm::vec4(keys.positions[keys.offsets[s]], 1.0f))),
            1e-4f);

    // Held still for 3 s, the hair follows: the tips end where the head faces, within a few degrees.
    for (int i = 0; i < static_cast<int>(3.0f / dt); ++i) {
        sim->solver().setHeadTransform(head);
        sim->step();
    }
    EXPECT_NEAR(tipTurn(), 60.0, 5.0);
    RecordProperty("tip_lag_degrees_at_end_of_turn", std::to_string(lagAtEnd));
    std::printf("tips lag %.1f degrees behind a 60-degree turn in 0.4 s\n", lagAtEnd);
}
