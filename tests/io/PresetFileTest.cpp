// Presets: the bundled ones load cleanly and look like their names; write → read is exact; the
// older version loads, a newer one is refused; every kind of bad value is refused with its key path
// and the value as written; hostile files are refused quickly instead of hanging the editor.

#include "io/PresetFile.h"
#include "IoTestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace wisp;
using namespace wisp::io;
namespace fs = std::filesystem;

namespace {

const ParameterValues kDefaults;

fs::path presetsDir()
{
    return fs::path(WISP_PRESETS_DIR);
}

// A fresh, empty folder per test, removed afterwards.
class PresetFileTest : public ::testing::Test {
protected:
    void SetUp() override { m_dir = wisp::test::freshTestFolder("wisp-preset"); }
    void TearDown() override { fs::remove_all(m_dir); }

    std::string write(const std::string& name, const std::string& text)
    {
        const fs::path path = m_dir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }

    fs::path m_dir;
};

Result<PresetReadResult> parse(const std::string& text)
{
    return parsePreset(text, "test.json");
}

// The error a text gives, as the editor would show it; "" when it loads.
std::string errorOf(const std::string& text)
{
    const Result<PresetReadResult> result = parse(text);
    return result ? std::string() : result.error().toString();
}

std::string v2(const std::string& body)
{
    return R"({"format": "wisp-preset", "version": 2)" + body + "}";
}

Preset unusualPreset()
{
    Preset preset;
    preset.name = "Test «look» 1";
    preset.description = "two regions,\n\"quoted\" text and odd numbers";
    EXPECT_EQ(preset.parameters.set(Param::Gravity, 0.1 + 0.2), ""); // 0.30000000000000004
    EXPECT_EQ(preset.parameters.set(Param::WindSpeed, 1.0 / 3.0), "");
    EXPECT_EQ(preset.parameters.set(Param::Segments, 97), "");
    EXPECT_EQ(preset.parameters.set(Param::Seed, 2147483647), "");
    EXPECT_EQ(preset.parameters.set(Param::TimeStep, 1.0 / 240.0), "");
    EXPECT_EQ(preset.parameters.set(Param::SimulateAllStrands, 1), "");
    EXPECT_EQ(preset.parameters.set(Param::WindAzimuth, -0.0), "");
    RegionLook top;
    top.name = "Top";
    EXPECT_EQ(top.wisp.set(Param::CurlRadius, 0.0123456789), "");
    EXPECT_EQ(top.wisp.set(Param::ClumpDegree, -1.0), "");
    EXPECT_EQ(top.wisp.set(Param::WispSize, 1024), "");
    top.rootColour = { 0.123456789f, 1.0f / 3.0f, 0.0f };
    top.tipColour = { 1.0f, 0.1f, 1e-7f };
    RegionLook fringe;
    fringe.name = "Fringe";
    EXPECT_EQ(fringe.wisp.set(Param::Length, 0.05), "");
    preset.regions = { top, fringe };
    return preset;
}

} // namespace

// ---- bundled presets --------------------------------------------------------------------------

TEST(BundledPresets, EveryFileLoadsWithoutWarningsAndChangesSomething)
{
    std::size_t count = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(presetsDir())) {
        if (entry.path().extension() != ".json")
            continue;
        ++count;
        SCOPED_TRACE(entry.path().string());
        const Result<PresetReadResult> result = readPreset(entry.path().string());
        ASSERT_TRUE(result) << result.error().toString();
        EXPECT_TRUE(result.value().warnings.empty()) << result.value().warnings.front();
        const Preset& preset = result.value().preset;
        EXPECT_FALSE(preset.name.empty());
        EXPECT_FALSE(preset.description.empty());
        ASSERT_EQ(preset.regions.size(), 1u);
        // A bundled preset is written out in full, so nothing silently depends on today's defaults.
        const nlohmann::json json = nlohmann::json::parse(std::ifstream(entry.path()));
        for (const ParameterInfo& info : allParameters()) {
            const bool global = info.group != ParamGroup::Wisp;
            const nlohmann::json& object = global ? json["parameters"] : json["regions"][0]["wisp"];
            EXPECT_TRUE(object.contains(std::string(info.key))) << info.key;
        }
    }
    EXPECT_EQ(count, 6u);
}

