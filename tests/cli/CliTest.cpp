// wisp-cli as a user runs it: real processes, exit statuses, messages and output files.
#include "io/StrandText.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/util/CpuName.h"
#include "sim/util/SimdTarget.h"

#include "CliRunner.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sys/wait.h>

namespace fs = std::filesystem;
using wisp::test::cli;
using wisp::test::CliRun;

namespace {

fs::path tempDir()
{
    fs::path dir = fs::temp_directory_path() / ("wisp-cli-test-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream(path) << text;
}

} // namespace

TEST(Cli, UsageAndHelp)
{
    EXPECT_EQ(cli("").status, 2);
    EXPECT_EQ(cli("--help").status, 0);
    const CliRun unknown = cli("frobnicate");
    EXPECT_EQ(unknown.status, 2);
    EXPECT_NE(unknown.output.find("unknown command"), std::string::npos);
    const CliRun help = cli("simulate --help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("--gravity"), std::string::npos);
    EXPECT_NE(help.output.find("m/s²"), std::string::npos);
    EXPECT_EQ(cli("bench --help").status, 0);
    EXPECT_NE(cli("bench --help").output.find("paper-35x35x30"), std::string::npos);
}

TEST(Cli, WrongUsageIsExitTwo)
{
    EXPECT_EQ(cli("simulate --bogus").status, 2);
    EXPECT_EQ(cli("simulate --steps").status, 2);
    EXPECT_EQ(cli("simulate stray").status, 2);
    EXPECT_EQ(cli("bench --json=yes").status, 2);
}

TEST(Cli, BadValuesAreExitOneNamingTheOption)
{
    const CliRun nan = cli("simulate --steps 1 --gravity nan");
    EXPECT_EQ(nan.status, 1);
    EXPECT_NE(nan.output.find("gravity"), std::string::npos);
    const CliRun segments = cli("simulate --steps 1 --segments 1");
    EXPECT_EQ(segments.status, 1);
    EXPECT_NE(segments.output.find("segments: 1 is outside 2..127"), std::string::npos);
    const CliRun length = cli("simulate --steps 1 --length 0");
    EXPECT_EQ(length.status, 1);
    EXPECT_NE(length.output.find("length"), std::string::npos);
    const CliRun steps = cli("simulate --steps many");
    EXPECT_EQ(steps.status, 1);
    EXPECT_NE(steps.output.find("--steps"), std::string::npos);
    EXPECT_EQ(cli("simulate --steps 1 --grid 10x10").status, 1);
    EXPECT_EQ(cli("bench --workload nope").status, 1);
}

// Every documented range end is accepted (real parameters are floats: 0.1f is above the double 0.1).
TEST(Cli, RangeEndsAreAccepted)
{
    for (const char* option : { "--time_step 0.1", "--time_step 0.001", "--curl_radius 0.05", "--length 0.005",
             "--length 2", "--hair_offset 0.02", "--substeps 32" }) {
        const CliRun run = cli(std::string("simulate --steps 1 --density 0.5 ") + option);
        EXPECT_EQ(run.status, 0) << option << ": " << run.output;
        EXPECT_EQ(run.output.find("outside"), std::string::npos) << option << ": " << run.output;
    }
}

TEST(Cli, WholeNumbersAndTogglesRefuseFractionsNamingThem)
{
    const CliRun substeps = cli("simulate --steps 1 --substeps 2.5");
    EXPECT_EQ(substeps.status, 1);
    EXPECT_NE(substeps.output.find("substeps: 2.5 is not a whole number"), std::string::npos) << substeps.output;
    const CliRun body = cli("simulate --steps 1 --body 0.5");
    EXPECT_EQ(body.status, 1);
    EXPECT_NE(body.output.find("body: 0.5 is not 0 or 1"), std::string::npos) << body.output;
    EXPECT_EQ(cli("simulate --steps 1 --body 2").status, 1);
    EXPECT_EQ(cli("simulate --steps 2 --density 0.5 --body 0").status, 0);
    EXPECT_EQ(cli("simulate --steps 2 --density 0.5 --body 1").status, 0);
    const CliRun help = cli("simulate --help");
    EXPECT_NE(help.output.find("--body 0|1"), std::string::npos);
}

TEST(Cli, BadFilesAreExitOneNamingTheFile)
{
    const fs::path dir = tempDir();
    const CliRun missing = cli("simulate --head " + (dir / "missing.obj").string());
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.output.find("missing.obj"), std::string::npos);

    writeText(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const CliRun noTriangles = cli("simulate --head " + (dir / "points.obj").string());
    EXPECT_EQ(noTriangles.status, 1);
    EXPECT_NE(noTriangles.output.find("points.obj"), std::string::npos);

    writeText(dir / "bad.params", "gravity = 9.8\nclump_degree = 3\n");
    const CliRun params = cli("simulate --steps 1 --params " + (dir / "bad.params").string());
    EXPECT_EQ(params.status, 1);
    EXPECT_NE(params.output.find("bad.params: line 2: clump_degree: 3 is outside -1..1"), std::string::npos);

    writeText(dir / "unknown.params", "gravity = 9.8\nwobble = 1\n");
    const CliRun unknown = cli("simulate --steps 1 --params " + (dir / "unknown.params").string());
    EXPECT_EQ(unknown.status, 1);
    EXPECT_NE(unknown.output.find("unknown parameter 'wobble'"), std::string::npos);

    const CliRun unwritable = cli("simulate --steps 1 --out /proc/no/such/dir/out.txt");
    EXPECT_EQ(unwritable.status, 1);
    EXPECT_NE(unwritable.output.find("out.txt"), std::string::npos);
    fs::remove_all(dir);
}

TEST(Cli, SimulateWritesEveryDrawnStrand)
{
    const fs::path dir = tempDir();
    const fs::path out = dir / "strands.txt";
    writeText(dir / "look.params", "# a test look\ndensity = 3\nwind_speed = 10\n");
    const CliRun r
        = cli("simulate --steps 30 --threads 2 --params " + (dir / "look.params").string() + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("ms per step"), std::string::npos);
    const auto curves = wisp::io::readStrandText(out.string());
    ASSERT_TRUE(curves.ok()) << curves.error().toString();
    EXPECT_GT(curves.value().strandCount(), 500u);
    EXPECT_EQ(curves.value().pointCount(), curves.value().strandCount() * 16); // 15 segments by default
    for (const glm::vec3& p : curves.value().positions)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));

