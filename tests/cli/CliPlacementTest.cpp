// wisp-cli simulate places a head file and the strands made on it as the editor does
// (io/HeadPlacement.h, io/StrandPlacement.h), says what it decided, and prints its warnings.
#include "io/HairFiles.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "io/StrandPlacement.h"
#include "io/StrandText.h"

#include "../SharedAssets.h"
#include "CliRunner.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace wisp;
using wisp::test::cli;
using wisp::test::CliRun;

namespace {

const fs::path kAssets = wisp::test::sharedAssetsDir();

class CliPlacement : public ::testing::Test {
protected:
    void SetUp() override
    {
        REQUIRE_SHARED_ASSET(kAssets / "hair");
        dir = fs::temp_directory_path() / ("wisp-cli-placement-" + std::to_string(::getpid()));
        fs::create_directories(dir);
    }
    void TearDown() override
    {
        if (!dir.empty())
            fs::remove_all(dir);
    }
    fs::path dir;
};

HairCurves readBangs()
{
    auto read = io::readHair((kAssets / "hair/ct2hair_bangs100.data").string());
    EXPECT_TRUE(read.ok());
    return read ? std::move(read).value().strands : HairCurves{};
}

float longestStrand(const HairCurves& strands)
{
    float longest = 0.0f;
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        float length = 0.0f;
        for (std::uint32_t i = strands.offsets[s] + 1; i < strands.offsets[s + 1]; ++i)
            length += glm::distance(strands.positions[i - 1], strands.positions[i]);
        longest = std::max(longest, length);
    }
    return longest;
}

} // namespace

// CT2Hair's bangs on the head they were made on: the command line moves the strands with the
// head (+X up, millimetres, centred), so each root stays where it was on the scalp.
TEST_F(CliPlacement, ImportedHairIsPlacedWithItsHead)
{
    const fs::path head = kAssets / "hair/ct2hair_bangs_head.ply", out = dir / "rest.txt";
    const CliRun run = cli("simulate --steps 0 --rest --head " + head.string() + " --hair "
        + (kAssets / "hair/ct2hair_bangs100.data").string() + " --out " + out.string());
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("strands placed with their head"), std::string::npos) << run.output;
    auto rest = io::readStrandText(out.string());
    ASSERT_TRUE(rest.ok()) << rest.error().toString();
    const HairCurves& grown = rest.value();
    ASSERT_EQ(grown.strandCount(), 100u);

    // Where the roots should be: the file's roots under the head's placement, computed here.
    auto mesh = io::readMesh(head.string());
    ASSERT_TRUE(mesh.ok());
    TriangleMesh placedHead = std::move(mesh).value().mesh;
    const io::HeadPlacement placement = io::placeHead(placedHead);
    const HairCurves file = readBangs();
    float worst = 0.0f;
    for (std::size_t s = 0; s < 100; ++s) {
        glm::vec3 root = file.positions[file.offsets[s]];
        io::applyPlacement(std::span<glm::vec3>(&root, 1), placement);
        worst = std::max(worst, glm::distance(root, grown.positions[grown.offsets[s]]));
    }
    EXPECT_LT(worst, 0.006f) << "each grown root within a few millimetres of its file root, placed";
}

// A .data groom in centimetres, with no head: its unit is found from its roots (not 22 m strands).
TEST_F(CliPlacement, AGroomInCentimetresIsScaledToMetres)
{
    HairCurves centimetres = readBangs();
    const float longestMm = longestStrand(centimetres);
    for (glm::vec3& p : centimetres.positions)
        p *= 0.1f;
    const fs::path data = dir / "bangs_cm.data", out = dir / "rest.txt";
    ASSERT_TRUE(io::writeHair(data.string(), centimetres));
    const CliRun run = cli("simulate --steps 0 --rest --hair " + data.string() + " --out " + out.string());
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("strands in centimetres"), std::string::npos) << run.output;
    auto rest = io::readStrandText(out.string());
    ASSERT_TRUE(rest.ok()) << rest.error().toString();
    const float longest = longestStrand(rest.value());
    EXPECT_NEAR(longest, longestMm * 0.001f, 0.01f) << "metres, as the millimetre file's " << longestMm << " mm";
    EXPECT_LT(longest, 0.3f);
}

// What placement decided goes to stdout, its warnings to stderr; --up and --z-up override the shape.
TEST_F(CliPlacement, SimulateSaysHowTheHeadWasPlacedAndWarns)
{
    const std::string head = (kAssets / "heads/cy_woman_head.ply").string();
    const CliRun found = cli("simulate --steps 0 --head " + head);
    ASSERT_EQ(found.status, 0) << found.output;
    EXPECT_NE(found.output.find("+Z up, face +X (from its shape)"), std::string::npos) << found.output;
    EXPECT_NE(found.output.find("warning: the skull is 64.7"), std::string::npos) << found.output;
    EXPECT_NE(found.output.find("scaled it to 0.16 m wide"), std::string::npos) << found.output;

    const CliRun chosen = cli("simulate --steps 0 --up +y --head " + head);
    ASSERT_EQ(chosen.status, 0) << chosen.output;
    EXPECT_NE(chosen.output.find("+Y up as chosen"), std::string::npos) << chosen.output;
    const CliRun zUp = cli("simulate --steps 0 --z-up --scale 0.0025 --head " + head);
    ASSERT_EQ(zUp.status, 0) << zUp.output;
    EXPECT_NE(zUp.output.find("+Z up as chosen"), std::string::npos) << zUp.output;
    EXPECT_NE(zUp.output.find("\u00D70.0025 (chosen scale), +Z up, face -Y"), std::string::npos) << zUp.output;

    const CliRun bad = cli("simulate --steps 0 --up w --head " + head);
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("--up: 'w' is no axis"), std::string::npos) << bad.output;
}
