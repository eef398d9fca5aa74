// wisp-cli's file commands as a user runs them: convert, validate, simulate with a preset, a head
// file, imported hair and an export; broken files end with exit status 1 and a message naming
// the file and the problem.
#include "io/HairFiles.h"

#include "../SharedAssets.h"
#include "CliRunner.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using wisp::test::cli;
using wisp::test::CliRun;

namespace {

const fs::path kAssets = wisp::test::sharedAssetsDir();
const fs::path kPresets = WISP_PRESETS_DIR;

class CliFiles : public ::testing::Test {
protected:
    void SetUp() override
    {
        REQUIRE_SHARED_ASSET(kAssets / "hair");
        dir = fs::temp_directory_path() / ("wisp-cli-files-" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    void TearDown() override
    {
        if (!dir.empty())
            fs::remove_all(dir);
    }
    fs::path dir;
};

} // namespace

TEST_F(CliFiles, ConvertRoundTripsTheSampleStrandsExactly)
{
    const fs::path hair = dir / "bangs.hair", data = dir / "bangs.data";
    const CliRun toHair = cli("convert " + (kAssets / "hair/ct2hair_bangs100.data").string() + " " + hair.string());
    ASSERT_EQ(toHair.status, 0) << toHair.output;
    EXPECT_NE(toHair.output.find("100 strands (1165 points)"), std::string::npos) << toHair.output;
    ASSERT_EQ(cli("convert " + hair.string() + " " + data.string()).status, 0);
    const auto original = wisp::io::readHair((kAssets / "hair/ct2hair_bangs100.data").string());
    const auto back = wisp::io::readHair(data.string());
    ASSERT_TRUE(original && back);
    EXPECT_EQ(back.value().strands.offsets, original.value().strands.offsets);
    EXPECT_EQ(back.value().strands.positions, original.value().strands.positions);

    // With a head beside the strands, as glTF.
    const fs::path glb = dir / "bangs.glb";
    const CliRun toGlb = cli("convert " + hair.string() + " " + glb.string() + " --head "
        + (kAssets / "hair/ct2hair_bangs_head.ply").string());
    ASSERT_EQ(toGlb.status, 0) << toGlb.output;
    const CliRun glbInfo = cli("validate " + glb.string());
    EXPECT_EQ(glbInfo.status, 0) << glbInfo.output;
    EXPECT_NE(glbInfo.output.find("7694 triangles"), std::string::npos) << glbInfo.output;

    const CliRun wrong = cli("convert " + hair.string() + " " + (dir / "x.abc").string());
    EXPECT_EQ(wrong.status, 1);
    EXPECT_NE(wrong.output.find("x.abc"), std::string::npos) << wrong.output;
    EXPECT_EQ(cli("convert " + hair.string()).status, 2) << "OUT is missing";
}

TEST_F(CliFiles, ValidateSaysWhatAFileHolds)
{
    const CliRun head = cli("validate " + (kAssets / "heads/max_planck_decimated.obj").string());
    EXPECT_EQ(head.status, 0) << head.output;
    EXPECT_NE(head.output.find("10540 triangles"), std::string::npos) << head.output;
    EXPECT_NE(head.output.find("imported at"), std::string::npos) << head.output;
    const CliRun hair = cli("validate " + (kAssets / "hair/ct2hair_bangs100.hair").string());
    EXPECT_EQ(hair.status, 0);
    EXPECT_NE(hair.output.find("100 strands, 1165 points"), std::string::npos) << hair.output;
    const CliRun preset = cli("validate " + (kPresets / "wavy.json").string());
    EXPECT_EQ(preset.status, 0);
    EXPECT_NE(preset.output.find("preset 'Wavy'"), std::string::npos) << preset.output;
}

TEST_F(CliFiles, ValidateNamesTheFileAndTheProblem)
{
    const CliRun draco = cli("validate " + (kAssets / "gltf/2CylinderEngine_draco/2CylinderEngine.gltf").string());
    EXPECT_EQ(draco.status, 1);
    EXPECT_NE(draco.output.find("Draco"), std::string::npos) << draco.output;
    const CliRun magic = cli("validate " + (kAssets / "gltf/validator_glb/invalid_magic.glb").string());
    EXPECT_EQ(magic.status, 1);
    EXPECT_NE(magic.output.find("invalid_magic.glb"), std::string::npos) << magic.output;

    // A preset with a value out of range names its key path.
    std::ofstream(dir / "bad.json") << R"({"format": "wisp-preset", "version": 2, "name": "Bad",
        "regions": [{"name": "A"}, {"name": "B", "clump_degree": 3.0}]})";
    const CliRun bad = cli("validate " + (dir / "bad.json").string());
    EXPECT_EQ(bad.status, 1);
    EXPECT_NE(bad.output.find("regions[1].clump_degree: 3.0 is outside -1..1"), std::string::npos) << bad.output;

    // A .hair whose header claims more points than it holds.
    {
        std::ifstream in(kAssets / "hair/ct2hair_bangs100.hair", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        std::ofstream(dir / "cut.hair", std::ios::binary) << bytes.substr(0, 1000);
    }
    const CliRun cut = cli("validate " + (dir / "cut.hair").string());
    EXPECT_EQ(cut.status, 1);
    EXPECT_NE(cut.output.find("cut.hair"), std::string::npos) << cut.output;
    EXPECT_EQ(cli("validate " + (dir / "what.xyz").string()).status, 1);
    EXPECT_EQ(cli("validate").status, 2);
}

TEST_F(CliFiles, SimulateWithAPresetAHeadFileAndAnExport)
{
    const fs::path out = dir / "curly.gltf";
    const CliRun run = cli("simulate --steps 10 --preset " + (kPresets / "curly.json").string() + " --head "
        + (kAssets / "heads/max_planck_decimated.obj").string() + " --density 1 --export " + out.string());
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("imported at"), std::string::npos) << run.output;
    ASSERT_TRUE(fs::exists(out));
    const CliRun info = cli("validate " + out.string());
    EXPECT_EQ(info.status, 0) << info.output;

    // Imported strands become simulated wisps; exported at rest they keep their count.
    const fs::path rest = dir / "rest.data";
    const CliRun hair = cli("simulate --steps 5 --hair " + (kAssets / "hair/ct2hair_bangs100.hair").string()
        + " --hair-scale 0.001 --rest --export " + rest.string());
    ASSERT_EQ(hair.status, 0) << hair.output;
    EXPECT_NE(hair.output.find("strands 100 (simulated 100"), std::string::npos) << hair.output;
    const auto back = wisp::io::readHair(rest.string());
    ASSERT_TRUE(back);
    EXPECT_EQ(back.value().strands.strandCount(), 100u);

    const CliRun badPreset = cli("simulate --steps 1 --preset " + (dir / "missing.json").string());
    EXPECT_EQ(badPreset.status, 1);
    EXPECT_NE(badPreset.output.find("missing.json"), std::string::npos) << badPreset.output;
}