    const CliRun keys = cli("simulate --steps 2 --density 3 --keys-only --out " + out.string());
    ASSERT_EQ(keys.status, 0) << keys.output;
    const auto keyCurves = wisp::io::readStrandText(out.string());
    ASSERT_TRUE(keyCurves.ok());
    EXPECT_LT(keyCurves.value().strandCount(), curves.value().strandCount() / 4); // wisps of 12
    fs::remove_all(dir);
}

TEST(Cli, SimulateReadsAHeadFromAFile)
{
    const fs::path dir = tempDir();
    const wisp::DefaultHead head = wisp::makeDefaultHead();
    {
        std::ofstream obj(dir / "head.obj");
        for (const glm::vec3& p : head.mesh.positions) // written in centimetres
            obj << "v " << p.x * 100 << " " << p.y * 100 << " " << p.z * 100 << "\n";
        for (const glm::uvec3& t : head.mesh.triangles)
            obj << "f " << t.x + 1 << " " << t.y + 1 << " " << t.z + 1 << "\n";
    }
    const CliRun r = cli("simulate --steps 5 --head " + (dir / "head.obj").string() + " --scale 0.01 --density 2 --out "
        + (dir / "s.txt").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const auto curves = wisp::io::readStrandText((dir / "s.txt").string());
    ASSERT_TRUE(curves.ok());
    EXPECT_GT(curves.value().strandCount(), 100u);
    fs::remove_all(dir);
}

TEST(Cli, GridReproducesThePapersParticleCount)
{
    const CliRun r = cli("simulate --steps 3 --grid 15x15x10");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("particles 2250"), std::string::npos) << r.output;
}