TEST(BundledPresets, EachLooksLikeItsName)
{
    auto load = [](const char* name) {
        const Result<PresetReadResult> result = readPreset((presetsDir() / (std::string(name) + ".json")).string());
        EXPECT_TRUE(result) << name << ": " << (result ? "" : result.error().toString());
        return result ? result.value().preset : Preset{};
    };
    const Preset straight = load("straight");
    EXPECT_EQ(straight.regions.at(0).wisp.get(Param::CurlRadius), 0.0);
    EXPECT_EQ(straight.parameters.get(Param::Gravity), kDefaults.get(Param::Gravity));

    const Preset wavy = load("wavy");
    EXPECT_NEAR(wavy.regions.at(0).wisp.get(Param::CurlRadius), 0.01, 0.003);
    EXPECT_NEAR(wavy.regions.at(0).wisp.get(Param::CurlTurns), 6.0, 2.0);
    EXPECT_NEAR(wavy.regions.at(0).wisp.get(Param::Length), 0.35, 1e-9);

    const Preset curly = load("curly");
    const ParameterValues& curl = curly.regions.at(0).wisp;
    EXPECT_GT(curl.get(Param::CurlRadius), 0.0);
    EXPECT_LT(curl.get(Param::CurlRadius), wavy.regions.at(0).wisp.get(Param::CurlRadius));
    // Ringlets: 15 or more turns per metre of hair, yet a coil its radius allows (2 pi r T < 0.95).
    EXPECT_GE(curl.get(Param::CurlTurns), 15.0);
    EXPECT_LT(2.0 * 3.14159265 * curl.get(Param::CurlRadius) * curl.get(Param::CurlTurns), 0.95);
    EXPECT_GE(curly.parameters.get(Param::Segments), 40.0);
    EXPECT_LT(curl.get(Param::Length), kDefaults.get(Param::Length));
    EXPECT_GT(curl.get(Param::ClumpDegree), kDefaults.get(Param::ClumpDegree));
    // Enough segments per turn of curl that the helix is a curve, not a zigzag.
    EXPECT_GE(curly.parameters.get(Param::Segments) / (curl.get(Param::CurlTurns) * curl.get(Param::Length)), 5.0);

    const Preset bob = load("short-bob");
    EXPECT_LT(bob.regions.at(0).wisp.get(Param::Length), 0.2);
    EXPECT_LT(bob.regions.at(0).wisp.get(Param::LengthVariation), kDefaults.get(Param::LengthVariation));
    EXPECT_GT(bob.parameters.get(Param::Stiffness), kDefaults.get(Param::Stiffness));

    const Preset windy = load("windy");
    EXPECT_GT(windy.parameters.get(Param::WindSpeed), 5.0);
    EXPECT_GT(windy.parameters.get(Param::Turbulence), kDefaults.get(Param::Turbulence));

    const Preset floating = load("zero-gravity");
    EXPECT_LE(floating.parameters.get(Param::Gravity), 0.0);
    EXPECT_LT(floating.parameters.get(Param::Damping), kDefaults.get(Param::Damping));
}

// ---- round trip and versions ------------------------------------------------------------------

TEST_F(PresetFileTest, WriteThenReadGivesTheSamePreset)
{
    const Preset preset = unusualPreset();
    const std::string path = (m_dir / "look.json").string();
    ASSERT_TRUE(writePreset(path, preset));
    const Result<PresetReadResult> result = readPreset(path);
    ASSERT_TRUE(result) << result.error().toString();
    EXPECT_TRUE(result.value().warnings.empty());
    EXPECT_EQ(result.value().preset, preset);
    EXPECT_EQ(std::signbit(result.value().preset.parameters.get(Param::WindAzimuth)), true);
    // Writing what was read gives the same text: nothing drifts on each save.
    EXPECT_EQ(presetToJson(result.value().preset), presetToJson(preset));
    // Only the file itself is left (the atomic write's temporary is gone).
    EXPECT_EQ(std::distance(fs::directory_iterator(m_dir), fs::directory_iterator()), 1);
}

