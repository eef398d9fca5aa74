// wisp-cli bake as a render farm runs it: a .hair sequence or a .usda, deterministic bytes, a
// part of a range equal to the same frames of the whole, the project's motion and timeline, and
// clear refusals (exit status 1 for bad values, 2 for wrong usage).
#include "io/HairFiles.h"
#include "io/ProjectFile.h"
#include "sim/geometry/DefaultHead.h"

#include "CliRunner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace fs = std::filesystem;
using wisp::test::cli;
using wisp::test::CliRun;

namespace {

std::string bytesOf(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

class CliBake : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path()
            / ("wisp-cli-bake-" + std::to_string(::getpid()) + "-"
                + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string at(const std::string& name) const { return (dir / name).string(); }
    fs::path dir;
};

} // namespace

TEST_F(CliBake, HairSequenceFramesMoveAndAPartOfTheRangeIsByteIdentical)
{
    const CliRun whole = cli("bake --frames 2:4 --motion nod --no-drape --threads 1 --out " + at("a.####.hair"), 300);
    ASSERT_EQ(whole.status, 0) << whole.output;
    EXPECT_NE(whole.output.find("wisp-cli bake: frame 4 of 4 (100 %)"), std::string::npos) << whole.output;
    EXPECT_NE(whole.output.find("baked frames 2:4 at 24 fps (3 steps"), std::string::npos) << whole.output;
    EXPECT_FALSE(fs::exists(at("a.0001.hair")));
    std::vector<wisp::HairCurves> frames;
    for (const char* name : { "a.0002.hair", "a.0003.hair", "a.0004.hair" }) {
        auto read = wisp::io::readHair(at(name));
        ASSERT_TRUE(read) << read.error().toString();
        frames.push_back(read.value().strands);
    }
    ASSERT_EQ(frames[0].pointCount(), frames[2].pointCount());
    ASSERT_GT(frames[0].strandCount(), 1000u);
    double travel = 0.0;
    for (std::size_t s = 0; s < frames[0].strandCount(); ++s) {
        const std::size_t tip = frames[0].offsets[s + 1] - 1;
        travel += glm::distance(frames[0].positions[tip], frames[2].positions[tip]);
    }
    EXPECT_GT(travel / static_cast<double>(frames[0].strandCount()), 1e-3) << "the tips should move between frames";

    // Frame 4 alone (another thread count) is the same file.
    const CliRun part = cli("bake --frames 4:4 --motion nod --no-drape --threads 2 --out " + at("b.##.hair"), 300);
    ASSERT_EQ(part.status, 0) << part.output;
    EXPECT_EQ(bytesOf(at("b.04.hair")), bytesOf(at("a.0004.hair")));
}

TEST_F(CliBake, UsdaHoldsOneSamplePerFrameWithCountsMatchingThePoints)
{
    const CliRun run = cli("bake --frames 1:3 --fps 30 --motion turn --no-drape --out " + at("c.usda"), 300);
    ASSERT_EQ(run.status, 0) << run.output;
    const std::string text = bytesOf(at("c.usda"));
    EXPECT_NE(text.find("timeCodesPerSecond = 30\n"), std::string::npos);
    EXPECT_NE(text.find("\n            1: [("), std::string::npos);
    EXPECT_NE(text.find("\n            3: [("), std::string::npos);
    EXPECT_EQ(text.find("\n            4: [("), std::string::npos);
    EXPECT_NE(text.find("def Mesh \"mesh\""), std::string::npos);
    // The counts add up to the points of a sample.
    const std::size_t counts = text.find("int[] curveVertexCounts = [");
    ASSERT_NE(counts, std::string::npos);
    std::size_t sum = 0, curves = 0;
    for (std::size_t i = counts + 27; text[i] != ']'; ++curves) {
        std::size_t used = 0;
        sum += std::stoul(text.substr(i), &used);
        i += used;
        if (text[i] == ',')
            i += 2;
    }
    const std::size_t sample = text.find("\n            2: [");
    const std::size_t end = text.find(']', sample + 17);
    std::size_t points = 0;
    for (std::size_t i = sample; i < end; ++i)
        points += text[i] == '(';
    EXPECT_EQ(points, sum);
    EXPECT_GT(curves, 1000u);
}

TEST_F(CliBake, TheProjectsMotionAndTimelineAreBaked)
{
    wisp::io::Project project;
    const wisp::DefaultHead head = wisp::makeDefaultHead();
    project.head = head.mesh;
    wisp::GrowthRegion region;
    region.name = "Scalp";
    region.weights = head.growthWeights;
    project.regions.push_back(region);
    project.motion.setKey(0.0, {});
    project.motion.setKey(0.1, { glm::vec3(0.0f), glm::angleAxis(0.5f, glm::vec3(0, 1, 0)) });
    project.timeline = { 1, 3, 20.0 };
    ASSERT_TRUE(wisp::io::writeProject(at("p.wisp"), project));
    const CliRun run = cli("bake " + at("p.wisp") + " --no-drape --out " + at("p.#.hair"), 300);
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("baked frames 1:3 at 20 fps"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("2 keys"), std::string::npos) << run.output;
    EXPECT_TRUE(fs::exists(at("p.3.hair")));
    EXPECT_FALSE(fs::exists(at("p.4.hair")));
}

TEST_F(CliBake, BadValuesAndUsageAreRefusedClearly)
{
    struct Case {
        std::string arguments;
        int status;
        std::string message;
    };
    const std::vector<Case> cases = {
        { "bake --frames 5:2 --out " + at("x.usda"), 1,
            "--frames/--fps: frames 5:2: the last frame comes before the first" },
        { "bake --frames 1:2 --fps 0 --out " + at("x.usda"), 1, "fps 0 is outside 1..1000" },
        { "bake --frames one --out " + at("x.usda"), 1, "--frames: 'one' is not A:B (e.g. 1:48)" },
        { "bake --frames 1:2 --motion spin --out " + at("x.usda"), 1,
            "--motion: 'spin' is not turn, nod, shake, walk or none" },
        { "bake --frames 1:2 --motion nod --amplitude 400 --out " + at("x.usda"), 1,
            "--motion nod: amplitude 400 is outside 0..90 degrees" },
        { "bake --frames 1:2 --motion walk --frequency 11 --out " + at("x.usda"), 1,
            "--motion walk: frequency 11 is outside 0.01..10 Hz" },
        { "bake --help", 0, "the motion's frequency, cycles per second, 0.01..10 Hz" },
        { "bake --frames 1:2 --out " + at("x.obj"), 1, "'.obj' is not a format Wisp writes" },
        { "bake --frames 1:2 --out " + at("x.hair"), 1, "a .hair sequence needs # in the file name" },
        { "bake --frames 1:2 --out " + at("no/x.usda"), 1, "does not exist" },
        { "bake --frames 1:2", 2, "needs --out FILE.usda or --out PATTERN.hair" },
        { "bake --out " + at("x.usda"), 2, "needs --frames A:B" },
        { "bake --frames 1:5000 --memory-mib 1 --out " + at("x.usda"), 1,
            "more than the bake's memory bound of 1.0 MiB; bake fewer frames, or export a .hair sequence" },
        { "bake " + at("missing.wisp") + " --frames 1:2 --out " + at("x.usda"), 1, "missing.wisp" },
    };
    for (const Case& c : cases) {
        const CliRun r = cli(c.arguments, 120);
        EXPECT_EQ(r.status, c.status) << c.arguments << "\n" << r.output;
        EXPECT_NE(r.output.find(c.message), std::string::npos) << c.arguments << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(at("x.usda")));
}

TEST_F(CliBake, ConvertReadsBackTheGltfGlbAndObjStrandsWispWrites)
{
    ASSERT_EQ(cli("bake --frames 1:1 --no-drape --density 1 --out " + at("s.#.hair"), 300).status, 0);
    const std::string original = bytesOf(at("s.1.hair"));
    for (const char* ext : { "gltf", "glb", "obj" }) {
        SCOPED_TRACE(ext);
        const std::string there = at(std::string("s.") + ext), back = at(std::string("back-") + ext + ".hair");
        const CliRun out = cli("convert " + at("s.1.hair") + " " + there);
        ASSERT_EQ(out.status, 0) << out.output;
        const CliRun in = cli("convert " + there + " " + back);
        ASSERT_EQ(in.status, 0) << in.output;
        EXPECT_EQ(bytesOf(back), original) << "float32 survives the round trip exactly";
    }
    std::ofstream(at("broken.obj")) << "v 0 0 0\nl 1 2\n";
    const CliRun broken = cli("convert " + at("broken.obj") + " " + at("x.hair"));
    EXPECT_EQ(broken.status, 1);
    EXPECT_NE(
        broken.output.find(at("broken.obj") + ": line 2: vertex 2 does not exist (the file has 1)"), std::string::npos)
        << broken.output;
}