TEST(Cli, BenchPrintsJsonLines)
{
    const CliRun r = cli("bench --workload sphere --strands 200 --steps 50 --threads 2 --json");
    ASSERT_EQ(r.status, 0) << r.output;
    for (const char* field : { "\"name\": \"sphere\"", "\"particles\": 3000", "\"threads\": 2", "\"ms_per_step\"",
             "\"peak_rss_mb\"", "\"physics\": [\"capsules\"]" }) // (the sphere's collider; --without's test below)
        EXPECT_NE(r.output.find(field), std::string::npos) << field << " in " << r.output;
}

TEST(Cli, BenchNamesItsTargetAndMeasuresTheFloorBesideEachWorkload)
{
    const CliRun r = cli("bench --workload sphere --strands 200 --steps 50 --threads 2 --json");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string target = std::string("\"target\": \"") + wisp::solverSimdTarget() + "\"";
    EXPECT_NE(r.output.find("\"name\": \"sphere\", " + target), std::string::npos) << r.output;
    EXPECT_NE(
        r.output.find("\"name\": \"floor\", " + target + ", \"particles\": 3000, \"strands\": 200"), std::string::npos)
        << r.output;
    // The workload's ratio is its time over the floor's, both measured in this run.
    const std::regex row("\"name\": \"sphere\".*\"ms_per_step\": ([0-9.]+).*\"floor_ms_per_step\": ([0-9.]+), "
                         "\"ratio_to_floor\": ([0-9.]+)");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.output, m, row)) << r.output;
    const double ms = std::stod(m[1]), floorMs = std::stod(m[2]), ratio = std::stod(m[3]);
    ASSERT_GT(floorMs, 0.0);
    // (Up to the printing: times to 0.0001 ms, which is a few per cent of a floor of 0.003 ms, and
    // the ratio to 0.01.)
    const double printed = 0.00005;
    EXPECT_NEAR(ratio, ms / floorMs, 0.006 + ratio * (printed / floorMs + printed / ms));
    // Timed in turns with the workload, as many steps: the floor's row has no peak memory of its
    // own (the workload's is read before the floor's rows are made).
    EXPECT_NE(r.output.find("\"name\": \"floor\", " + target
                  + ", \"particles\": 3000, \"strands\": 200, "
                    "\"threads\": 2, \"substeps\": 1, \"steps\": 50,"),
        std::string::npos)
        << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("\"name\": \"sphere\".*\"peak_rss_mb\": [0-9]+\\.[0-9]\\}")))
        << r.output;
    EXPECT_TRUE(std::regex_search(r.output, std::regex("\"name\": \"floor\".*\"peak_rss_mb\": null\\}"))) << r.output;

    const CliRun table = cli("bench --workload sphere --strands 200 --steps 50 --threads 1");
    ASSERT_EQ(table.status, 0) << table.output;
    EXPECT_EQ(table.output.rfind(std::string("target ") + wisp::solverSimdTarget() + " (", 0), 0u) << table.output;
    EXPECT_NE(table.output.find("x floor"), std::string::npos) << table.output;
    // The machine, by its maker's name, on the second line and in every JSON row.
    EXPECT_NE(table.output.find("\ncpu " + wisp::cpuModelName() + ", "), std::string::npos) << table.output;
    EXPECT_NE(r.output.find("\"cpu\": \"" + wisp::cpuModelName() + "\""), std::string::npos) << r.output;
    EXPECT_NE(table.output.find("\nfloor "), std::string::npos) << table.output;
}

