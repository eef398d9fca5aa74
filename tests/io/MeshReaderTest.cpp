#include "io/MeshReader.h"
#include "IoTestSupport.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

using namespace wisp;
using namespace wisp::io;
namespace fs = std::filesystem;
using wisp::test::assetPath;
using wisp::test::slurp;

namespace {

// Reads vertex `i` straight from a little-endian binary PLY whose vertex element comes first
// and starts with float x, y, z: an independent check of what readMesh returned.
glm::vec3 rawPlyVertex(const std::string& bytes, std::size_t stride, std::size_t i)
{
    const std::size_t data = bytes.find("end_header\n") + std::strlen("end_header\n");
    float xyz[3];
    std::memcpy(xyz, bytes.data() + data + i * stride, sizeof xyz);
    return { xyz[0], xyz[1], xyz[2] };
}

// Six times the enclosed volume's sign-carrying sum: positive when triangles wind
// counter-clockwise seen from outside.
double signedVolume(const TriangleMesh& mesh)
{
    double v = 0.0;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        v += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    return v;
}

// ---- generated files ------------------------------------------------------------------------------

// Unit cube as six quads, counter-clockwise seen from outside.
const std::vector<glm::vec3> kCubeVertices
    = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
const std::vector<std::vector<int>> kCubeQuads
    = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 3, 7, 6, 2 }, { 0, 4, 7, 3 }, { 1, 2, 6, 5 } };

std::string cubeObj(const std::string& eol = "\n")
{
    std::string s = "# cube with quads" + eol + "o cube" + eol;
    for (const glm::vec3& v : kCubeVertices)
        s += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + eol;
    s += "vt 0 0" + eol + "vn 0 0 1" + eol;
    for (const auto& q : kCubeQuads) {
        s.push_back('f');
        for (int i : q)
            s += ' ' + std::to_string(i + 1) + "/1/1";
        s += eol;
    }
    return s;
}

std::string cubeOff()
{
    std::string s = "OFF\n# a comment before the counts\n8 6 12\n";
    for (const glm::vec3& v : kCubeVertices)
        s += std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "  # corner\n";
    for (const auto& q : kCubeQuads) {
        s.push_back('4');
        for (int i : q)
            s += ' ' + std::to_string(i);
        s += "\n";
    }
    return s;
}

std::vector<std::array<glm::vec3, 3>> cubeTriangles()
{
    std::vector<std::array<glm::vec3, 3>> tris;
    for (const auto& q : kCubeQuads) {
        tris.push_back({ kCubeVertices[q[0]], kCubeVertices[q[1]], kCubeVertices[q[2]] });
        tris.push_back({ kCubeVertices[q[0]], kCubeVertices[q[2]], kCubeVertices[q[3]] });
    }
    return tris;
}

std::string cubeStlAscii()
{
    std::string s = "solid cube\n";
    for (const auto& t : cubeTriangles()) {
        const glm::vec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
        s += "  facet normal " + std::to_string(n.x) + " " + std::to_string(n.y) + " " + std::to_string(n.z) + "\n";
        s += "    outer loop\n";
        for (const glm::vec3& v : t)
            s += "      vertex " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n";
        s += "    endloop\n  endfacet\n";
    }
    return s + "endsolid cube\n";
}

template <typename T> void append(std::string& s, T value, bool bigEndian = false)
{
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian)
        std::reverse(raw, raw + sizeof(T));
    s.append(raw, sizeof(T));
}

std::string cubeStlBinary()
{
    std::string s(80, ' ');
    s.replace(0, 12, "binary cube!");
    const auto tris = cubeTriangles();
    append<std::uint32_t>(s, static_cast<std::uint32_t>(tris.size()));
    for (const auto& t : tris) {
        const glm::vec3 n = glm::normalize(glm::cross(t[1] - t[0], t[2] - t[0]));
        for (float f : { n.x, n.y, n.z })
            append(s, f);
        for (const glm::vec3& v : t)
            for (float f : { v.x, v.y, v.z })
                append(s, f);
        append<std::uint16_t>(s, 0);
    }
    return s;
}

struct PlyOptions {
    std::string format = "binary_little_endian"; // or ascii, binary_big_endian
    bool extraBefore = false; // a double before x
    bool extraAfter = false; // double s, t and uchar r after z
    bool doubleCoordinates = false;
    std::string countType = "uchar";
    std::string indexType = "int";
    bool faceFirst = false;
    bool edgeElement = false; // an element that is not a surface
};

