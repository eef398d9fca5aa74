// Mesh reading: missing, broken, cut and corrupted files are refused with a clear message, never a crash.
#include "MeshReaderTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::mesh;

// ---- refusals -----------------------------------------------------------------------------------

TEST_F(MeshReaderFiles, MissingUnreadableAndUnknownFiles)
{
    const std::string missing = (m_dir / "nowhere.obj").string();
    auto r = readMesh(missing);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().toString().find(missing), std::string::npos);
    EXPECT_NE(r.error().message.find("does not exist"), std::string::npos) << r.error().toString();

    fs::create_directories(m_dir / "folder.ply");
    r = readMesh((m_dir / "folder.ply").string());
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("folder"), std::string::npos) << r.error().toString();

    std::string text = expectError("head.fbx", "whatever");
    for (const char* ext : { ".obj", ".ply", ".off", ".stl" })
        EXPECT_NE(text.find(ext), std::string::npos) << "the message should list " << ext << ": " << text;
    text = expectError("head", "v 0 0 0\n");
    EXPECT_NE(text.find("no extension"), std::string::npos) << text;

    for (const char* name : { "empty.obj", "empty.ply", "empty.off", "empty.stl" }) {
        text = expectError(name, "");
        EXPECT_NE(text.find("empty (0 bytes)"), std::string::npos) << text;
    }
}