// --target runs the kernels on a lower target than the CPU's best, and says so in the table's first
// line and each JSON row; a target the binary or the CPU lacks is refused with the choices.
TEST(Cli, BenchRunsOnTheTargetItIsToldAndRefusesOneItLacks)
{
    for (const std::string& t : wisp::availableSimdTargets()) {
        const CliRun r = cli("bench --workload sphere --strands 200 --steps 50 --threads 1 --json --target " + t);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_NE(r.output.find("\"name\": \"sphere\", \"target\": \"" + t + "\""), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("\"name\": \"floor\", \"target\": \"" + t + "\""), std::string::npos) << r.output;
    }
#if defined(__x86_64__)
    const CliRun table = cli("bench --workload sphere --strands 200 --steps 50 --threads 1 --target sse4");
    ASSERT_EQ(table.status, 0) << table.output;
    EXPECT_EQ(table.output.rfind("target SSE4 (chosen at run time of ", 0), 0u) << table.output;
#endif
    const CliRun bad = cli("bench --workload sphere --strands 200 --steps 50 --target MMX");
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("--target: no SIMD target 'MMX'"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find(wisp::availableSimdTargets().front()), std::string::npos) << bad.output;
}

// --without runs the grid workloads without the physics it names, to see what each costs, and every
// JSON row lists the physics its solver stepped with, read from the solver (not from the options).
TEST(Cli, BenchRunsTheGridWorkloadsWithoutThePhysicsItIsToldAndListsWhatRan)
{
    const std::string grid = "bench --workload paper-15x15x10 --steps 50 --threads 1 --json";
    const CliRun all = cli(grid);
    ASSERT_EQ(all.status, 0) << all.output;
    EXPECT_NE(all.output.find("\"name\": \"paper-15x15x10\""), std::string::npos) << all.output;
    EXPECT_NE(all.output.find("\"physics\": [\"head-contact\", \"bending\", \"gusts\", \"volume\"]"), std::string::npos)
        << all.output;
    EXPECT_NE(all.output.find("\"name\": \"floor\""), std::string::npos) << all.output;
    EXPECT_TRUE(std::regex_search(all.output, std::regex("\"name\": \"floor\".*\"physics\": \\[\\]"))) << all.output;

    const CliRun limp = cli(grid + " --without bending");
    ASSERT_EQ(limp.status, 0) << limp.output;
    EXPECT_NE(limp.output.find("\"physics\": [\"head-contact\", \"gusts\", \"volume\"]"), std::string::npos)
        << limp.output;

    const CliRun bare = cli(grid + " --without 'head-contact, volume,gusts,bending,gusts'");
    ASSERT_EQ(bare.status, 0) << bare.output;
    EXPECT_TRUE(std::regex_search(bare.output, std::regex("\"name\": \"paper-15x15x10\".*\"physics\": \\[\\]")))
        << bare.output;
    // Without the volume the solver holds no grid: fewer bytes a particle.
    const std::regex bytes("\"name\": \"paper-15x15x10\".*\"solver_bytes_per_particle\": ([0-9.]+)");
    std::smatch withGrid, without;
    ASSERT_TRUE(std::regex_search(all.output, withGrid, bytes)) << all.output;
    ASSERT_TRUE(std::regex_search(bare.output, without, bytes)) << bare.output;
    EXPECT_LT(std::stod(without[1]), std::stod(withGrid[1]));

    const CliRun table = cli("bench --workload paper-15x15x10 --steps 50 --threads 1 --without gusts,head-contact");
    ASSERT_EQ(table.status, 0) << table.output;
    EXPECT_NE(table.output.find("\nthe grid workloads without gusts, head-contact\n"), std::string::npos)
        << table.output;
}

