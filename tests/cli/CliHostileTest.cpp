// wisp-cli against hostile input (issue 12), run as a user runs it. Every run goes through
// `timeout`, so a command that blocks (the FIFO) or loops fails its test with status 124 instead
// of hanging the suite; every hostile file is small and written here.
#include "io/HairFiles.h"

#include "CliRunner.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using wisp::test::CliRun;

namespace {

// Far above what any command here needs (the sanitizer build is ~10x slower); only a hang reaches it.
CliRun run(const std::string& arguments)
{
    return wisp::test::cli(arguments, 120);
}

class CliHostile : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir = fs::temp_directory_path()
            / ("wisp-cli-hostile-" + std::to_string(::getpid()) + "-"
                + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string write(const std::string& name, const std::string& text) const
    {
        const fs::path path = dir / name;
        fs::create_directories(path.parent_path());
        std::ofstream(path, std::ios::binary) << text;
        return path.string();
    }

    // A 20 x 20 grid 0.19 m across in x and y whose last row is lifted by a subnormal 1e-42 in z.
    std::string flatObj() const
    {
        std::string text;
        constexpr int n = 20;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                text += "v " + std::to_string(0.01 * i) + " " + std::to_string(0.01 * j)
                    + (i == n - 1 ? " 1e-42\n" : " 0\n");
        for (int i = 0; i + 1 < n; ++i)
            for (int j = 0; j + 1 < n; ++j) {
                const int a = i * n + j + 1, b = a + 1, c = a + n, d = c + 1;
                text += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + "\n";
                text += "f " + std::to_string(a) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
            }
        return write("flat.obj", text);
    }

    // A 0.3 m tetrahedron and one vertex 16,372 units away (the issue's STL, as OBJ).
    std::string strayVertexObj() const
    {
        return write("stray.obj",
            "v 0 0 0\nv 0.3 0 0\nv 0 0.3 0\nv 0 0 0.3\nv 16372 0 0\n"
            "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 2 5 3\n");
    }

    std::string tetraObj() const
    {
        return write("tetra.obj", "v 0 0 0\nv 0.2 0 0\nv 0 0.2 0\nv 0 0 0.2\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    }

    fs::path dir;
};

bool mentions(const CliRun& r, const std::string& text)
{
    return r.output.find(text) != std::string::npos;
}

} // namespace

// SIGSEGV (exit 139) in the BVH build on a nearly flat head; validate accepted it with exit 0.
TEST_F(CliHostile, FlatHeadIsRefusedByValidateAndSimulate)
{
    const std::string flat = flatObj();
    const CliRun validate = run("validate " + flat);
    EXPECT_EQ(validate.status, 1) << validate.output;
    EXPECT_TRUE(mentions(validate, "flat.obj: the placed head is 0.19 x 0.19 x 1.001e-42 m: flat along z"))
        << validate.output;
    const CliRun simulate = run("simulate --steps 2 --head " + flat);
    EXPECT_EQ(simulate.status, 1) << simulate.output;
    EXPECT_TRUE(mentions(simulate, "flat along z")) << simulate.output;
    EXPECT_FALSE(mentions(simulate, "strands ")) << "refused before grooming";
}

// One vertex far away made `simulate --steps 2` take 12-34 s and 266 MB.
TEST_F(CliHostile, StrayFarVertexIsRefusedBeforeGrooming)
{
    const std::string stray = strayVertexObj();
    const CliRun validate = run("validate " + stray);
    EXPECT_EQ(validate.status, 1) << validate.output;
    // Placed by its "skull" (the stray vertex makes it 16,372 units wide), the head is refused
    // before any groom is built, and the placement says why it looked wrong.
    EXPECT_TRUE(mentions(validate, "stray.obj: the placed head is")) << validate.output;
    EXPECT_TRUE(mentions(validate, "16372 units wide")) << validate.output;
    for (const std::string scale : { "", " --scale 1", " --scale 0.001" }) {
        const CliRun simulate = run("simulate --steps 2 --head " + stray + scale);
        EXPECT_EQ(simulate.status, 1) << scale << ": " << simulate.output;
        EXPECT_TRUE(mentions(simulate, "stray.obj: the placed head is")) << simulate.output;
        EXPECT_FALSE(mentions(simulate, "strands ")) << "refused before grooming";
    }
    // A usable head passes both, and validate says what simulate will grow.
    const CliRun good = run("validate " + tetraObj());
    EXPECT_EQ(good.status, 0) << good.output;
    EXPECT_TRUE(mentions(good, "default groom: ")) << good.output;
}

// A FIFO named x.json made validate block forever.
TEST_F(CliHostile, FifoIsRefusedWithoutBlocking)
{
    for (const std::string name : { "x.json", "x.obj", "x.hair", "x.wisp", "x.glb" }) {
        const fs::path fifo = dir / name;
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
        const CliRun r = run("validate " + fifo.string());
        EXPECT_EQ(r.status, 1) << name << ": " << r.output;
        EXPECT_TRUE(mentions(r, "a pipe (FIFO), not a regular file")) << r.output;
    }
}

// --params /dev/zero read 1 GB for 5 s and ran with defaults (exit 0); a folder ran with defaults.
TEST_F(CliHostile, ParamsMustBeARegularFile)
{
    const CliRun zero = run("simulate --steps 1 --params /dev/zero");
    EXPECT_EQ(zero.status, 1) << zero.output;
    EXPECT_TRUE(mentions(zero, "/dev/zero: this is a character device, not a regular file")) << zero.output;
    const CliRun folder = run("simulate --steps 1 --params " + dir.string());
    EXPECT_EQ(folder.status, 1) << folder.output;
    EXPECT_TRUE(mentions(folder, "this is a folder, not a parameter file")) << folder.output;
    const CliRun preset = run("simulate --steps 1 --preset /dev/zero");
    EXPECT_EQ(preset.status, 1) << preset.output;
}

// A typo in a bufferView key and a `true` byteOffset read the wrong bytes (then crashed the BVH);
// a buffer URI leaving the folder was embedded by convert --head.
TEST_F(CliHostile, GltfStructureAndUrisAreChecked)
{
    const std::string buffer = std::string(
        "\x00\x00\x02\x00\x01\x00\x00\x00\x01\x00\x03\x00\x00\x00\x03\x00\x02\x00\x01\x00\x02\x00\x03\x00", 24);
    std::string positions;
    for (const float f : { 0.0f, 0.0f, 0.0f, 0.2f, 0.0f, 0.0f, 0.0f, 0.2f, 0.0f, 0.0f, 0.0f, 0.2f })
        positions.append(reinterpret_cast<const char*>(&f), 4);
    write("secret.bin", buffer + positions);
    write("head/inside.bin", buffer + positions);
    const auto gltf = [&](const std::string& name, const std::string& offsetKey, const std::string& offsetValue,
                          const std::string& uri) {
        return write("head/" + name,
            R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":72,"uri":")" + uri + R"("}],
            "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":24},{"buffer":0,")"
                + offsetKey + "\":" + offsetValue + R"(,"byteLength":48}],
            "accessors":[{"bufferView":0,"componentType":5123,"count":12,"type":"SCALAR"},
                         {"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"}],
            "meshes":[{"primitives":[{"attributes":{"POSITION":1},"indices":0}]}],
            "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
    };
    const CliRun good = run("validate " + gltf("good.gltf", "byteOffset", "24", "inside.bin"));
    EXPECT_EQ(good.status, 0) << good.output;
    const CliRun typo = run("validate " + gltf("typo.gltf", "byteOffet", "24", "inside.bin"));
    EXPECT_EQ(typo.status, 1) << typo.output;
    EXPECT_TRUE(mentions(typo, "typo.gltf: bufferViews[1].byteOffet: unknown key (did you mean 'byteOffset'?)"))
        << typo.output;
    const CliRun boolean = run("validate " + gltf("bool.gltf", "byteOffset", "true", "inside.bin"));
    EXPECT_EQ(boolean.status, 1) << boolean.output;
    EXPECT_TRUE(mentions(boolean, "bufferViews[1].byteOffset: must be a whole number, not true")) << boolean.output;

    // convert --head with a glTF reading ../secret.bin: refused, and nothing is written.
    wisp::HairCurves strands;
    strands.addStrand(3);
    strands.positions = { { 0, 0.1f, 0 }, { 0, 0.05f, 0 }, { 0, 0, 0 } };
    ASSERT_TRUE(wisp::io::writeHair((dir / "s.hair").string(), strands));
    const fs::path out = dir / "out.glb";
    const CliRun escape = run("convert " + (dir / "s.hair").string() + " " + out.string() + " --head "
        + gltf("escape.gltf", "byteOffset", "24", "../secret.bin"));
    EXPECT_EQ(escape.status, 1) << escape.output;
    EXPECT_TRUE(mentions(escape, "buffers[0].uri: '../secret.bin' lies outside the glTF file's folder"))
        << escape.output;
    EXPECT_FALSE(fs::exists(out));
}

// A bad output path or extension was found only after the whole simulation.
TEST_F(CliHostile, OutputsAreCheckedBeforeAnyWork)
{
    // 10 million steps would run for hours: refusing before the first one is what ends it.
    const std::vector<std::pair<std::string, std::string>> cases = {
        { "--export " + (dir / "x.xyz").string(),
            "--export: " + (dir / "x.xyz").string() + ": '.xyz' is not a format Wisp writes" },
        { "--export " + (dir / "none/x.glb").string(), "the folder " + (dir / "none").string() + " does not exist" },
        { "--out " + (dir / "none/x.txt").string(), "--out: " + (dir / "none/x.txt").string() + ": the folder" },
        { "--out " + dir.string(), "this is a folder; give a file name" },
        { "--export " + (dir / "s.hair/x.glb").string(), "is not a folder" },
    };
    write("s.hair", "x");
    for (const auto& [option, message] : cases) {
        const CliRun r = run("simulate --steps 10000000 " + option);
        EXPECT_EQ(r.status, 1) << option << ": " << r.output;
        EXPECT_TRUE(mentions(r, message)) << r.output;
        EXPECT_FALSE(mentions(r, "strands ")) << "refused before grooming";
    }
    const CliRun convert = run("convert " + write("in.hair", "x") + " " + (dir / "none/out.hair").string());
    EXPECT_EQ(convert.status, 1) << convert.output;
    EXPECT_TRUE(mentions(convert, "OUT: " + (dir / "none/out.hair").string() + ": the folder")) << convert.output;
}

// No input makes wisp-cli exit with anything but 0, 1 or 2 (a crash is 128 + signal, a hang 124).
TEST_F(CliHostile, EveryHostileFileEndsWithStatusOneOrTwo)
{
    std::vector<std::string> files = { flatObj(), strayVertexObj(), write("empty.obj", ""),
        write("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        write("inf.off", "OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n"),
        write("huge.stl",
            "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e39 0 0\n"
            "vertex 0 1 0\nendloop\nendfacet\nendsolid\n"),
        write("garbage.glb", std::string("glTF\x02\0\0\0\x10\0\0\0", 12)), write("deep.gltf", std::string(100000, '[')),
        write("bad.json", "{\"format\": \"wisp-preset\", \"version\": [1]}"), write("bad.wisp", "{\"format\": 3}"),
        write("bad.hair", "HAIR"), write("bad.data", std::string(4, '\xff')) };
    for (const std::string& file : files) {
        const CliRun validate = run("validate " + file);
        EXPECT_EQ(validate.status, 1) << file << ": " << validate.output;
        EXPECT_TRUE(mentions(validate, fs::path(file).filename().string())) << validate.output;
        EXPECT_FALSE(mentions(validate, "[json.exception")) << validate.output;
    }
}

// Finite strands that overflow once scaled, or that lie nowhere near the head, ran with 0 strands
// and exit 0.
TEST_F(CliHostile, HairThatCannotBeUsedIsRefused)
{
    wisp::HairCurves strands;
    strands.addStrand(3);
    strands.positions = { { 0, 0.1f, 0 }, { 0, 0.05f, 0 }, { 3e37f, 0, 0 } };
    const std::string huge = (dir / "huge.data").string();
    ASSERT_TRUE(wisp::io::writeHair(huge, strands));
    const CliRun scaled = run("simulate --steps 1 --hair " + huge + " --hair-scale 100");
    EXPECT_EQ(scaled.status, 1) << scaled.output;
    EXPECT_TRUE(mentions(scaled, "huge.data: point 2 is not finite once placed")) << scaled.output;
    strands.positions = { { 1e30f, 0, 0 }, { 1e30f, 1, 0 }, { 1e30f, 2, 0 } };
    ASSERT_TRUE(wisp::io::writeHair(huge, strands));
    const CliRun far = run("simulate --steps 1 --hair " + huge);
    EXPECT_EQ(far.status, 1) << far.output;
    EXPECT_TRUE(mentions(far, "huge.data: point 0 lies 1e+30 m from the head, more than 10 m")) << far.output;
}
