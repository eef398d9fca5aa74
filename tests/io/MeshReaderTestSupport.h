#pragma once
// What the mesh reader tests share: generated cubes in every format (OBJ, OFF, STL, PLY variants),
// volume and cube checks, and the fixture's scratch folder. Split by topic: MeshReaderTest (real
// heads and generated formats) and MeshReaderRefusalTest (broken files).
#include "IoTestSupport.h"
#include "io/MeshReader.h"

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

namespace wisp::test::mesh {

using namespace wisp::io;
namespace fs = std::filesystem;
using wisp::test::assetPath;
using wisp::test::slurp;

// Reads vertex `i` straight from a little-endian binary PLY whose vertex element comes first
// and starts with float x, y, z: an independent check of what readMesh returned.
inline glm::vec3 rawPlyVertex(const std::string& bytes, std::size_t stride, std::size_t i)
{
    const std::size_t data = bytes.find("end_header\n") + std::strlen("end_header\n");
    float xyz[3];
    std::memcpy(xyz, bytes.data() + data + i * stride, sizeof xyz);
    return { xyz[0], xyz[1], xyz[2] };
}

// ---- generated files ------------------------------------------------------------------------------

// Unit cube as six quads, counter-clockwise seen from outside.
inline const std::vector<glm::vec3> kCubeVertices
    = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
inline const std::vector<std::vector<int>> kCubeQuads
    = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 3, 7, 6, 2 }, { 0, 4, 7, 3 }, { 1, 2, 6, 5 } };

inline std::string cubeObj(const std::string& eol = "\n")
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

inline std::string cubeOff()
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

inline std::vector<std::array<glm::vec3, 3>> cubeTriangles()
{
    std::vector<std::array<glm::vec3, 3>> tris;
    for (const auto& q : kCubeQuads) {
        tris.push_back({ kCubeVertices[q[0]], kCubeVertices[q[1]], kCubeVertices[q[2]] });
        tris.push_back({ kCubeVertices[q[0]], kCubeVertices[q[2]], kCubeVertices[q[3]] });
    }
    return tris;
}

inline std::string cubeStlAscii()
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

inline std::string cubeStlBinary()
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

inline void appendTyped(std::string& s, const PlyOptions& o, const std::string& type, long long value)
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

inline std::string cubePly(const PlyOptions& o = {})
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

inline void expectUnitCube(const MeshReadResult& r, const std::string& what)
{
    EXPECT_EQ(r.mesh.vertexCount(), 8u) << what;
    EXPECT_EQ(r.mesh.triangleCount(), 12u) << what;
    EXPECT_NEAR(signedVolume(r.mesh), 1.0, 1e-5) << what << ": winding or geometry changed";
    const Aabb box = boundsOf(r.mesh);
    EXPECT_EQ(box.min, glm::vec3(0.0f)) << what;
    EXPECT_EQ(box.max, glm::vec3(1.0f)) << what;
}

} // namespace wisp::test::mesh