TEST(Cli, BenchRefusesAWithoutListItCannotRun)
{
    const CliRun unknown = cli("bench --workload paper-15x15x10 --steps 50 --without bending,magnetism");
    EXPECT_EQ(unknown.status, 1) << unknown.output;
    EXPECT_NE(unknown.output.find("--without: no physics 'magnetism' to turn off (there are: head-contact, bending, "
                                  "gusts, volume)"),
        std::string::npos)
        << unknown.output;
    for (const char* list : { "bending,", ",bending", "bending,,gusts", "''" }) {
        const CliRun empty = cli(std::string("bench --workload paper-15x15x10 --steps 50 --without ") + list);
        EXPECT_EQ(empty.status, 1) << list << ": " << empty.output;
        EXPECT_NE(empty.output.find("--without: expects physics names separated by commas, with none empty (there "
                                    "are: head-contact, bending, gusts, volume)"),
            std::string::npos)
            << list << ": " << empty.output;
    }
    const CliRun both = cli("bench --workload paper-15x15x10 --steps 50 --without volume --volume 0.3");
    EXPECT_EQ(both.status, 1) << both.output;
    EXPECT_NE(both.output.find("--without volume and --volume"), std::string::npos) << both.output;
    const CliRun sphere = cli("bench --workload sphere --strands 200 --steps 50 --without gusts");
    EXPECT_EQ(sphere.status, 1) << sphere.output;
    EXPECT_NE(sphere.output.find("--without is for the grid workloads"), std::string::npos) << sphere.output;
}

// simulate --target runs the solver on the target it is told, and every target writes the same
// file, byte for byte (the README's rule: the same bits on every target), wind and volume on.
TEST(Cli, SimulateOnEveryTargetWritesTheSameFile)
{
    const fs::path dir = tempDir();
    auto bytesOf = [](const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    };
    const std::string run = "simulate --steps 40 --threads 2 --wind_speed 6 --volume 0.5 --export ";
    const CliRun best = cli(run + (dir / "best.hair").string());
    ASSERT_EQ(best.status, 0) << best.output;
    const std::string expected = bytesOf(dir / "best.hair");
    ASSERT_GT(expected.size(), 10'000u);
    const std::vector<std::string> targets = wisp::availableSimdTargets();
    for (const std::string& t : targets) {
        const fs::path out = dir / (t + ".hair");
        const CliRun r = cli(run + out.string() + " --target " + t);
        ASSERT_EQ(r.status, 0) << r.output;
        EXPECT_TRUE(bytesOf(out) == expected) << t << " wrote other positions than the best target";
    }
    const CliRun bad = cli("simulate --steps 1 --target MMX --out " + (dir / "x.txt").string());
    EXPECT_EQ(bad.status, 1) << bad.output;
    EXPECT_NE(bad.output.find("--target: no SIMD target 'MMX'"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "x.txt"));
    fs::remove_all(dir);
}

TEST(Cli, BenchGivesNoFloorToTheBrushAndCombWorkloads)
{
    const CliRun r = cli("bench --workload brush-dab --steps 50 --threads 1 --json");
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("\"name\": \"brush-dab\""), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("\"name\": \"floor\""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"ratio_to_floor\": 0.00"), std::string::npos) << r.output;
}

TEST(Cli, ACpuWithoutTheBuildsInstructionsIsToldSoInsteadOfCrashing)
{
    // The refusal, as on a CPU without SSE2 (every build needs it; the test hook pretends).
    ::setenv("WISP_TEST_CPU_LACKS", "sse2", 1);
    const CliRun r = cli("--help");
    ::unsetenv("WISP_TEST_CPU_LACKS");
    EXPECT_EQ(r.status, 3) << r.output;
    EXPECT_NE(
        r.output.find("this build was compiled for instructions this CPU does not have: sse2."), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("-DWISP_NATIVE=OFF"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("usage:"), std::string::npos) << "it ran on: " << r.output;
    // The widest instruction set the build was compiled for, lacking alone, is named alone.
    const std::string widest = std::string(wisp::baselineSimdTarget()) == "AVX-512" ? "avx512f"
        : std::string(wisp::baselineSimdTarget()) == "AVX2"                         ? "avx2"
                                                                                    : "sse2";
    ::setenv("WISP_TEST_CPU_LACKS", widest.c_str(), 1);
    const CliRun wide = cli("--help");
    ::unsetenv("WISP_TEST_CPU_LACKS");
    EXPECT_EQ(wide.status, 3) << wide.output;
    EXPECT_NE(wide.output.find("does not have: " + widest + "."), std::string::npos) << wide.output;
    // And nothing is refused on the machine that built it.
    const CliRun here = cli("--help");
    EXPECT_EQ(here.status, 0) << here.output;
}