TEST_F(PresetFileTest, AProceduralHeadMotionIsKeptAndOnlyWhenThereIsOne)
{
    Preset preset = unusualPreset();
    EXPECT_EQ(presetToJson(preset).find("\"motion\""), std::string::npos) << "no motion: no key";
    preset.motion = ProceduralMotion{ MotionKind::Nod, 12.5, 0.6, 0.0 };
    const std::string path = (m_dir / "nodding.json").string();
    ASSERT_TRUE(writePreset(path, preset));
    const Result<PresetReadResult> result = readPreset(path);
    ASSERT_TRUE(result) << result.error().toString();
    EXPECT_TRUE(result.value().warnings.empty());
    EXPECT_EQ(result.value().preset.motion, preset.motion);

    // Keys in a preset are a shot's, not a look's: ignored with a warning; a bad amplitude is refused
    // with its place.
    nlohmann::json json = nlohmann::json::parse(presetToJson(preset));
    json["motion"]["keys"] = nlohmann::json::array({ { { "time", 0.0 } } });
    const Result<PresetReadResult> withKeys = parsePreset(json.dump(), "keys.json");
    ASSERT_TRUE(withKeys) << withKeys.error().toString();
    ASSERT_EQ(withKeys.value().warnings.size(), 1u);
    EXPECT_NE(withKeys.value().warnings[0].find("motion.keys"), std::string::npos) << withKeys.value().warnings[0];
    json["motion"]["procedural"]["amplitude"] = 400;
    const Result<PresetReadResult> wild = parsePreset(json.dump(), "wild.json");
    ASSERT_FALSE(wild);
    EXPECT_EQ(wild.error().toString(), "wild.json: motion.procedural.amplitude: 400 is outside 0..90 degrees");
    // The ranges are the registry's (MotionSetting), the same the Motion panel's spin boxes take.
    json["motion"]["procedural"]["amplitude"] = motionSettingInfo(MotionSetting::TurnAmplitude).maximum;
    json["motion"]["procedural"]["frequency"] = motionSettingInfo(MotionSetting::Frequency).maximum * 2.0;
    const Result<PresetReadResult> fast = parsePreset(json.dump(), "fast.json");
    ASSERT_FALSE(fast);
    EXPECT_EQ(fast.error().toString(), "fast.json: motion.procedural.frequency: 20 is outside 0.01..10 Hz");
}

TEST_F(PresetFileTest, WrittenJsonIsVersion2InRegistryOrderWithReadableNumbers)
{
    Preset preset;
    preset.name = "Plain";
    preset.regions.push_back(RegionLook{ "Scalp", {}, { 0.16f, 0.10f, 0.06f }, { 0.45f, 0.30f, 0.17f } });
    const std::string text = presetToJson(preset);
    EXPECT_NE(text.find(R"("version": 2)"), std::string::npos);
    EXPECT_NE(text.find(R"("root_colour": [0.16, 0.1, 0.06])"), std::string::npos) << text;
    EXPECT_NE(text.find(R"("segments": 15,)"), std::string::npos) << text; // integers without ".0"
    EXPECT_NE(text.find(R"("simulate_all_strands": false)"), std::string::npos);
    // Keys in registry order: segments, seed, gravity ... within "parameters".
    EXPECT_LT(text.find("\"seed\""), text.find("\"gravity\""));
    EXPECT_LT(text.find("\"gravity\""), text.find("\"wind_speed\""));
    EXPECT_LT(text.find("\"density\""), text.find("\"clump_degree\""));
    // Global keys are not in the region, and wisp keys are not in "parameters".
    const nlohmann::json json = nlohmann::json::parse(text);
    EXPECT_FALSE(json["parameters"].contains("length"));
    EXPECT_FALSE(json["regions"][0]["wisp"].contains("gravity"));
    EXPECT_EQ(json["parameters"].size() + json["regions"][0]["wisp"].size(), kParamCount);
}

TEST_F(PresetFileTest, MissingKeysTakeDefaults)
{
    const Result<PresetReadResult> result = parse(v2(R"(, "regions": [{}])"));
    ASSERT_TRUE(result) << result.error().toString();
    const Preset& preset = result.value().preset;
    EXPECT_EQ(preset.name, "test"); // the file's stem
    EXPECT_EQ(preset.parameters, kDefaults);
    ASSERT_EQ(preset.regions.size(), 1u);
    EXPECT_EQ(preset.regions[0], (RegionLook{ "Region 1", {}, { 0.16f, 0.10f, 0.06f }, { 0.45f, 0.30f, 0.17f } }));
    // No "regions" at all: a preset of global settings only.
    const Result<PresetReadResult> globalOnly = parse(v2(R"(, "parameters": {"gravity": 3})"));
    ASSERT_TRUE(globalOnly);
    EXPECT_TRUE(globalOnly.value().preset.regions.empty());
    EXPECT_EQ(globalOnly.value().preset.parameters.get(Param::Gravity), 3.0);
}