template <typename T> void appendScalar(std::string& s, const PlyOptions& o, T value)
{
    if (o.format == "ascii")
        s += std::to_string(value) + " ";
    else
        append(s, value, o.format == "binary_big_endian");
}

void appendTyped(std::string& s, const PlyOptions& o, const std::string& type, long long value)
{
    if (type == "uchar")
        appendScalar<std::uint8_t>(s, o, static_cast<std::uint8_t>(value));
    else if (type == "ushort")
        appendScalar<std::uint16_t>(s, o, static_cast<std::uint16_t>(value));
    else if (type == "uint")
        appendScalar<std::uint32_t>(s, o, static_cast<std::uint32_t>(value));
    else
        appendScalar<std::int32_t>(s, o, static_cast<std::int32_t>(value));
}

std::string cubePly(const PlyOptions& o = {})
{
    std::string header = "ply\nformat " + o.format + " 1.0\ncomment made by MeshReaderTest\n";
    const std::string vertexElement = std::string("element vertex 8\n")
        + (o.extraBefore ? "property double quality\n" : "")
        + (o.doubleCoordinates ? "property double x\nproperty double y\nproperty double z\n"
                               : "property float x\nproperty float y\nproperty float z\n")
        + (o.extraAfter ? "property double s\nproperty double t\nproperty uchar red\n" : "");
    const std::string faceElement
        = "element face 6\nproperty list " + o.countType + " " + o.indexType + " vertex_indices\n";
    header += o.faceFirst ? faceElement + vertexElement : vertexElement + faceElement;
    if (o.edgeElement)
        header += "element edge 2\nproperty int vertex1\nproperty int vertex2\n";
    header += "end_header\n";

    std::string vertices;
    for (const glm::vec3& v : kCubeVertices) {
        if (o.extraBefore)
            appendScalar<double>(vertices, o, 0.5);
        for (float f : { v.x, v.y, v.z }) {
            if (o.doubleCoordinates)
                appendScalar<double>(vertices, o, f);
            else
                appendScalar<float>(vertices, o, f);
        }
        if (o.extraAfter) {
            appendScalar<double>(vertices, o, 0.25);
            appendScalar<double>(vertices, o, 0.75);
            appendTyped(vertices, o, "uchar", 200);
        }
        if (o.format == "ascii")
            vertices += "\n";
    }
    std::string faces;
    for (const auto& q : kCubeQuads) {
        appendTyped(faces, o, o.countType, 4);
        for (int i : q)
            appendTyped(faces, o, o.indexType, i);
        if (o.format == "ascii")
            faces += "\n";
    }
    std::string edges;
    if (o.edgeElement)
        for (int e = 0; e < 2; ++e) {
            appendTyped(edges, o, "int", e);
            appendTyped(edges, o, "int", e + 1);
            if (o.format == "ascii")
                edges += "\n";
        }
    return header + (o.faceFirst ? faces + vertices : vertices + faces) + edges;
}

class MeshReaderFiles : public ::testing::Test {
protected:
    void SetUp() override { m_dir = wisp::test::freshTestFolder("wisp_mesh_reader"); }
    void TearDown() override { fs::remove_all(m_dir); }

    std::string write(const std::string& name, const std::string& bytes)
    {
        const fs::path p = m_dir / name;
        std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return p.string();
    }

    // Reads `bytes` as `name` and expects a refusal that names the file; returns the message.
    std::string expectError(const std::string& name, const std::string& bytes)
    {
        const std::string path = write(name, bytes);
        const Result<MeshReadResult> r = readMesh(path);
        EXPECT_FALSE(r.ok()) << name << " was accepted";
        if (r.ok())
            return {};
        const std::string text = r.error().toString();
        EXPECT_NE(text.find(path), std::string::npos) << text;
        EXPECT_EQ(r.error().file, path);
        return text;
    }

    MeshReadResult expectMesh(const std::string& name, const std::string& bytes)
    {
        const Result<MeshReadResult> r = readMesh(write(name, bytes));
        EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().toString());
        return r.ok() ? r.value() : MeshReadResult{};
    }

    fs::path m_dir;
};

