// The head's motion and the timeline in projects, and the USD writer's text.
#include "IoTestSupport.h"
#include "io/ProjectFile.h"
#include "io/UsdaWriter.h"
#include "sim/geometry/DefaultHead.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test;

namespace {

io::Project headOnly()
{
    static const TriangleMesh head = makeDefaultHead().mesh;
    io::Project p;
    p.head = head;
    return p;
}

HeadMotion someMotion()
{
    HeadMotion m;
    m.setKey(
        0.25, { glm::vec3(0.01f, -0.02f, 0.003f), glm::angleAxis(0.3f, glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f))) });
    m.setKey(1.0 / 3.0, { glm::vec3(0.1f, 0.0f, 0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f) });
    m.setProcedural({ MotionKind::Walk, 0.035, 1.1, 0.5 });
    return m;
}

} // namespace

TEST(MotionFile, KeysMotionAndTimelineRoundTripExactly)
{
    const auto dir = freshTestFolder("wisp-motion");
    io::Project project = headOnly();
    project.motion = someMotion();
    project.timeline = { 10, 120, 30.0 };
    const std::string path = (dir / "m.wisp").string();
    ASSERT_TRUE(writeProject(path, project));
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    EXPECT_EQ(read.value().project.motion, project.motion); // bit for bit: times, translations, quaternions
    EXPECT_EQ(read.value().project.timeline, project.timeline);
    const nlohmann::json json = nlohmann::json::parse(slurp(path));
    EXPECT_EQ(json["motion"]["procedural"]["kind"], "walk");
    EXPECT_EQ(json["motion"]["keys"].size(), 2u);
    EXPECT_EQ(json["timeline"]["fps"], 30.0);
}

TEST(MotionFile, OlderProjectsReadAsStillAndDefaultsAreNotWritten)
{
    const auto dir = freshTestFolder("wisp-motion");
    const std::string path = (dir / "old.wisp").string();
    ASSERT_TRUE(writeProject(path, headOnly()));
    const std::string text = slurp(path);
    EXPECT_EQ(text.find("\"motion\""), std::string::npos);
    EXPECT_EQ(text.find("\"timeline\""), std::string::npos);
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read);
    EXPECT_TRUE(read.value().project.motion.isStill());
    EXPECT_EQ(read.value().project.timeline, BakeRange{});
}

TEST(MotionFile, BadMotionIsRefusedWithItsKeyPath)
{
    const auto dir = freshTestFolder("wisp-motion");
    io::Project project = headOnly();
    project.motion = someMotion();
    const std::string path = (dir / "bad.wisp").string();
    ASSERT_TRUE(writeProject(path, project));
    nlohmann::json json = nlohmann::json::parse(slurp(path));
    auto refusal = [&](const nlohmann::json& edited) {
        const Result<ProjectReadResult> r = parseProject(edited.dump(), path);
        return r ? std::string("accepted") : r.error().toString();
    };
    nlohmann::json j = json;
    j["motion"]["keys"][1]["time"] = 0.1;
    EXPECT_EQ(refusal(j), path + ": motion.keys[1].time: keys must be in increasing time");
    j = json;
    j["motion"]["keys"][0]["rotation"] = { 2, 0, 0, 0 };
    EXPECT_EQ(refusal(j), path + ": motion: keys[0]: rotation is not a unit quaternion (length 2)");
    j = json;
    j["motion"]["procedural"]["kind"] = "spin";
    EXPECT_EQ(refusal(j), path + ": motion.procedural.kind: 'spin' is not none, turn, nod, shake or walk");
    j = json;
    j["motion"]["procedural"]["amplitude"] = 5;
    EXPECT_EQ(refusal(j), path + ": motion.procedural.amplitude: 5 is outside 0..0.2 m");
    // Every number against the registry's range (MotionSetting), refused at its own field.
    j = json;
    j["motion"]["procedural"]["frequency"] = 0.001;
    EXPECT_EQ(refusal(j), path + ": motion.procedural.frequency: 0.001 is outside 0.01..10 Hz");
    j = json;
    j["motion"]["procedural"]["start"] = -2e6;
    EXPECT_EQ(refusal(j), path + ": motion.procedural.start: -2e+06 is outside -1e+06..1e+06 s");
    j = json;
    j["motion"]["keys"][1]["time"] = 5e6;
    EXPECT_EQ(refusal(j), path + ": motion.keys[1].time: 5e+06 is outside -1e+06..1e+06 s");
    j = json;
    j["motion"]["keys"][0]["translation"] = { 0, 150, 0 };
    EXPECT_EQ(refusal(j), path + ": motion.keys[0].translation[1]: 150 is outside -100..100 m");
    j = json;
    j["timeline"] = { { "first_frame", 9 }, { "last_frame", 3 } };
    EXPECT_EQ(refusal(j), path + ": timeline: frames 9:3: the last frame comes before the first");
    j = json;
    j["timeline"] = { { "fps", "fast" } };
    EXPECT_NE(refusal(j).find(path + ": timeline.fps: "), std::string::npos);
}