TEST_F(PresetFileTest, Version1FlatParametersBecomeOneRegion)
{
    const std::string text = R"({ "format": "wisp-preset", "version": 1, "name": "Old",
        "parameters": { "gravity": 4.5, "length": 0.5, "curl_radius": 0.02, "segments": 30,
                        "simulate_all_strands": 1, "clump_degree": -0.5 } })";
    const Result<PresetReadResult> result = parse(text);
    ASSERT_TRUE(result) << result.error().toString();
    EXPECT_TRUE(result.value().warnings.empty());
    const Preset& preset = result.value().preset;
    EXPECT_EQ(preset.name, "Old");
    EXPECT_EQ(preset.parameters.get(Param::Gravity), 4.5);
    EXPECT_EQ(preset.parameters.get(Param::Segments), 30.0);
    EXPECT_EQ(preset.parameters.get(Param::SimulateAllStrands), 1.0);
    EXPECT_EQ(preset.parameters.get(Param::Length), kDefaults.get(Param::Length)); // wisp keys go to the region
    ASSERT_EQ(preset.regions.size(), 1u);
    EXPECT_EQ(preset.regions[0].name, "Scalp");
    EXPECT_EQ(preset.regions[0].wisp.get(Param::Length), 0.5);
    EXPECT_EQ(preset.regions[0].wisp.get(Param::CurlRadius), 0.02);
    EXPECT_EQ(preset.regions[0].wisp.get(Param::ClumpDegree), -0.5);
    EXPECT_EQ(preset.regions[0].wisp.get(Param::Gravity), kDefaults.get(Param::Gravity));
    // Version 1 had no regions list: one there is unknown.
    const Result<PresetReadResult> withRegions
        = parse(R"({"format": "wisp-preset", "version": 1, "parameters": {}, "regions": []})");
    ASSERT_TRUE(withRegions);
    EXPECT_EQ(withRegions.value().warnings, std::vector<std::string>{ "regions: unknown key, ignored" });
}

TEST_F(PresetFileTest, NewerVersionIsRefused)
{
    EXPECT_EQ(errorOf(R"({"format": "wisp-preset", "version": 3, "regions": "whatever"})"),
        "test.json: version 3 is newer than this Wisp reads (2)");
    EXPECT_EQ(errorOf(R"({"format": "wisp-preset", "version": 0})"),
        "test.json: version: 0 is not a version (they start at 1)");
    EXPECT_EQ(
        errorOf(R"({"format": "wisp-preset", "version": "2"})"), "test.json: version: \"2\" is not a whole number");
    EXPECT_EQ(errorOf(R"({"format": "wisp-preset"})"), "test.json: version: missing");
}

TEST_F(PresetFileTest, OtherFormatsAreRefused)
{
    EXPECT_EQ(errorOf(R"({"format": "wisp-project", "version": 1})"),
        "test.json: format: this is a Wisp project, not a preset");
    EXPECT_EQ(
        errorOf(R"({"format": "blender", "version": 1})"), "test.json: format: \"blender\" is not \"wisp-preset\"");
    EXPECT_EQ(errorOf(R"({"version": 1})"),
        "test.json: format: missing; the file should start with \"format\": \"wisp-preset\"");
    EXPECT_EQ(errorOf("[1, 2]"), "test.json: expected a JSON object { ... } around the whole file, found a list");
}