void expectUnitCube(const MeshReadResult& r, const std::string& what)
{
    EXPECT_EQ(r.mesh.vertexCount(), 8u) << what;
    EXPECT_EQ(r.mesh.triangleCount(), 12u) << what;
    EXPECT_NEAR(signedVolume(r.mesh), 1.0, 1e-5) << what << ": winding or geometry changed";
    const Aabb box = boundsOf(r.mesh);
    EXPECT_EQ(box.min, glm::vec3(0.0f)) << what;
    EXPECT_EQ(box.max, glm::vec3(1.0f)) << what;
}

} // namespace

// ---- real heads ---------------------------------------------------------------------------------

TEST(MeshReaderAssets, MaxPlanckObj)
{
    const fs::path path = assetPath("heads/max_planck_decimated.obj");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    EXPECT_EQ(r.value().mesh.vertexCount(), 5272u);
    EXPECT_EQ(r.value().mesh.triangleCount(), 10540u);
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    EXPECT_EQ(validateMesh(r.value().mesh), "");
}

TEST(MeshReaderAssets, CyWomanHeadBinaryPly)
{
    const fs::path path = assetPath("heads/cy_woman_head.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 43662u);
    EXPECT_EQ(mesh.triangleCount(), 78520u);
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions.front(), rawPlyVertex(bytes, 12, 0));
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 12, 43661));
}

TEST(MeshReaderAssets, IgeaTriangleStrips)
{
    const fs::path path = assetPath("heads/igea_tristrips.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string()); // its load time is a figure: tests/bench, ReadHead
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 134345u);
    EXPECT_EQ(mesh.triangleCount(), 268686u);
    const glm::vec3 size = boundsOf(mesh).size();
    EXPECT_GT(size.y, 0.05f);
    EXPECT_LT(size.y, 0.2f) << "igea is stored in metres, about 0.1 m tall";
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 12, 134344));
    // Alternating winding: every strip triangle keeps the orientation of the first, so the
    // surface is consistently oriented and encloses a volume of one sign (outward here).
    EXPECT_GT(signedVolume(mesh), 0.0);
    std::size_t flipped = 0;
    const auto normals = vertexNormals(mesh);
    for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::vec3 avg = normals[tri.x] + normals[tri.y] + normals[tri.z];
        flipped += glm::dot(faceNormal(mesh, t), avg) < 0.0f ? 1 : 0;
    }
    EXPECT_LT(flipped, mesh.triangleCount() / 1000)
        << "triangles facing against their neighbours: strip winding is wrong";
}