TEST_F(MeshReaderFiles, ObjWithoutSurfaceOrWithBadNumbersIsRefused)
{
    std::string text = expectError("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_NE(text.find("no faces"), std::string::npos) << text;
    text = expectError("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2 3\np 1\n");
    EXPECT_NE(text.find("1 line"), std::string::npos) << text;
    text = expectError("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(text.find("line 2"), std::string::npos) << text;
    EXPECT_NE(text.find("finite"), std::string::npos) << text;
    text = expectError("huge.obj", "v 0 0 0\nv 1 1e39 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(text.find("line 2"), std::string::npos) << text;
    text = expectError("word.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(text.find("'abc' is not a number"), std::string::npos) << text;
    text = expectError("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    EXPECT_NE(text.find("line 4: a face refers to vertex 4, but the file has 3 vertices"), std::string::npos) << text;
    text = expectError("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    EXPECT_NE(text.find("from 1"), std::string::npos) << text;
    text = expectError("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n");
    EXPECT_NE(text.find("line 3"), std::string::npos) << text;
    text = expectError("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    EXPECT_NE(text.find("zero area"), std::string::npos) << text;
}

TEST_F(MeshReaderFiles, BrokenPlyIsRefusedBeforeAllocating)
{
    PlyOptions binary;
    const std::string good = cubePly(binary);
    std::string text = expectError("truncated.ply", good.substr(0, good.size() - 10));
    EXPECT_NE(text.find("truncated"), std::string::npos) << text;
    EXPECT_NE(text.find("face"), std::string::npos) << text;

    // Four billion vertices promised by a 200-byte file: refused from the header alone.
    std::string huge = good;
    huge.replace(huge.find("element vertex 8"), 16, "element vertex 4000000000");
    text = expectError("huge_count.ply", huge); // the message names the header's count: no stopwatch needed
    EXPECT_NE(text.find("4000000000"), std::string::npos) << text;
    huge = good;
    huge.replace(huge.find("element face 6"), 14, "element face 900000000000");
    text = expectError("huge_faces.ply", huge);
    EXPECT_NE(text.find("header"), std::string::npos) << text;

    // A list length of 2^32 - 1 inside the data.
    PlyOptions uintLists;
    uintLists.countType = "uint";
    std::string longList = cubePly(uintLists);
    const std::size_t faces = longList.find("end_header\n") + 11 + 8 * 12;
    longList.replace(faces, 4, std::string(4, '\xff'));
    text = expectError("long_list.ply", longList);
    EXPECT_NE(text.find("4294967295"), std::string::npos) << text;

    std::string outOfRange = cubePly(binary);
    outOfRange.replace(outOfRange.find("end_header\n") + 11 + 8 * 12 + 1, 4, std::string("\x09\0\0\0", 4));
    text = expectError("out_of_range.ply", outOfRange);
    EXPECT_NE(text.find("refers to vertex 9, but the file has 8 vertices"), std::string::npos) << text;

    std::string notFinite = cubePly(binary);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    notFinite.replace(
        notFinite.find("end_header\n") + 11 + 12 * 3 + 4, 4, std::string(reinterpret_cast<const char*>(&nan), 4));
    text = expectError("nan.ply", notFinite);
    EXPECT_NE(text.find("vertex 3 has a non-finite coordinate"), std::string::npos) << text;

    PlyOptions ascii;
    ascii.format = "ascii";
    std::string asciiText = cubePly(ascii);
    asciiText.replace(asciiText.find("\n4 ") + 1, 1, "x");
    text = expectError("ascii_word.ply", asciiText);
    EXPECT_NE(text.find("'x' is not a whole number"), std::string::npos) << text;
    EXPECT_NE(text.find("line 19"), std::string::npos) << text; // 10 header lines, 8 vertices, then the first face

    text = expectError("no_end.ply", good.substr(0, good.find("end_header")));
    EXPECT_NE(text.find("no 'end_header' line"), std::string::npos) << text;
    std::string misspelt = good;
    misspelt.replace(misspelt.find("end_header"), 10, "end_headrr");
    text = expectError("misspelt.ply", misspelt);
    EXPECT_NE(text.find("line 10: unexpected header line 'end_headrr'"), std::string::npos) << text;
    text = expectError("not_ply.ply", "solid cube\nfacet normal 0 0 1\n");
    EXPECT_NE(text.find("not a PLY file"), std::string::npos) << text;
    text = expectError(
        "only_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n");
    EXPECT_NE(text.find("x, y or z"), std::string::npos) << text;
    text = expectError("points.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "end_header\n0 0 0\n1 0 0\n0 1 0\n");
    EXPECT_NE(text.find("no triangles"), std::string::npos) << text;
    text = expectError("bad_strip.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
        "4 0 1 -2 2\n");
    EXPECT_NE(text.find("refers to vertex -2"), std::string::npos) << text;
}

TEST_F(MeshReaderFiles, BrokenOffIsRefused)
{
    const std::string good = cubeOff();
    std::string text = expectError("truncated.off", good.substr(0, good.find("4 0 3")));
    EXPECT_NE(text.find("ends after 0 of 6 faces"), std::string::npos) << text;
    text = expectError("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
    EXPECT_NE(text.find("line 6"), std::string::npos) << text;
    EXPECT_NE(text.find("vertex 3"), std::string::npos) << text;
    text = expectError("counts.off", "OFF\n3000000000 1 0\n0 0 0\n");
    EXPECT_NE(text.find("truncated"), std::string::npos) << text;
    text = expectError("corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n");
    EXPECT_NE(text.find("corners"), std::string::npos) << text;
    text = expectError("negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 1 2\n");
    EXPECT_NE(text.find("line 6"), std::string::npos) << text;
    text = expectError("binary.off", "OFF BINARY\n\0\0\0\3");
    EXPECT_NE(text.find("binary OFF"), std::string::npos) << text;
    text = expectError("inf.off", "OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n");
    EXPECT_NE(text.find("non-finite"), std::string::npos) << text;
    text = expectError("notoff.off", "ply\n");
    EXPECT_NE(text.find("not an OFF file"), std::string::npos) << text;
}

TEST_F(MeshReaderFiles, BrokenStlIsRefused)
{
    const std::string binary = cubeStlBinary();
    std::string text = expectError("truncated.stl", binary.substr(0, binary.size() - 7));
    EXPECT_NE(text.find("truncated"), std::string::npos) << text;
    text = expectError("short.stl", binary.substr(0, 40));
    EXPECT_NE(text.find("too short"), std::string::npos) << text;

    std::string nanStl = binary;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    nanStl.replace(84 + 50 * 5 + 12 + 4, 4, std::string(reinterpret_cast<const char*>(&nan), 4));
    text = expectError("nan.stl", nanStl);
    EXPECT_NE(text.find("triangle 5 has a non-finite coordinate"), std::string::npos) << text;

    std::string ascii = cubeStlAscii();
    ascii.replace(ascii.find("vertex ") + 7, 8, "nan");
    text = expectError("nan_ascii.stl", ascii);
    EXPECT_NE(text.find("line 4"), std::string::npos) << text;

    text = expectError("words.stl", "solid nothing\nendsolid nothing\n");
    EXPECT_NE(text.find("no triangles"), std::string::npos) << text;
    text = expectError("cut.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n");
    EXPECT_NE(text.find("ends inside a facet"), std::string::npos) << text;
}

// Every prefix of every generated file, and a few hundred corrupted copies, must give a mesh or
// an error: never a crash, a hang or an exception.
TEST_F(MeshReaderFiles, CutAndCorruptedFilesNeverCrash)
{
    PlyOptions ascii;
    ascii.format = "ascii";
    PlyOptions bigEndian;
    bigEndian.format = "binary_big_endian";
    bigEndian.extraAfter = true;
    const std::vector<std::pair<std::string, std::string>> files = { { "f.ply", cubePly() },
        { "f.ply", cubePly(ascii) }, { "f.ply", cubePly(bigEndian) }, { "f.obj", cubeObj() }, { "f.off", cubeOff() },
        { "f.stl", cubeStlAscii() }, { "f.stl", cubeStlBinary() } };
    std::mt19937 random(1234);
    std::size_t reads = 0;
    testing::internal::CaptureStderr();
    for (const auto& [name, bytes] : files) {
        for (std::size_t cut = 0; cut < bytes.size(); cut += 1 + bytes.size() / 300) {
            const auto r = readMesh(write(name, bytes.substr(0, cut)));
            ++reads;
            if (!r.ok()) {
                EXPECT_NE(r.error().toString().find(name), std::string::npos);
            }
        }
        for (int trial = 0; trial < 100; ++trial) {
            std::string corrupt = bytes;
            const int flips = 1 + static_cast<int>(random() % 4);
            for (int k = 0; k < flips; ++k)
                corrupt[random() % corrupt.size()] = static_cast<char>(random() % 256);
            const auto r = readMesh(write(name, corrupt));
            ++reads;
            if (r.ok()) {
                EXPECT_EQ(validateMesh(r.value().mesh), "");
            } else {
                EXPECT_NE(r.error().toString().find(name), std::string::npos);
            }
        }
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    std::cout << "[ fuzz     ] " << reads << " cut or corrupted files read without a crash\n";
}