TEST_F(PresetFileTest, UnknownKeysWarnWithTheirPath)
{
    const Result<PresetReadResult> result = parse(v2(R"(, "author": "me",
        "parameters": { "gravity": 9, "gravitty": 9, "length": 0.3 },
        "regions": [ { "name": "A", "wisp": { "sheen": 0.5, "gravity": 1, "length": 0.2 }, "shine": 1 } ])"));
    ASSERT_TRUE(result) << result.error().toString();
    const std::vector<std::string> expected = {
        "parameters.gravitty: unknown key, ignored",
        "parameters.length: a region's parameter, which belongs in a region's \"wisp\"; ignored here",
        "regions[0].wisp.gravity: a global parameter, which belongs in \"parameters\"; ignored here",
        "regions[0].wisp.sheen: unknown key, ignored",
        "regions[0].shine: unknown key, ignored",
        "author: unknown key, ignored",
    };
    EXPECT_EQ(result.value().warnings, expected);
    EXPECT_EQ(result.value().preset.parameters.get(Param::Gravity), 9.0);
    EXPECT_EQ(result.value().preset.regions.at(0).wisp.get(Param::Length), 0.2);
}

TEST_F(PresetFileTest, AMillionUnknownKeysGiveAScreenfulOfWarnings)
{
    std::string text = R"({"format": "wisp-preset", "version": 2, "parameters": {)";
    for (int i = 0; i < 1'000'000; ++i)
        text += (i ? ",\"k" : "\"k") + std::to_string(i) + "\":0";
    text += "}}";
    const Result<PresetReadResult> result = parse(text);
    ASSERT_TRUE(result);
    ASSERT_EQ(result.value().warnings.size(), 51u);
    EXPECT_EQ(result.value().warnings.back(), "… and 999950 more warnings like these");
}

// ---- refusals ---------------------------------------------------------------------------------

TEST_F(PresetFileTest, BadValuesAreRefusedWithTheirKeyPath)
{
    const std::string region0 = R"({"name": "A"}, )";
    const std::vector<std::pair<std::string, std::string>> cases = {
        // The issue's example, verbatim: the value as written (3.0, not 3).
        { v2(R"(, "regions": [{"name": "A"}, {"name": "B", "clump_degree": 3.0}])"),
            "regions[1].clump_degree: 3.0 is outside -1..1" },
        { v2(R"(, "regions": [{}, {"wisp": {"clump_degree": 3.0}}])"),
            "regions[1].wisp.clump_degree: 3.0 is outside -1..1" },
        { v2(R"(, "regions": [{}, {"wisp": {"clump_degree": 3}}])"),
            "regions[1].wisp.clump_degree: 3 is outside -1..1" },
        { v2(R"(, "parameters": {"gravity": "strong"})"), "parameters.gravity: \"strong\" is not a number" },
        { v2(R"(, "parameters": {"gravity": true})"), "parameters.gravity: true is not a number" },
        { v2(R"(, "parameters": {"gravity": null})"), "parameters.gravity: null is not a number" },
        { v2(R"(, "parameters": {"gravity": [9.81]})"), "parameters.gravity: a list is not a number" },
        { v2(R"(, "parameters": {"time_step": 0.5})"), "parameters.time_step: 0.5 is outside 0.001..0.1" },
        { v2(R"(, "parameters": {"seed": -1})"), "parameters.seed: -1 is outside 0..2147483647" },
        { v2(R"(, "parameters": {"segments": 40.5})"), "parameters.segments: 40.5 is not a whole number" },
        { v2(R"(, "parameters": {"simulate_all_strands": 2})"),
            "parameters.simulate_all_strands: 2 is not true or false" },
        { v2(R"(, "parameters": {"simulate_all_strands": "yes"})"),
            "parameters.simulate_all_strands: \"yes\" is not true or false" },
        { v2(R"(, "regions": [{"wisp": {"wisp_size": 12.5}}])"),
            "regions[0].wisp.wisp_size: 12.5 is not a whole number" },
        { v2(R"(, "regions": [{"root_colour": [0.1, 0.2]}])"), "regions[0].root_colour: expected 3 numbers 0..1" },
        { v2(R"(, "regions": [{"root_colour": [0.1, 0.2, 1.5]}])"), "regions[0].root_colour: expected 3 numbers 0..1" },
        { v2(R"(, "regions": [{"root_colour": "brown"}])"), "regions[0].root_colour: expected 3 numbers 0..1" },
        { v2(R"(, "regions": [)" + region0 + R"({"tip_colour": [0, "0", 0]}])"),
            "regions[1].tip_colour: expected 3 numbers 0..1" },
        { v2(R"(, "regions": [{"wisp": {"length": 0.2}, "length": 0.3}])"),
            "regions[0].length: given twice, here and at regions[0].wisp.length" },
        { v2(R"(, "regions": {"name": "A"})"), "regions: expected a list [ ... ] of regions, found an object" },
        { v2(R"(, "regions": [3])"), "regions[0]: expected an object { ... }, found 3" },
        { v2(R"(, "regions": [{"wisp": [1]}])"), "regions[0].wisp: expected an object { ... }, found a list" },
        { v2(R"(, "regions": [{"name": 7}])"), "regions[0].name: 7 is not text (text goes in double quotes)" },
        { v2(R"(, "parameters": 9.81)"), "parameters: expected an object { ... }, found 9.81" },
        { v2(R"(, "name": ["a"])"), "name: a list is not text (text goes in double quotes)" },
    };
    for (const auto& [text, expected] : cases) {
        SCOPED_TRACE(text);
        EXPECT_EQ(errorOf(text), "test.json: " + expected);
    }
    // The location alone is the key path, for an editor that wants to point at it.
    const Result<PresetReadResult> result = parse(cases[0].first);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().location, "regions[1].clump_degree");
    EXPECT_EQ(result.error().message, "3.0 is outside -1..1");
}

