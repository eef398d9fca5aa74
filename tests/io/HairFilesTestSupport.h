#pragma once
// What the hair file tests share: byte writers, a small groom, and independent parsers of the OBJ
// and glTF that Wisp writes. Split by topic: HairFilesTest (the real samples, parsed back) and
// HairFilesRefusalTest (broken files and failed writes).
#include "IoTestSupport.h"
#include "io/HairFiles.h"

#include <glm/common.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace wisp::test::hair {

using namespace wisp::io;
namespace fs = std::filesystem;
using wisp::test::assetPath;
using wisp::test::slurp;

inline const fs::path kBangsHair = assetPath("hair/ct2hair_bangs100.hair");
inline const fs::path kBangsData = assetPath("hair/ct2hair_bangs100.data");

inline void spit(const fs::path& path, const std::string& bytes)
{
    // Removed first: truncating a file with content makes ext4 flush it to disk on close
    // (auto_da_alloc), which makes the loops below over many copies take seconds.
    fs::remove(path);
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline void putU32(std::string& bytes, std::size_t at, std::uint32_t v)
{
    std::memcpy(bytes.data() + at, &v, 4);
} // tests run little-endian
inline void putF32(std::string& bytes, std::size_t at, float v)
{
    std::memcpy(bytes.data() + at, &v, 4);
}
inline void appendI32(std::string& bytes, std::int32_t v)
{
    bytes.append(reinterpret_cast<const char*>(&v), 4);
}
inline void appendF32(std::string& bytes, float v)
{
    bytes.append(reinterpret_cast<const char*>(&v), 4);
}
inline std::uint32_t getU32(const std::string& bytes, std::size_t at)
{
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

inline HairCurves readOk(const fs::path& path)
{
    Result<HairReadResult> r = readHair(path.string());
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().toString());
    if (!r.ok())
        return {};
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    return std::move(r).value().strands;
}

inline std::string errorText(const fs::path& path)
{
    Result<HairReadResult> r = readHair(path.string());
    EXPECT_FALSE(r.ok()) << path << " was read, but should have been refused";
    return r.ok() ? std::string() : r.error().toString();
}

inline void expectBitIdentical(const HairCurves& a, const HairCurves& b)
{
    ASSERT_EQ(a.offsets, b.offsets);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)));
}

inline std::size_t segmentCount(const HairCurves& c)
{
    std::size_t n = 0;
    for (std::size_t s = 0; s < c.strandCount(); ++s)
        n += c.pointsIn(s) - 1;
    return n;
}

// Three strands of 2, 5 and 3 points, in metres.
inline HairCurves smallGroom()
{
    HairCurves c;
    const std::uint32_t counts[] = { 2, 5, 3 };
    for (std::uint32_t n : counts) {
        const std::size_t s = c.addStrand(n);
        std::span<glm::vec3> p = c.strandForWrite(s);
        for (std::uint32_t i = 0; i < n; ++i)
            p[i] = { 0.01f * float(s) + 1e-7f * float(i), 0.1f - 0.012f * float(i), -0.003f * float(s * i) };
    }
    return c;
}

inline TriangleMesh tetrahedron()
{
    TriangleMesh m;
    m.positions = { { 0, 0, 0 }, { 0.1f, 0, 0 }, { 0, 0.1f, 0 }, { 0, 0, 0.1f } };
    for (const auto& [a, b, c] : { std::array{ 0u, 2u, 1u }, { 0u, 1u, 3u }, { 0u, 3u, 2u }, { 1u, 2u, 3u } })
        m.triangles.emplace_back(a, b, c);
    return m;
}

class HairFiles : public ::testing::Test {
protected:
    void SetUp() override { dir = wisp::test::freshTestFolder("wisp-hairfiles"); }
    void TearDown() override { fs::remove_all(dir); }

