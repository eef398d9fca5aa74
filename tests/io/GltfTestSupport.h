#pragma once
// What the glTF reader tests share: hand-made glTF files (GltfBuilder), a scratch folder and a few
// geometric checks. The tests are split by topic: GltfSampleFilesTest (the shared sample files),
// GltfReaderTest (each rule on its own), GltfHostileTest (hostile structure, issue 12).
#include "IoTestSupport.h"
#include "io/GltfReader.h"
#include "io/MeshReader.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace wisp::test::gltf {

using namespace wisp::io;
namespace fs = std::filesystem;
using Json = nlohmann::json;

inline void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance, const std::string& what)
{
    EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
    EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
    EXPECT_NEAR(actual.z, expected.z, tolerance) << what;
}

inline std::string joined(const std::vector<std::string>& lines)
{
    std::string s;
    for (const std::string& line : lines)
        s += line + "\n";
    return s;
}

// The JSON chunk of a GLB, parsed here independently of the reader.
inline Json glbJson(const std::string& bytes)
{
    std::uint32_t jsonBytes = 0;
    std::memcpy(&jsonBytes, bytes.data() + 12, 4);
    return Json::parse(bytes.substr(20, jsonBytes));
}

// A scratch folder for files written by a test, removed afterwards.
class TempDir {
public:
    TempDir()
    {
        static int serial = 0;
        m_path = fs::temp_directory_path()
            / ("wisp_gltf_test_" + std::to_string(::getpid()) + "_" + std::to_string(serial++));
        fs::create_directories(m_path);
    }
    ~TempDir()
    {
        std::error_code ec;
        fs::remove_all(m_path, ec);
    }
    fs::path write(const std::string& name, const std::string& bytes) const
    {
        const fs::path path = m_path / name;
        std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return path;
    }
    const fs::path& path() const { return m_path; }

private:
    fs::path m_path;
};

// ---- hand-made glTF ---------------------------------------------------------------------------

inline std::string base64(const std::string& bytes)
{
    static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16)
            | (static_cast<unsigned char>(bytes[i + 1]) << 8) | static_cast<unsigned char>(bytes[i + 2]);
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += alphabet[(v >> 6) & 63];
        out += alphabet[v & 63];
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const unsigned v
            = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
        out += alphabet[(v >> 18) & 63];
        out += alphabet[(v >> 12) & 63];
        out += alphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

// Builds a one-buffer glTF: add data, views and accessors, then meshes and nodes as JSON.
class GltfBuilder {
public:
    GltfBuilder()
    {
        root["asset"] = { { "version", "2.0" } };
        root["bufferViews"] = Json::array();
        root["accessors"] = Json::array();
        root["meshes"] = Json::array();
        root["nodes"] = Json::array();
    }

    // Appends raw bytes (4-byte aligned) as a bufferView; returns its index.
    int view(const std::string& bytes, int strideBytes = 0)
    {
        while (m_buffer.size() % 4 != 0)
            m_buffer += '\0';
        Json v = { { "buffer", 0 }, { "byteOffset", m_buffer.size() }, { "byteLength", bytes.size() } };
        if (strideBytes > 0)
            v["byteStride"] = strideBytes;
        m_buffer += bytes;
        root["bufferViews"].push_back(v);
        return static_cast<int>(root["bufferViews"].size()) - 1;
    }

    int accessor(int viewIndex, int componentType, std::size_t count, const char* type, bool normalized = false)
    {
        Json a
            = { { "bufferView", viewIndex }, { "componentType", componentType }, { "count", count }, { "type", type } };
        if (normalized)
            a["normalized"] = true;
        root["accessors"].push_back(a);
        return static_cast<int>(root["accessors"].size()) - 1;
    }

    int floats(const std::vector<float>& values)
    {
        return accessor(view(bytesOf(values)), 5126, values.size() / 3, "VEC3");
    }

    template <typename T> int indices(const std::vector<T>& values)
    {
        const int type = sizeof(T) == 1 ? 5121 : sizeof(T) == 2 ? 5123 : 5125;
        return accessor(view(bytesOf(values)), type, values.size(), "SCALAR");
    }

    int mesh(int positions, int indexAccessor, int mode = 4)
    {
        Json primitive = { { "attributes", { { "POSITION", positions } } }, { "mode", mode } };
        if (indexAccessor >= 0)
            primitive["indices"] = indexAccessor;
        root["meshes"].push_back({ { "primitives", Json::array({ primitive }) } });
        return static_cast<int>(root["meshes"].size()) - 1;
    }

    int node(Json node)
    {
        root["nodes"].push_back(std::move(node));
        return static_cast<int>(root["nodes"].size()) - 1;
    }

    void scene(std::vector<int> roots)
    {
        root["scenes"] = Json::array({ { { "nodes", roots } } });
        root["scene"] = 0;
    }

    // The .gltf text with the buffer as a data URI.
    std::string gltf()
    {
        Json copy = root;
        copy["buffers"] = Json::array({ { { "byteLength", m_buffer.size() },
            { "uri", "data:application/octet-stream;base64," + base64(m_buffer) } } });
        return copy.dump();
    }

    // The same as a GLB with the buffer in the BIN chunk.
    std::string glb()
    {
        Json copy = root;
        copy["buffers"] = Json::array({ { { "byteLength", m_buffer.size() } } });
        std::string json = copy.dump();
        while (json.size() % 4 != 0)
            json += ' ';
        std::string bin = m_buffer;
        while (bin.size() % 4 != 0)
            bin += '\0';
        std::string out;
        auto u32 = [&out](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        out += "glTF";
        u32(2);
        u32(static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
        u32(static_cast<std::uint32_t>(json.size()));
        out += "JSON";
        out += json;
        u32(static_cast<std::uint32_t>(bin.size()));
        out.append("BIN\0", 4);
        out += bin;
        return out;
    }

    Json root;
    const std::string& buffer() const { return m_buffer; }

    template <typename T> static std::string bytesOf(const std::vector<T>& values)
    {
        return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }

private:
    std::string m_buffer;
};

// A unit square in the z = 0 plane as four corners, counter-clockwise seen from +Z.
inline const std::vector<float> squareCorners = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0 };

// A closed tetrahedron (outward winding), for winding checks under mirroring transforms.
inline const std::vector<float> tetraCorners = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1 };
inline const std::vector<std::uint16_t> tetraIndices = { 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3 };

} // namespace wisp::test::gltf