TEST_F(PresetFileTest, LongTextValuesAreShortenedInMessages)
{
    const std::string error = errorOf(v2(R"(, "parameters": {"gravity": ")" + std::string(100'000, 'x') + "\"}"));
    EXPECT_EQ(error, "test.json: parameters.gravity: \"" + std::string(40, 'x') + "…\" is not a number");
}

TEST_F(PresetFileTest, MalformedJsonGivesLineAndColumn)
{
    const std::string text = "{\n  \"format\": \"wisp-preset\",\n  \"version\": 2,\n}\n";
    const Result<PresetReadResult> result = parse(text);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().location, "line 4, column 1");
    EXPECT_NE(result.error().message.find("unexpected '}'"), std::string::npos) << result.error().message;
    EXPECT_EQ(result.error().message.find("json.exception"), std::string::npos) << result.error().message;

    const Result<PresetReadResult> cut = parse("{\n  \"format\": \"wisp-pre");
    ASSERT_FALSE(cut);
    EXPECT_EQ(cut.error().location, "line 2, column 22"); // one past the last character
}

TEST_F(PresetFileTest, EmptyAndMissingFilesAreRefused)
{
    EXPECT_EQ(readPreset(write("empty.json", "")).error().message, "the file is empty");
    EXPECT_EQ(readPreset(write("blank.json", " \n\t\n")).error().message, "the file is empty");
    const Result<PresetReadResult> missing = readPreset((m_dir / "nope.json").string());
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().toString(), (m_dir / "nope.json").string() + ": the file does not exist");
    EXPECT_EQ(readPreset(m_dir.string()).error().message, "this is a folder, not a preset file");
}

TEST_F(PresetFileTest, TruncatedPresetsAreRefusedAtEveryLength)
{
    const std::string text = presetToJson(unusualPreset());
    const std::size_t end = text.find_last_not_of(" \n") + 1;
    for (std::size_t length = 0; length < end; ++length) {
        const Result<PresetReadResult> result = parse(text.substr(0, length));
        ASSERT_FALSE(result) << "length " << length;
        EXPECT_FALSE(result.error().toString().empty());
    }
    EXPECT_TRUE(parse(text.substr(0, end)));
}

TEST_F(PresetFileTest, HostileFilesAreRefusedWithoutHanging)
{
    // A million regions: refused before any is read.
    std::string many = R"({"format": "wisp-preset", "version": 2, "regions": [{})";
    for (int i = 1; i < 1'000'000; ++i)
        many += ",{}";
    many += "]}";
    EXPECT_EQ(errorOf(many), "test.json: regions: 1000000 regions; at most 256 are allowed");

    // A 100 MB string: refused before parsing.
    const std::string huge = v2(R"(, "description": ")" + std::string(100u << 20, 'a') + "\"");
    const Result<PresetReadResult> hugeResult = parse(huge);
    ASSERT_FALSE(hugeResult);
    EXPECT_EQ(hugeResult.error().message, "the text is 101 MB; a preset is at most 16 MB");
    // The same on disk is refused by its size, without reading it.
    const std::string bigFile = (m_dir / "big.json").string();
    {
        std::ofstream out(bigFile, std::ios::binary);
        out << huge;
    }
    EXPECT_EQ(readPreset(bigFile).error().message, "the file is 101 MB; a preset file is at most 16 MB");

    // A long description under the file limit is refused by its own limit.
    EXPECT_EQ(errorOf(v2(R"(, "description": ")" + std::string(1u << 20, 'a') + "\"")),
        "test.json: description: the text is 1048576 bytes long; at most 65536 are allowed");
    EXPECT_EQ(errorOf(v2(R"(, "name": ")" + std::string(300, 'n') + "\"")),
        "test.json: name: the text is 300 bytes long; at most 256 are allowed");

    // Deep nesting neither overflows the stack while parsing nor while freeing.
    const std::string deep
        = v2(R"(, "parameters": {"gravity": )" + std::string(1'000'000, '[') + std::string(1'000'000, ']') + "}");
    EXPECT_EQ(errorOf(deep), "test.json: parameters.gravity: a list is not a number");

    // Text that is not UTF-8 is a syntax error with a place.
    const Result<PresetReadResult> latin1 = parse(v2(", \"name\": \"caf\xe9\""));
    ASSERT_FALSE(latin1);
    EXPECT_EQ(latin1.error().location.rfind("line 1, column ", 0), 0u);
}

