// Every reader in io/ reads regular files only, with a size cap (io/RegularFile.h): a FIFO named
// like a head used to block `wisp-cli validate` forever, and `--params /dev/zero` read 1 GB and
// then ran with defaults. Each reader is asked for a FIFO, a character device and a folder.
#include "IoTestSupport.h"

#include "io/GltfReader.h"
#include "io/HairFiles.h"
#include "io/MeshReader.h"
#include "io/ParameterText.h"
#include "io/PresetFile.h"
#include "io/ProjectFile.h"
#include "io/RegularFile.h"
#include "io/StrandText.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>

namespace wisp::io {
namespace {

namespace fs = std::filesystem;
using test::freshTestFolder;

// Each reader's error for `path`, or "" when it accepted the file.
std::string errorOf(const std::string& reader, const std::string& path)
{
    const std::map<std::string, std::function<std::string()>> readers = {
        { "mesh",
            [&] {
                auto r = readMesh(path);
                return r ? std::string() : r.error().toString();
            } },
        { "gltf",
            [&] {
                auto r = readGltf(path);
                return r ? std::string() : r.error().toString();
            } },
        { "hair",
            [&] {
                auto r = readHair(path);
                return r ? std::string() : r.error().toString();
            } },
        { "preset",
            [&] {
                auto r = readPreset(path);
                return r ? std::string() : r.error().toString();
            } },
        { "project",
            [&] {
                auto r = readProject(path);
                return r ? std::string() : r.error().toString();
            } },
        { "params",
            [&] {
                auto r = readParameterText(path);
                return r ? std::string() : r.error().toString();
            } },
        { "strands",
            [&] {
                auto r = readStrandText(path);
                return r ? std::string() : r.error().toString();
            } },
    };
    return readers.at(reader)();
}

const char* const kReaders[] = { "mesh", "gltf", "hair", "preset", "project", "params", "strands" };

// The extension each reader dispatches on, so that the FIFO's name is what an artist would type.
std::string nameFor(const std::string& reader)
{
    if (reader == "mesh")
        return "head.obj";
    if (reader == "gltf")
        return "head.gltf";
    if (reader == "hair")
        return "hair.hair";
    if (reader == "project")
        return "p.wisp";
    if (reader == "params")
        return "p.txt";
    if (reader == "strands")
        return "s.txt";
    return "x.json";
}

TEST(SpecialFiles, EveryReaderRefusesAFifoWithoutBlocking)
{
    const fs::path dir = freshTestFolder("wisp-fifo");
    for (const std::string reader : kReaders) {
        const fs::path fifo = dir / nameFor(reader);
        ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << fifo;
        // No writer ever opens the FIFO: a blocking open or read would hang this test.
        const std::string error = errorOf(reader, fifo.string());
        EXPECT_NE(error.find("a pipe (FIFO), not a regular file"), std::string::npos) << reader << ": " << error;
        EXPECT_EQ(error.rfind(fifo.string(), 0), 0u) << reader << ": " << error;
    }
    fs::remove_all(dir);
}

TEST(SpecialFiles, EveryReaderRefusesACharacterDeviceAndAFolder)
{
    ASSERT_TRUE(fs::exists("/dev/zero"));
    const fs::path dir = freshTestFolder("wisp-special");
    for (const std::string reader : kReaders) {
        // /dev/zero under the name an artist would give (readers pick the format by extension).
        const fs::path zero = dir / ("zero-" + nameFor(reader));
        fs::create_symlink("/dev/zero", zero);
        const std::string device = errorOf(reader, zero.string());
        EXPECT_NE(device.find("a character device, not a regular file"), std::string::npos) << reader << ": " << device;
        const fs::path folder = dir / nameFor(reader);
        fs::create_directories(folder);
        const std::string asFolder = errorOf(reader, folder.string());
        EXPECT_NE(asFolder.find("this is a folder"), std::string::npos) << reader << ": " << asFolder;
        const std::string missing = errorOf(reader, (dir / ("missing-" + nameFor(reader))).string());
        EXPECT_NE(missing.find("the file does not exist"), std::string::npos) << reader << ": " << missing;
    }
    fs::remove_all(dir);
}

TEST(SpecialFiles, SizeCapIsCheckedBeforeReading)
{
    const fs::path dir = freshTestFolder("wisp-cap");
    const fs::path big = dir / "params.txt";
    {
        std::ofstream out(big);
        out << "# padding\n";
    }
    fs::resize_file(big, kMaxTextFileBytes + 1); // sparse: costs no disk
    const std::string error = errorOf("params", big.string());
    EXPECT_NE(error.find("a parameter file is at most 1 MB"), std::string::npos) << error;
    const Result<std::string> within = readRegularFile(big.string(), { kMaxTextFileBytes + 1, "test", false });
    ASSERT_TRUE(within) << within.error().toString();
    EXPECT_EQ(within.value().size(), kMaxTextFileBytes + 1);
    fs::remove_all(dir);
}

// OpenMesh opened an OBJ's material library by the name the file gives: a FIFO beside the file
// blocked the reader forever. No material library is opened now.
TEST(SpecialFiles, ObjMaterialLibraryIsNeverOpened)
{
    const fs::path dir = freshTestFolder("wisp-mtllib");
    ASSERT_EQ(::mkfifo((dir / "skin.mtl").c_str(), 0600), 0);
    const fs::path obj = dir / "head.obj";
    std::ofstream(obj) << "mtllib skin.mtl\nusemtl skin\nv 0 0 0\nv 0.2 0 0\nv 0 0.2 0\nv 0 0 0.2\n"
                          "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const Result<MeshReadResult> read = readMesh(obj.string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().mesh.triangleCount(), 4u);
    const std::vector<std::string>& warnings = read.value().warnings;
    EXPECT_NE(
        std::find(warnings.begin(), warnings.end(), "ignored the material library 'skin.mtl': Wisp reads no materials"),
        warnings.end());
    fs::remove_all(dir);
}

} // namespace
} // namespace wisp::io