    std::vector<std::string> filesInDir() const
    {
        std::vector<std::string> names;
        for (const auto& e : fs::directory_iterator(dir))
            names.push_back(e.path().filename().string());
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir;
};

// ---- OBJ and glTF parsed back independently -------------------------------------------------------

struct ObjFile {
    std::vector<glm::vec3> vertices;
    std::vector<std::vector<std::size_t>> lines; // 1-based, as written
    std::vector<std::vector<std::size_t>> faces;
    std::vector<std::string> comments;
};

inline ObjFile parseObj(const std::string& text)
{
    ObjFile obj;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string tag;
        words >> tag;
        if (tag == "#") {
            obj.comments.push_back(line);
        } else if (tag == "v") {
            glm::vec3 v;
            words >> v.x >> v.y >> v.z;
            obj.vertices.push_back(v);
        } else if (tag == "l" || tag == "f") {
            std::vector<std::size_t> indices;
            for (std::size_t i; words >> i;)
                indices.push_back(i);
            (tag == "l" ? obj.lines : obj.faces).push_back(indices);
        }
    }
    return obj;
}

inline std::string decodeBase64(const std::string& text)
{
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        if (c == '=')
            break;
        bits = bits << 6 | static_cast<std::uint32_t>(alphabet.find(c));
        if ((count += 6) >= 8) {
            count -= 8;
            out.push_back(static_cast<char>(bits >> count & 0xff));
        }
    }
    return out;
}

struct Gltf {
    nlohmann::json json;
    std::string buffer;

    // The bytes of accessor `a` and how many elements it has.
    const char* data(std::size_t a) const
    {
        const auto& accessor = json["accessors"][a];
        const auto& view = json["bufferViews"][accessor["bufferView"].get<std::size_t>()];
        return buffer.data() + view.value("byteOffset", std::size_t(0)) + accessor.value("byteOffset", std::size_t(0));
    }
    std::size_t count(std::size_t a) const { return json["accessors"][a]["count"]; }
    template <typename T> std::vector<T> read(std::size_t a, std::size_t components) const
    {
        std::vector<T> v(count(a) * components);
        std::memcpy(v.data(), data(a), v.size() * sizeof(T));
        return v;
    }
};

inline Gltf parseGltf(const std::string& text)
{
    Gltf g;
    g.json = nlohmann::json::parse(text);
    const std::string uri = g.json["buffers"][0]["uri"];
    const std::string prefix = "data:application/octet-stream;base64,";
    EXPECT_EQ(0u, uri.rfind(prefix, 0));
    g.buffer = decodeBase64(uri.substr(prefix.size()));
    EXPECT_EQ(g.json["buffers"][0]["byteLength"].get<std::size_t>(), g.buffer.size());
    return g;
}

inline Gltf parseGlb(const std::string& bytes)
{
    Gltf g;
    EXPECT_GE(bytes.size(), 28u);
    EXPECT_EQ(0, std::memcmp(bytes.data(), "glTF", 4));
    EXPECT_EQ(2u, getU32(bytes, 4));
    EXPECT_EQ(bytes.size(), getU32(bytes, 8));
    const std::uint32_t jsonLength = getU32(bytes, 12);
    EXPECT_EQ(0u, jsonLength % 4);
    EXPECT_EQ(0, std::memcmp(bytes.data() + 16, "JSON", 4));
    g.json = nlohmann::json::parse(bytes.substr(20, jsonLength));
    const std::size_t bin = 20 + jsonLength;
    const std::uint32_t binLength = getU32(bytes, bin);
    EXPECT_EQ(0, std::memcmp(bytes.data() + bin + 4, "BIN\0", 4));
    EXPECT_EQ(bytes.size(), bin + 8 + binLength);
    g.buffer = bytes.substr(bin + 8, binLength);
    EXPECT_FALSE(g.json["buffers"][0].contains("uri"));
    EXPECT_LE(g.json["buffers"][0]["byteLength"].get<std::size_t>(), g.buffer.size());
    return g;
}

