// wisp-cli style: one salon brush stroke replayed on a project, as a user runs it; the written
// project holds the stroke's edits, measured in millimetres and metres; bad strokes are refused
// with a message naming what is wrong.
#include "io/ProjectFile.h"
#include "sim/geometry/DefaultHead.h"

#include "CliRunner.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using wisp::test::cli;
using wisp::test::CliRun;

namespace {

class CliStyle : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path() / ("wisp-cli-style-" + std::to_string(::getpid()));
        fs::create_directories(dir);
        project = (dir / "hair.wisp").string();
        // The built-in head with a light groom: 0.3 m strands, all the same length.
        wisp::io::Project p;
        wisp::DefaultHead head = wisp::makeDefaultHead();
        p.head = std::move(head.mesh);
        p.parameters.set(wisp::Param::Volume, 0.0);
        p.parameters.set(wisp::Param::Body, 0.0);
        wisp::GrowthRegion scalp;
        scalp.id = 1;
        scalp.name = "Scalp";
        scalp.weights = std::move(head.growthWeights);
        scalp.values.set(wisp::Param::Density, 2.0);
        scalp.values.set(wisp::Param::WispSize, 4.0);
        scalp.values.set(wisp::Param::Length, 0.3);
        scalp.values.set(wisp::Param::LengthVariation, 0.0);
        p.regions.push_back(std::move(scalp));
        ASSERT_TRUE(wisp::io::writeProject(project, p));
    }
    void TearDown() override { fs::remove_all(dir); }
    wisp::StyleEdits styleOf(const std::string& path)
    {
        auto read = wisp::io::readProject(path);
        EXPECT_TRUE(read) << path;
        return read ? read.value().project.style : wisp::StyleEdits{};
    }
    fs::path dir;
    std::string project;
};

// Behind the head, level with the middle of the hair hanging down the back.
const std::string kEye = "--eye 0,-0.12,-0.6";

} // namespace

TEST_F(CliStyle, CombMovesTheCaughtStrandsAlongTheStroke)
{
    const std::string still = (dir / "still.wisp").string(), combed = (dir / "combed.wisp").string();
    const std::string common = " --brush comb --strength 1 --falloff 0 --radius 0.01 --no-drape " + kEye;
    // The same catch without a move, for where the strands were; then 30 mm to the right (+x).
    CliRun r = cli("style " + project + common + " --stroke '0,-0.12,-0.125;0,-0.12,-0.125' --out " + still, 120);
    ASSERT_EQ(r.status, 0) << r.output;
    r = cli(
        "style " + project + common + " --stroke '0,-0.12,-0.125;0.015,-0.12,-0.125;0.03,-0.12,-0.125' --out " + combed,
        120);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("comb: "), std::string::npos) << r.output;
    const wisp::StyleEdits before = styleOf(still), after = styleOf(combed);
    ASSERT_FALSE(after.empty());
    ASSERT_EQ(before.size(), after.size()) << "the same strands are caught";
    float meanTipMetres = 0.0f;
    for (const auto& [id, style] : after) {
        ASSERT_TRUE(before.count(id));
        const std::vector<glm::vec3>& from = before.at(id).shape;
        ASSERT_EQ(style.shape.size(), from.size());
        EXPECT_EQ(style.shape.front(), from.front()) << "the root stays";
        meanTipMetres += (style.shape.back() - from.back()).x / static_cast<float>(after.size());
    }
    // The tips are pulled the whole 30 mm (full strength, no falloff) less what keeping the
    // segments' lengths takes back: between 15 and 30 mm along the stroke.
    EXPECT_GT(meanTipMetres, 0.015f);
    EXPECT_LE(meanTipMetres, 0.0301f);
}

TEST_F(CliStyle, LengthGrowsTheStrandsUnderTheBrushBySixPercent)
{
    const std::string out = (dir / "grown.wisp").string();
    const CliRun r = cli("style " + project + " --brush length --strength 1 --falloff 0 --radius 0.01 --no-drape "
            + kEye + " --stroke '0,-0.12,-0.125' --out " + out,
        120);
    ASSERT_EQ(r.status, 0) << r.output;
    const wisp::StyleEdits grown = styleOf(out);
    ASSERT_FALSE(grown.empty());
    for (const auto& [id, style] : grown)
        EXPECT_NEAR(style.lengthMetres, 0.3f * 1.06f, 2e-3f) << "strand " << id;
}

TEST_F(CliStyle, CutShortensTheStrandsTheBladeCrosses)
{
    const std::string out = (dir / "cut.wisp").string();
    const CliRun r = cli("style " + project + " --brush cut --no-drape " + kEye
            + " --stroke '-0.03,-0.12,-0.125;0.03,-0.12,-0.125' --out " + out,
        120);
    ASSERT_EQ(r.status, 0) << r.output;
    const wisp::StyleEdits cut = styleOf(out);
    ASSERT_FALSE(cut.empty());
    // The blade lies in the plane y = -0.12 m (the eye and both points are at that height); each
    // crossed strand keeps its part from the root down to the plane, shorter than its 0.3 m. The
    // strands rooted at the back of the crown (y about 0.015 m, hanging straight down) cross it
    // after about 0.135 m of arc.
    bool backOfCrown = false;
    std::string lengths;
    for (const auto& [id, style] : cut) {
        EXPECT_GT(style.lengthMetres, wisp::kStyleMinLengthMetres) << "strand " << id;
        EXPECT_LT(style.lengthMetres, 0.299f) << "strand " << id;
        backOfCrown = backOfCrown || (style.lengthMetres > 0.12f && style.lengthMetres < 0.16f);
        lengths += std::to_string(style.lengthMetres) + " ";
    }
    EXPECT_TRUE(backOfCrown) << lengths;
}

TEST_F(CliStyle, BadStrokesAreRefusedWithTheReason)
{
    const std::string out = (dir / "never.wisp").string();
    CliRun r = cli("style " + project + " --brush comb --stroke '0,abc,0;0,0,0' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("--stroke: point 1 '0,abc,0' is not x,y,z"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush comb --stroke '0,0,-0.2' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("give two or more"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush comb --stroke '0,0,-0.2;0,0,40' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("point 2 '0,0,40' lies more than 10 m from the head"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush brushy --stroke '0,0,-0.2' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("'brushy' is no brush"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush blow-dry --stroke '0,0,-0.2' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("editor"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush length --radius 3 --stroke '0,0,-0.2' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("brush radius: 3 is outside"), std::string::npos) << r.output;
    r = cli("style " + project + " --brush length --stroke '0,0,-0.2'", 60);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("--out FILE is required"), std::string::npos) << r.output;
    r = cli("style " + (dir / "missing.wisp").string() + " --brush length --stroke '0,0,-0.2' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("missing.wisp"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing is written for a refused stroke";
}

TEST_F(CliStyle, APermOutsideItsRangeIsRefusedWithTheRange)
{
    const std::string out = (dir / "permed.wisp").string();
    const CliRun r
        = cli("style " + project + " --brush curl --curl-radius 0.2 --stroke '0,-0.12,-0.125' --out " + out, 60);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("--curl-radius: 0.2 is outside 0..0.05"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
}