TEST_F(PresetFileTest, WritingIntoAMissingFolderFailsCleanly)
{
    const std::string path = (m_dir / "missing" / "look.json").string();
    const Result<void> result = writePreset(path, Preset{});
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().file, path);
    EXPECT_EQ(result.error().message.find(path), std::string::npos); // the path is said once, as the file
    EXPECT_FALSE(fs::exists(m_dir / "missing"));
    EXPECT_TRUE(fs::is_empty(m_dir));
}

// ---- range ends and the body toggle ------------------------------------------------------------

TEST_F(PresetFileTest, RangeEndsAsWrittenAreAccepted)
{
    const Result<PresetReadResult> result = parse(v2(R"(, "parameters": {"time_step": 0.1, "hair_offset": 0.02},
        "regions": [{"wisp": {"curl_radius": 0.05, "length": 0.005, "length_variation": 0.9}}])"));
    ASSERT_TRUE(result) << result.error().toString();
    EXPECT_FLOAT_EQ(static_cast<float>(result.value().preset.parameters.get(Param::TimeStep)), 0.1f);
    EXPECT_FLOAT_EQ(static_cast<float>(result.value().preset.regions.at(0).wisp.get(Param::CurlRadius)), 0.05f);
    const Result<PresetReadResult> substeps = parse(v2(R"(, "parameters": {"substeps": 2.5})"));
    ASSERT_FALSE(substeps);
    EXPECT_NE(substeps.error().toString().find("parameters.substeps: 2.5 is not a whole number"), std::string::npos)
        << substeps.error().toString();
}

TEST_F(PresetFileTest, TheBodyToggleRoundTrips)
{
    for (bool on : { false, true }) {
        Preset preset;
        ASSERT_EQ(preset.parameters.set(Param::Body, on ? 1 : 0), "");
        const std::string path = (m_dir / "body.json").string();
        ASSERT_TRUE(writePreset(path, preset));
        const Result<PresetReadResult> result = readPreset(path);
        ASSERT_TRUE(result) << result.error().toString();
        EXPECT_EQ(result.value().preset.parameters.get(Param::Body), on ? 1.0 : 0.0);
        EXPECT_EQ(nlohmann::json::parse(presetToJson(preset))["parameters"]["body"], on);
    }
    // Absent (a preset from before the body): on, the default.
    const Result<PresetReadResult> old = parse(v2(R"(, "parameters": {"gravity": 3})"));
    ASSERT_TRUE(old);
    EXPECT_EQ(old.value().preset.parameters.get(Param::Body), 1.0);
    const Result<PresetReadResult> half = parse(v2(R"(, "parameters": {"body": 0.5})"));
    ASSERT_FALSE(half);
    EXPECT_NE(half.error().toString().find("parameters.body: 0.5 is not true or false"), std::string::npos)
        << half.error().toString();
}

// Issue 12: a number that overflows a double surfaced nlohmann's raw text
// ("[json.exception.out_of_range.406] number overflow parsing '1e999'") with no place.
TEST(PresetFileErrors, NumberOverflowNamesTheLineAndColumn)
{
    const std::string text = "{\"format\": \"wisp-preset\", \"version\": 2,\n \"name\": \"1e999\",\n"
                             " \"parameters\": {\"gravity\": -1e999}}";
    EXPECT_EQ(
        errorOf(text), "test.json: line 3, column 28: the number -1e999 is too large to hold (it overflows a double)");
    EXPECT_EQ(errorOf(text).find("json.exception"), std::string::npos);
}