TEST(UsdaWriter, AnimatedCurvesHaveOneSamplePerFrameAndExactNumbers)
{
    UsdaScene scene;
    scene.offsets = { 0, 3, 3, 4, 6 }; // an empty strand and a one-point strand are left out
    scene.widthsMetres = taperedWidths(scene.offsets, std::vector<float>{ 80e-6f, 1e-4f, 1e-4f, 60e-6f }, 0.25f);
    ASSERT_EQ(scene.widthsMetres.size(), 6u);
    EXPECT_FLOAT_EQ(scene.widthsMetres[0], 80e-6f);
    EXPECT_FLOAT_EQ(scene.widthsMetres[2], 20e-6f);
    std::vector<glm::vec3> a
        = { { 0, 1, 0 }, { 0, 0.9f, 0 }, { 0, 0.8f, 0.1f }, { 5, 5, 5 }, { 0.1f, 1, 0 }, { 0.1f, 0.7f, 1.0f / 3.0f } };
    std::vector<glm::vec3> b = a;
    b[2].z = -0.25f;
    glm::mat4 moved(1.0f);
    moved[3] = glm::vec4(0.5f, 0.0f, -2.0f, 1.0f);
    scene.frames = { { 1.0, a, glm::mat4(1.0f) }, { 2.0, b, moved } };
    scene.framesPerSecond = 24.0;
    const TriangleMesh head = { { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 } } };
    scene.head = &head;
    std::string error;
    const std::string text = usdaText(scene, &error);
    ASSERT_EQ(error, "");
    EXPECT_NE(text.find("metersPerUnit = 1\n"), std::string::npos);
    EXPECT_NE(text.find("upAxis = \"Y\"\n"), std::string::npos);
    EXPECT_NE(text.find("startTimeCode = 1\n    endTimeCode = 2\n    timeCodesPerSecond = 24\n"), std::string::npos);
    EXPECT_NE(text.find("int[] curveVertexCounts = [3, 2]\n"), std::string::npos);
    EXPECT_NE(
        text.find("            1: [(0, 1, 0), (0, 0.9, 0), (0, 0.8, 0.1), (0.1, 1, 0), (0.1, 0.7, 0.33333334)],\n"),
        std::string::npos)
        << text;
    EXPECT_NE(text.find("            2: [(0, 1, 0), (0, 0.9, 0), (0, 0.8, -0.25), "), std::string::npos);
    EXPECT_NE(
        text.find("float[] widths = [8e-05, 5e-05, 2e-05, 6e-05, 1.5e-05] (\n            interpolation = \"vertex\""),
        std::string::npos)
        << text;
    EXPECT_NE(text.find("2: ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0.5, 0, -2, 1)),"), std::string::npos) << text;
    EXPECT_NE(text.find("int[] faceVertexIndices = [0, 1, 2]"), std::string::npos);
    // Deterministic.
    EXPECT_EQ(usdaText(scene, nullptr), text);

    // A still: plain values, no time samples.
    scene.animated = false;
    scene.frames.resize(1);
    const std::string still = usdaText(scene, &error);
    EXPECT_EQ(still.find("timeSamples"), std::string::npos);
    EXPECT_NE(still.find("point3f[] points = [(0, 1, 0),"), std::string::npos);
}

TEST(UsdaWriter, RefusesWhatItCannotWriteAndLeavesNoFile)
{
    const auto dir = freshTestFolder("wisp-usda");
    UsdaScene scene;
    scene.offsets = { 0, 2 };
    scene.widthsMetres = { 1e-4f, 1e-4f };
    std::vector<glm::vec3> p = { { 0, 0, 0 }, { 0, NAN, 0 } };
    scene.frames = { { 1.0, p, glm::mat4(1.0f) } };
    const std::string path = (dir / "x.usda").string();
    const Result<void> e = writeUsda(path, scene);
    ASSERT_FALSE(e.ok());
    EXPECT_EQ(e.error().toString(), path + ": frame 0 (time code 1): point 1 is not finite");
    EXPECT_FALSE(std::filesystem::exists(path));
    p[1].y = 1.0f;
    scene.widthsMetres = { 1e-4f };
    EXPECT_EQ(writeUsda(path, scene).error().message, "1 widths for 2 points");
    scene.widthsMetres = { 1e-4f, 1e-4f };
    scene.frames.clear();
    EXPECT_EQ(writeUsda(path, scene).error().message, "there is no frame to write");
    scene.frames = { { 1.0, p, glm::mat4(1.0f) } };
    EXPECT_FALSE(writeUsda((dir / "missing" / "x.usda").string(), scene).ok());
    EXPECT_TRUE(writeUsda(path, scene).ok());
    EXPECT_TRUE(std::filesystem::exists(path));
}