// Checks a glTF written from `strands` (and `head`, when given) with the default widths.
inline void expectGltfHolds(const Gltf& g, const HairCurves& strands, const TriangleMesh* head)
{
    const nlohmann::json& j = g.json;
    EXPECT_EQ("2.0", j["asset"]["version"]);
    ASSERT_EQ(head ? 2u : 1u, j["meshes"].size());
    ASSERT_EQ(head ? 2u : 1u, j["nodes"].size());
    EXPECT_EQ(head ? 2u : 1u, j["scenes"][j["scene"].get<std::size_t>()]["nodes"].size());
    for (const auto& view : j["bufferViews"])
        EXPECT_EQ(0u, view.value("byteOffset", std::size_t(0)) % 4);

    const auto& hair = j["meshes"][0]["primitives"][0];
    EXPECT_EQ(1, hair["mode"]); // LINES
    const std::size_t position = hair["attributes"]["POSITION"], width = hair["attributes"]["_WIDTH"],
                      indices = hair["indices"];
    EXPECT_EQ(5126, j["accessors"][position]["componentType"]);
    EXPECT_EQ("VEC3", j["accessors"][position]["type"]);
    EXPECT_EQ(5125, j["accessors"][indices]["componentType"]);

    // Positions, and min/max that match them exactly.
    ASSERT_EQ(strands.pointCount(), g.count(position));
    const std::vector<float> xyz = g.read<float>(position, 3);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t i = 0; i < strands.pointCount(); ++i) {
        const glm::vec3 p{ xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2] };
        ASSERT_NEAR(strands.positions[i].x, p.x, 1e-6f);
        ASSERT_NEAR(strands.positions[i].y, p.y, 1e-6f);
        ASSERT_NEAR(strands.positions[i].z, p.z, 1e-6f);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(lo[k], j["accessors"][position]["min"][k].get<float>());
        EXPECT_EQ(hi[k], j["accessors"][position]["max"][k].get<float>());
    }

    // One index pair per segment, each joining neighbours of one strand.
    ASSERT_EQ(2 * segmentCount(strands), g.count(indices));
    const std::vector<std::uint32_t> pairs = g.read<std::uint32_t>(indices, 1);
    std::size_t k = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        for (std::uint32_t i = strands.offsets[s]; i + 1 < strands.offsets[s + 1]; ++i, k += 2) {
            ASSERT_EQ(i, pairs[k]);
            ASSERT_EQ(i + 1, pairs[k + 1]);
        }

    // Widths taper from the root width to the tip width along every strand.
    ASSERT_EQ(strands.pointCount(), g.count(width));
    EXPECT_EQ("SCALAR", j["accessors"][width]["type"]);
    const std::vector<float> widths = g.read<float>(width, 1);
    const HairExportOptions defaults;
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t first = strands.offsets[s], last = strands.offsets[s + 1] - 1;
        EXPECT_FLOAT_EQ(defaults.rootWidthMetres, widths[first]);
        EXPECT_FLOAT_EQ(defaults.tipWidthMetres, widths[last]);
        for (std::uint32_t i = first; i < last; ++i)
            ASSERT_GT(widths[i], widths[i + 1]) << "strand " << s;
    }

    if (head) {
        const auto& h = j["meshes"][1]["primitives"][0];
        EXPECT_EQ(4, h.value("mode", 4)); // TRIANGLES
        const std::size_t hp = h["attributes"]["POSITION"], hi3 = h["indices"];
        ASSERT_EQ(head->positions.size(), g.count(hp));
        ASSERT_EQ(3 * head->triangles.size(), g.count(hi3));
        EXPECT_TRUE(j["accessors"][hp].contains("min"));
        const std::vector<float> v = g.read<float>(hp, 3);
        for (std::size_t i = 0; i < head->positions.size(); ++i)
            EXPECT_EQ(head->positions[i].y, v[3 * i + 1]);
        const std::vector<std::uint32_t> t = g.read<std::uint32_t>(hi3, 1);
        for (std::size_t i = 0; i < head->triangles.size(); ++i)
            EXPECT_EQ(head->triangles[i].z, t[3 * i + 2]);
    }
}

} // namespace wisp::test::hair