TEST(MeshReaderAssets, Ct2HairHeadSkipsDoubleProperties)
{
    const fs::path path = assetPath("hair/ct2hair_bangs_head.ply");
    REQUIRE_ASSET(path);
    const auto r = readMesh(path.string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    const TriangleMesh& mesh = r.value().mesh;
    EXPECT_EQ(mesh.vertexCount(), 3943u);
    EXPECT_EQ(mesh.triangleCount(), 7694u);
    // x, y, z float then s, t double: 28 bytes a vertex. A wrong skip would garble later vertices.
    const std::string bytes = slurp(path);
    EXPECT_EQ(mesh.positions[0], rawPlyVertex(bytes, 28, 0));
    EXPECT_EQ(mesh.positions[1971], rawPlyVertex(bytes, 28, 1971));
    EXPECT_EQ(mesh.positions.back(), rawPlyVertex(bytes, 28, 3942));
}

TEST_F(MeshReaderFiles, TruncatedRealBinaryPlyIsRefused)
{
    const fs::path path = assetPath("heads/igea_tristrips.ply");
    REQUIRE_ASSET(path);
    const std::string bytes = slurp(path);
    const std::string text = expectError("igea_half.ply", bytes.substr(0, bytes.size() / 2));
    EXPECT_NE(text.find("truncated"), std::string::npos) << text;
    // Cut inside the strip list: the header's counts fit, the list's length does not.
    const std::string text2 = expectError("igea_cut.ply", bytes.substr(0, bytes.size() - 100));
    EXPECT_NE(text2.find("tristrips"), std::string::npos) << text2;
}

// ---- formats, generated ---------------------------------------------------------------------------

TEST_F(MeshReaderFiles, ObjQuadsAreFanTriangulated)
{
    expectUnitCube(expectMesh("cube.obj", cubeObj()), "obj");
    expectUnitCube(expectMesh("CUBE_CRLF.OBJ", cubeObj("\r\n")), "upper-case extension, CRLF");

    // A hexagon becomes four triangles; relative (negative) indices count back from the last vertex.
    std::string hex;
    for (int i = 0; i < 6; ++i) {
        const double a = i * 3.14159265358979 / 3.0;
        hex += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    hex += "f -6 -5 -4 -3 -2 -1\n";
    const MeshReadResult r = expectMesh("hexagon.obj", hex);
    EXPECT_EQ(r.mesh.vertexCount(), 6u);
    ASSERT_EQ(r.mesh.triangleCount(), 4u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(r.mesh.triangles[3], glm::uvec3(0, 4, 5));
}

TEST_F(MeshReaderFiles, ObjNonManifoldFacesAreKeptWithTheirVertices)
{
    // Three triangles on one edge: an OpenMesh mesh would refuse the third ("complex edge") or
    // give it copies of its vertices. A collider wants all three on the original vertices.
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    const MeshReadResult r = expectMesh("fin.obj", obj);
    EXPECT_EQ(r.mesh.vertexCount(), 5u);
    EXPECT_EQ(r.mesh.triangleCount(), 3u);
    EXPECT_TRUE(r.warnings.empty());
}

TEST_F(MeshReaderFiles, ObjWarningsStayOffStderr)
{
    std::string obj = "mtllib no_such_file.mtl\nusemtl skin\n" + cubeObj();
    obj += "f 1 1 2\nl 1 2\np 3\n";
    testing::internal::CaptureStderr();
    const MeshReadResult r = expectMesh("cube_with_extras.obj", obj);
    const std::string stderrText = testing::internal::GetCapturedStderr();
    EXPECT_EQ(stderrText, "");
    expectUnitCube(r, "obj with extras");
    std::string all;
    for (const std::string& w : r.warnings)
        all += w + "\n";
    // The material library is named, never opened (a missing one is no problem either).
    EXPECT_NE(all.find("ignored the material library 'no_such_file.mtl'"), std::string::npos) << all;
    EXPECT_NE(all.find("skipped 1 face"), std::string::npos) << all;
    EXPECT_NE(all.find("1 line element"), std::string::npos) << all;
}

// OpenMesh's OBJ reader refused one-component texture coordinates ("Only single 2D or 3D texture
// coordinate..."), which are legal OBJ; a collider reads no texture coordinates at all.
TEST_F(MeshReaderFiles, ObjTextureCoordinatesOfAnySizeAreSkipped)
{
    const MeshReadResult r
        = expectMesh("vt1.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5\nvt 0.5 0.5 0.5 0.5\nf 1/1 2/2 3/1\n");
    EXPECT_EQ(r.mesh.vertexCount(), 3u);
    ASSERT_EQ(r.mesh.triangleCount(), 1u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_TRUE(r.warnings.empty());
}

// A face may name a vertex written after it (positive indices are absolute); a negative index
// counts back from the vertices above the face.
TEST_F(MeshReaderFiles, ObjFacesMayNameLaterVertices)
{
    const MeshReadResult r = expectMesh("forward.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf -3 -1 -2\n");
    EXPECT_EQ(r.mesh.vertexCount(), 4u);
    ASSERT_EQ(r.mesh.triangleCount(), 2u);
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(r.mesh.triangles[1], glm::uvec3(1, 3, 2));
    const std::string text = expectError("forward_bad.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\n");
    EXPECT_NE(text.find("line 2: a face refers to vertex 3, but the file has 2 vertices"), std::string::npos) << text;
}

// STL corners are welded by value: -0 and +0 are one corner, so the cube stays closed.
TEST_F(MeshReaderFiles, StlWeldsSignedZeros)
{
    // Every other zero coordinate of a vertex line written as -0.
    std::string signedZeros = cubeStlAscii();
    int n = 0;
    for (std::size_t at = signedZeros.find(" 0.000000"); at != std::string::npos;
         at = signedZeros.find(" 0.000000", at + 2))
        if (n++ % 2 == 1 && signedZeros.rfind("vertex", at) > signedZeros.rfind('\n', at))
            signedZeros.insert(at + 1, "-");
    ASSERT_NE(signedZeros.find("-0"), std::string::npos);
    expectUnitCube(expectMesh("signed_zero.stl", signedZeros), "ascii stl with -0");
}

TEST_F(MeshReaderFiles, OffWithCommentsColoursAndSameLineCounts)
{
    expectUnitCube(expectMesh("cube.off", cubeOff()), "off");
    std::string sameLine = cubeOff();
    sameLine.replace(0, sameLine.find("8 6 12\n") + 7, "OFF 8 6 0\n");
    expectUnitCube(expectMesh("same_line.off", sameLine), "counts on the OFF line");
    std::string coloured = "COFF\n8 6 0\n";
    for (const glm::vec3& v : kCubeVertices)
        coloured += std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + " 255 0 0 255\n";
    for (const auto& q : kCubeQuads)
        coloured += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " "
            + std::to_string(q[3]) + " 0.5 0.5 0.5\n";
    expectUnitCube(expectMesh("coloured.off", coloured), "COFF");
}

TEST_F(MeshReaderFiles, StlAsciiAndBinaryCubesWeldCorners)
{
    expectUnitCube(expectMesh("cube_ascii.stl", cubeStlAscii()), "ascii stl");
    expectUnitCube(expectMesh("cube_binary.STL", cubeStlBinary()), "binary stl");
    // A binary STL whose header happens to start with "solid" is still binary (by its size).
    std::string solidHeader = cubeStlBinary();
    solidHeader.replace(0, 5, "solid");
    expectUnitCube(expectMesh("cube_solid_header.stl", solidHeader), "binary stl with 'solid' header");
}

TEST_F(MeshReaderFiles, PlyVariantsAllGiveTheSameCube)
{
    std::vector<std::pair<std::string, PlyOptions>> variants;
    for (const std::string format : { "ascii", "binary_little_endian", "binary_big_endian" }) {
        PlyOptions o;
        o.format = format;
        variants.push_back({ format, o });
        o.extraBefore = o.extraAfter = true;
        variants.push_back({ format + " extra properties", o });
        o.doubleCoordinates = true;
        o.countType = "uint";
        o.indexType = "uint";
        variants.push_back({ format + " doubles, uint lists", o });
        o.countType = "ushort";
        o.indexType = "ushort";
        o.faceFirst = true;
        o.edgeElement = true;
        variants.push_back({ format + " faces first, ushort, edges", o });
    }
    int n = 0;
    for (const auto& [what, options] : variants) {
        const MeshReadResult r = expectMesh("cube" + std::to_string(n++) + ".ply", cubePly(options));
        expectUnitCube(r, what);
        EXPECT_EQ(r.warnings.size(), options.edgeElement ? 1u : 0u) << what;
    }
}

TEST_F(MeshReaderFiles, PlyTriangleStripsSplitAtMinusOneWithAlternatingWinding)
{
    // Two strips over a flat 2x3 grid in z = 0, ASCII so the test reads like the data:
    //   3 4 5      strip A = 0 1 3 4 gives (0 1 3) and, swapped, (3 1 4);
    //   0 1 2      strip B = 1 2 4 5 gives (1 2 4) and (4 2 5). All must face +z.
    const std::string ply
        = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
          "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
          "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n"
          "9 0 1 3 4 -1 1 2 4 5\n";
    const MeshReadResult r = expectMesh("strips.ply", ply);
    ASSERT_EQ(r.mesh.triangleCount(), 4u);
    for (std::uint32_t t = 0; t < 4; ++t)
        EXPECT_GT(faceNormal(r.mesh, t).z, 0.99f) << "triangle " << t;
    EXPECT_EQ(r.mesh.triangles[0], glm::uvec3(0, 1, 3));
    EXPECT_EQ(r.mesh.triangles[1], glm::uvec3(3, 1, 4));

    // Degenerate triangles that stitch strips together are dropped without a warning.
    const std::string stitched
        = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
          "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
          "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n"
          "6 0 1 3 4 4 1\n";
    const MeshReadResult s = expectMesh("stitched.ply", stitched);
    EXPECT_EQ(s.mesh.triangleCount(), 2u);
    EXPECT_TRUE(s.warnings.empty());
}

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

TEST(MeshReaderApi, SupportedExtensions)
{
    const std::vector<std::string> expected = { "obj", "ply", "off", "stl", "gltf", "glb" };
    EXPECT_EQ(supportedMeshExtensions(), expected);
}
