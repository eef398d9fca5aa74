// Hair files: cyHair .hair and USC .data in and out, OBJ and glTF export, and refusals of broken files.

#include "io/HairFiles.h"
#include "IoTestSupport.h"

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

using namespace wisp;
using namespace wisp::io;
namespace fs = std::filesystem;
using wisp::test::assetPath;
using wisp::test::slurp;

namespace {

const fs::path kBangsHair = assetPath("hair/ct2hair_bangs100.hair");
const fs::path kBangsData = assetPath("hair/ct2hair_bangs100.data");

void spit(const fs::path& path, const std::string& bytes)
{
    // Removed first: truncating a file with content makes ext4 flush it to disk on close
    // (auto_da_alloc), which makes the loops below over many copies take seconds.
    fs::remove(path);
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void putU32(std::string& bytes, std::size_t at, std::uint32_t v)
{
    std::memcpy(bytes.data() + at, &v, 4);
} // tests run little-endian
void putF32(std::string& bytes, std::size_t at, float v)
{
    std::memcpy(bytes.data() + at, &v, 4);
}
void appendI32(std::string& bytes, std::int32_t v)
{
    bytes.append(reinterpret_cast<const char*>(&v), 4);
}
void appendF32(std::string& bytes, float v)
{
    bytes.append(reinterpret_cast<const char*>(&v), 4);
}
std::uint32_t getU32(const std::string& bytes, std::size_t at)
{
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + at, 4);
    return v;
}

HairCurves readOk(const fs::path& path)
{
    Result<HairReadResult> r = readHair(path.string());
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().toString());
    if (!r.ok())
        return {};
    EXPECT_TRUE(r.value().warnings.empty()) << r.value().warnings.front();
    return std::move(r).value().strands;
}

std::string errorText(const fs::path& path)
{
    Result<HairReadResult> r = readHair(path.string());
    EXPECT_FALSE(r.ok()) << path << " was read, but should have been refused";
    return r.ok() ? std::string() : r.error().toString();
}

void expectBitIdentical(const HairCurves& a, const HairCurves& b)
{
    ASSERT_EQ(a.offsets, b.offsets);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)));
}

std::size_t segmentCount(const HairCurves& c)
{
    std::size_t n = 0;
    for (std::size_t s = 0; s < c.strandCount(); ++s)
        n += c.pointsIn(s) - 1;
    return n;
}

// Three strands of 2, 5 and 3 points, in metres.
HairCurves smallGroom()
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

TriangleMesh tetrahedron()
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

ObjFile parseObj(const std::string& text)
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

std::string decodeBase64(const std::string& text)
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

Gltf parseGltf(const std::string& text)
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

Gltf parseGlb(const std::string& bytes)
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
void expectGltfHolds(const Gltf& g, const HairCurves& strands, const TriangleMesh* head)
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

} // namespace

// ---- the real samples ------------------------------------------------------------------------------

TEST_F(HairFiles, SamplesLoadAsTheSameHundredStrands)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    const HairCurves fromHair = readOk(kBangsHair);
    const HairCurves fromData = readOk(kBangsData);
    EXPECT_EQ(100u, fromHair.strandCount());
    EXPECT_EQ(1165u, fromHair.pointCount());
    for (std::size_t s = 0; s < fromHair.strandCount(); ++s) { // the README: 4-20 segments a strand
        EXPECT_GE(fromHair.pointsIn(s), 5u);
        EXPECT_LE(fromHair.pointsIn(s), 21u);
    }
    expectBitIdentical(fromHair, fromData);

    // Checked against the raw bytes: the .data file's first strand and its first point.
    const std::string raw = slurp(kBangsData);
    EXPECT_EQ(fromData.pointsIn(0), getU32(raw, 4));
    EXPECT_EQ(0, std::memcmp(raw.data() + 8, &fromData.positions[0], 12));
}

TEST_F(HairFiles, CyHairAndUscRoundTripExactly)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    for (const fs::path& sample : { kBangsHair, kBangsData }) {
        SCOPED_TRACE(sample.string());
        const HairCurves original = readOk(sample);
        for (const char* name : { "out.hair", "out.data", "OUT.HAIR", "Out.Data" }) {
            SCOPED_TRACE(name);
            ASSERT_TRUE(writeHair((dir / name).string(), original));
            expectBitIdentical(original, readOk(dir / name));
        }
    }
    // The .data format has no free fields: the written file is the sample, byte for byte. The
    // .hair file differs only in its info string ("Wisp").
    const HairCurves bangs = readOk(kBangsHair);
    ASSERT_TRUE(writeHair((dir / "bangs.data").string(), bangs));
    EXPECT_EQ(slurp(kBangsData), slurp(dir / "bangs.data"));
    ASSERT_TRUE(writeHair((dir / "bangs.hair").string(), bangs));
    const std::string ours = slurp(dir / "bangs.hair"), theirs = slurp(kBangsHair);
    ASSERT_EQ(theirs.size(), ours.size());
    EXPECT_EQ(theirs.substr(0, 40), ours.substr(0, 40));
    EXPECT_EQ(std::string("Wisp\0\0", 6), ours.substr(40, 6));
    EXPECT_EQ(theirs.substr(128), ours.substr(128));
    EXPECT_EQ(0x3u, getU32(ours, 12));
    EXPECT_EQ(6u, filesInDir().size()); // and no temporary files left behind
}

TEST_F(HairFiles, ObjPolylinesParseBack)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    const fs::path path = dir / "bangs.obj";
    ASSERT_TRUE(writeHair(path.string(), bangs));
    const ObjFile obj = parseObj(slurp(path));
    ASSERT_FALSE(obj.comments.empty());
    EXPECT_NE(std::string::npos, obj.comments[0].find("100 strands, 1165 points")) << obj.comments[0];
    ASSERT_EQ(bangs.pointCount(), obj.vertices.size());
    for (std::size_t i = 0; i < obj.vertices.size(); ++i) {
        ASSERT_NEAR(bangs.positions[i].x, obj.vertices[i].x, 1e-6f);
        ASSERT_NEAR(bangs.positions[i].y, obj.vertices[i].y, 1e-6f);
        ASSERT_NEAR(bangs.positions[i].z, obj.vertices[i].z, 1e-6f);
        ASSERT_EQ(bangs.positions[i], obj.vertices[i]); // %.9g round-trips a float
    }
    ASSERT_EQ(bangs.strandCount(), obj.lines.size());
    for (std::size_t s = 0; s < bangs.strandCount(); ++s) {
        ASSERT_EQ(bangs.pointsIn(s), obj.lines[s].size());
        for (std::size_t i = 0; i < obj.lines[s].size(); ++i)
            ASSERT_EQ(bangs.offsets[s] + i + 1, obj.lines[s][i]);
    }
    EXPECT_TRUE(obj.faces.empty());

    // With a head: a second object whose faces index past the strands' points.
    const TriangleMesh head = tetrahedron();
    HairExportOptions options;
    options.head = &head;
    ASSERT_TRUE(writeHair((dir / "with_head.OBJ").string(), bangs, options));
    const ObjFile both = parseObj(slurp(dir / "with_head.OBJ"));
    ASSERT_EQ(bangs.pointCount() + head.positions.size(), both.vertices.size());
    ASSERT_EQ(head.triangles.size(), both.faces.size());
    EXPECT_EQ(bangs.pointCount() + 1 + head.triangles[3].y, both.faces[3][1]);
    EXPECT_EQ(head.positions[2], both.vertices[bangs.pointCount() + 2]);
}

TEST_F(HairFiles, GltfAndGlbParseBack)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    const TriangleMesh head = tetrahedron();
    HairExportOptions withHead;
    withHead.head = &head;

    ASSERT_TRUE(writeHair((dir / "bangs.gltf").string(), bangs));
    {
        SCOPED_TRACE("gltf");
        expectGltfHolds(parseGltf(slurp(dir / "bangs.gltf")), bangs, nullptr);
    }
    ASSERT_TRUE(writeHair((dir / "bangs.glb").string(), bangs));
    {
        SCOPED_TRACE("glb");
        expectGltfHolds(parseGlb(slurp(dir / "bangs.glb")), bangs, nullptr);
    }
    ASSERT_TRUE(writeHair((dir / "head.GLTF").string(), bangs, withHead));
    {
        SCOPED_TRACE("gltf with head");
        expectGltfHolds(parseGltf(slurp(dir / "head.GLTF")), bangs, &head);
    }
    ASSERT_TRUE(writeHair((dir / "head.glb").string(), smallGroom(), withHead));
    {
        SCOPED_TRACE("glb with head");
        expectGltfHolds(parseGlb(slurp(dir / "head.glb")), smallGroom(), &head);
    }
}

TEST_F(HairFiles, GltfWidthsFollowTheOptions)
{
    HairExportOptions options;
    options.rootWidthMetres = 100e-6f;
    options.tipWidthMetres = 0.0f;
    const HairCurves groom = smallGroom();
    ASSERT_TRUE(writeHair((dir / "w.gltf").string(), groom, options));
    const Gltf g = parseGltf(slurp(dir / "w.gltf"));
    const std::size_t width = g.json["meshes"][0]["primitives"][0]["attributes"]["_WIDTH"];
    const std::vector<float> w = g.read<float>(width, 1);
    // Strand 1 has five points: 100, 75, 50, 25, 0 micrometres.
    for (int i = 0; i < 5; ++i)
        EXPECT_NEAR(100e-6f * (1.0f - 0.25f * float(i)), w[2 + i], 1e-9f);

    options.rootWidthMetres = std::numeric_limits<float>::quiet_NaN();
    const Result<void> error = writeHair((dir / "nan.gltf").string(), groom, options);
    ASSERT_FALSE(error.ok());
    EXPECT_NE(std::string::npos, error.error().message.find("width")) << error.error().toString();
    EXPECT_FALSE(fs::exists(dir / "nan.gltf"));
}

// ---- refusals -------------------------------------------------------------------------------------

TEST_F(HairFiles, CyHairClaimingMorePointsThanItHoldsIsRefused)
{
    REQUIRE_ASSET(kBangsHair);
    const std::string bytes = slurp(kBangsHair);
    // Cut after 300 points: 128 + 2 x 100 + 12 x 300 = 3928 bytes.
    const fs::path cut = dir / "ct2hair_bangs100.hair";
    spit(cut, bytes.substr(0, 3928));
    EXPECT_EQ(cut.string() + ": byte 3928: the header claims 1165 points but the file holds only 300", errorText(cut));

    // A header claiming four billion points in a 14 KB file: refused by its size, at once.
    std::string huge = bytes;
    putU32(huge, 8, 0xffffffffu);
    spit(dir / "huge.hair", huge);
    // "At once" is shown by the message, not a stopwatch: it compares the header's claim with the
    // file's size, so nothing was allocated or read for the claimed points (under ASan a 4-billion-point
    // allocation would abort the test).
    const std::string message = errorText(dir / "huge.hair");
    EXPECT_NE(std::string::npos, message.find("huge.hair")) << message;
    EXPECT_NE(std::string::npos, message.find("4294967295 points but the file holds only 1165")) << message;

    // Four billion strands: the segments array cannot fit.
    std::string strands = bytes;
    putU32(strands, 4, 0xfffffff0u);
    putU32(strands, 8, 0xfffffff0u);
    spit(dir / "strands.hair", strands);
    EXPECT_NE(std::string::npos,
        errorText(dir / "strands.hair").find("4294967280 strands but the file holds segment counts for only"));

    // Segment counts that do not add up to the point count.
    std::string sum = bytes;
    sum[128] = static_cast<char>(sum[128] + 1);
    spit(dir / "sum.hair", sum);
    EXPECT_NE(std::string::npos,
        errorText(dir / "sum.hair").find("segment counts add up to 1166 points but the header claims 1165"));

    // Zero counts, no points array, not a cyHair file.
    std::string zero = bytes;
    putU32(zero, 4, 0);
    spit(dir / "zero.hair", zero);
    EXPECT_NE(std::string::npos, errorText(dir / "zero.hair").find("no strands"));
    std::string noPoints = bytes;
    putU32(noPoints, 12, 0x1);
    spit(dir / "nopoints.hair", noPoints);
    EXPECT_NE(std::string::npos, errorText(dir / "nopoints.hair").find("no points array"));
    std::string notHair = bytes;
    notHair[0] = 'X';
    spit(dir / "nothair.hair", notHair);
    EXPECT_NE(std::string::npos, errorText(dir / "nothair.hair").find("not a cyHair file"));
}

TEST_F(HairFiles, CyHairExtraArraysAreSkippedButTheirSizesChecked)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    std::string bytes = slurp(kBangsHair);
    putU32(bytes, 12, 0x3 | 0x4 | 0x10); // + thickness, colour
    const std::string full = bytes + std::string(1165 * 4 + 1165 * 12, '\0');
    spit(dir / "extras.hair", full);
    Result<HairReadResult> r = readHair((dir / "extras.hair").string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    expectBitIdentical(bangs, r.value().strands);
    ASSERT_EQ(1u, r.value().warnings.size());
    EXPECT_NE(std::string::npos, r.value().warnings[0].find("thickness and colour")) << r.value().warnings[0];

    spit(dir / "short.hair", full.substr(0, full.size() - 1));
    EXPECT_NE(std::string::npos, errorText(dir / "short.hair").find("thickness, colour arrays"));
}

TEST_F(HairFiles, CyHairWithoutSegmentsArrayUsesTheDefault)
{
    std::string bytes(128, '\0');
    std::memcpy(bytes.data(), "HAIR", 4);
    putU32(bytes, 4, 2); // strands
    putU32(bytes, 8, 8); // points
    putU32(bytes, 12, 0x2); // points only
    putU32(bytes, 16, 3); // default segments
    for (int i = 0; i < 24; ++i)
        appendF32(bytes, float(i));
    spit(dir / "default.hair", bytes);
    const HairCurves c = readOk(dir / "default.hair");
    ASSERT_EQ(2u, c.strandCount());
    EXPECT_EQ(4u, c.pointsIn(1));
    EXPECT_EQ(glm::vec3(12, 13, 14), c.positions[4]);

    putU32(bytes, 16, 2);
    spit(dir / "mismatch.hair", bytes);
    EXPECT_NE(
        std::string::npos, errorText(dir / "mismatch.hair").find("2 strands of 2 segments (6 points) but 8 points"));
}

TEST_F(HairFiles, UscDataClaimingTwoBillionStrandsIsRefusedAtOnce)
{
    std::string tiny;
    appendI32(tiny, std::numeric_limits<std::int32_t>::max());
    appendI32(tiny, 2);
    appendF32(tiny, 0.0f);
    spit(dir / "tiny.data", tiny);
    // Refused from the header and the file's size (the message says so), before any allocation.
    const std::string message = errorText(dir / "tiny.data");
    EXPECT_EQ((dir / "tiny.data").string()
            + ": byte 0: the header claims 2147483647 strands but the 12-byte file can hold at most 2",
        message);

    // One strand claiming a billion points.
    std::string greedy;
    appendI32(greedy, 1);
    appendI32(greedy, 1'000'000'000);
    for (int i = 0; i < 6; ++i)
        appendF32(greedy, 1.0f);
    spit(dir / "greedy.data", greedy);
    EXPECT_EQ(
        (dir / "greedy.data").string() + ": byte 4: strand 0 claims 1000000000 points but the file holds only 2 more",
        errorText(dir / "greedy.data"));

    std::string negative;
    appendI32(negative, -5);
    spit(dir / "negative.data", negative);
    EXPECT_NE(std::string::npos, errorText(dir / "negative.data").find("negative (-5)"));
    std::string negativePoints;
    appendI32(negativePoints, 1);
    appendI32(negativePoints, -2);
    spit(dir / "negpoints.data", negativePoints);
    EXPECT_NE(std::string::npos, errorText(dir / "negpoints.data").find("strand 0 claims a negative point count (-2)"));
}

TEST_F(HairFiles, UscSinglePointStrandsAreSkippedWithAWarning)
{
    std::string bytes;
    appendI32(bytes, 4);
    const int counts[] = { 1, 3, 1, 2 };
    for (int n : counts) {
        appendI32(bytes, n);
        for (int i = 0; i < 3 * n; ++i)
            appendF32(bytes, float(n * 10 + i));
    }
    bytes += "junk";
    spit(dir / "single.data", bytes);
    Result<HairReadResult> r = readHair((dir / "single.data").string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    EXPECT_EQ(2u, r.value().strands.strandCount());
    EXPECT_EQ(5u, r.value().strands.pointCount());
    EXPECT_EQ(glm::vec3(20, 21, 22), r.value().strands.positions[3]);
    ASSERT_EQ(2u, r.value().warnings.size());
    EXPECT_EQ("skipped 2 strands of fewer than two points (strands 0, 2)", r.value().warnings[0]);
    EXPECT_NE(std::string::npos, r.value().warnings[1].find("4 bytes after the last strand"));

    std::string onlySingles;
    appendI32(onlySingles, 1);
    appendI32(onlySingles, 1);
    for (int i = 0; i < 3; ++i)
        appendF32(onlySingles, 0.0f);
    spit(dir / "singles.data", onlySingles);
    EXPECT_NE(std::string::npos, errorText(dir / "singles.data").find("no strands of two or more points"));
}

TEST_F(HairFiles, NonFinitePointIsRefusedWithItsIndex)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    const HairCurves bangs = readOk(kBangsHair);
    std::size_t strand17 = 0;
    while (bangs.offsets[strand17 + 1] <= 17)
        ++strand17;

    std::string hair = slurp(kBangsHair);
    const std::size_t hairAt = 128 + 200 + 17 * 12 + 4;
    putF32(hair, hairAt, std::numeric_limits<float>::quiet_NaN());
    spit(dir / "nan.hair", hair);
    EXPECT_EQ((dir / "nan.hair").string() + ": byte " + std::to_string(hairAt - 4) + ": point 17 (strand "
            + std::to_string(strand17) + ") is not finite",
        errorText(dir / "nan.hair"));

    // In the .data file point 17 sits after one point count per strand up to its own.
    std::string data = slurp(kBangsData);
    const std::size_t dataAt = 4 + 4 * (strand17 + 1) + 17 * 12 + 8;
    putF32(data, dataAt, std::numeric_limits<float>::infinity());
    spit(dir / "inf.data", data);
    EXPECT_NE(std::string::npos,
        errorText(dir / "inf.data").find("point 17 (strand " + std::to_string(strand17) + ") is not finite"));

    // Writers refuse them too, and write nothing.
    HairCurves broken = smallGroom();
    broken.positions[3].y = -std::numeric_limits<float>::infinity();
    for (const char* name : { "w.hair", "w.data", "w.obj", "w.gltf", "w.glb" }) {
        const Result<void> error = writeHair((dir / name).string(), broken);
        ASSERT_FALSE(error.ok()) << name;
        EXPECT_NE(std::string::npos, error.error().message.find("point 3 (strand 1) is not finite"))
            << error.error().toString();
        EXPECT_FALSE(fs::exists(dir / name));
    }
}

TEST_F(HairFiles, TruncatedAndCorruptedCopiesNeverCrash)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    for (const fs::path& sample : { kBangsHair, kBangsData }) {
        const std::string bytes = slurp(sample);
        const fs::path copy = dir / ("copy" + sample.extension().string());
        // Every length through the header, the segment counts and the first strands, then every 7th
        // and the last few: each is refused (the counts promise more than is there), none crashes.
        for (std::size_t length = 0; length < bytes.size();
             length += (length < 600 || length + 16 >= bytes.size()) ? 1 : 7) {
            spit(copy, bytes.substr(0, length));
            Result<HairReadResult> r = readHair(copy.string());
            ASSERT_FALSE(r.ok()) << sample << " cut to " << length << " bytes was read";
            ASSERT_NE(std::string::npos, r.error().toString().find(copy.string())) << r.error().toString();
        }
        // Random bytes overwritten: refused or read, never a crash or inconsistent strands.
        std::mt19937 random(1234);
        for (int trial = 0; trial < 1000; ++trial) {
            std::string corrupt = bytes;
            const int flips = 1 + trial % 4;
            for (int f = 0; f < flips; ++f) {
                const std::size_t at
                    = trial % 2 ? random() % 160 : random() % corrupt.size(); // the header half the time
                corrupt[at] = static_cast<char>(random());
            }
            spit(copy, corrupt);
            Result<HairReadResult> r = readHair(copy.string());
            if (r.ok()) {
                const HairCurves& c = r.value().strands;
                ASSERT_EQ(c.offsets.back(), c.positions.size());
                for (const glm::vec3& p : c.positions)
                    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            }
        }
    }
}

TEST_F(HairFiles, UnknownExtensionsListTheSupportedOnes)
{
    EXPECT_EQ((std::vector<std::string>{ "hair", "data", "obj", "gltf", "glb" }), hairReadExtensions());
    EXPECT_EQ((std::vector<std::string>{ "hair", "data", "obj", "gltf", "glb" }), hairWriteExtensions());
    EXPECT_EQ(HairFormat::CyHair, hairFormatForPath("a/b.HaIr"));
    EXPECT_EQ(HairFormat::Glb, hairFormatForPath("x.GLB"));
    EXPECT_FALSE(hairFormatForPath("x.abc").has_value());
    EXPECT_FALSE(hairFormatForPath("hair").has_value());

    Result<HairReadResult> r = readHair((dir / "groom.abc").string());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ((dir / "groom.abc").string()
            + ": '.abc' is not a hair file extension Wisp knows; Wisp reads hair from .hair (cyHair), .data "
              "(USC-HairSalon), "
              ".obj (OBJ polylines), .gltf (glTF), .glb (binary glTF)",
        r.error().toString());
    r = readHair((dir / "groom.glb").string()); // a readable format, but no such file
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, (dir / "groom.glb").string());

    const Result<void> error = writeHair((dir / "groom").string(), smallGroom());
    ASSERT_FALSE(error.ok());
    EXPECT_EQ(
        "the file name has no extension to tell its format; Wisp writes hair as .hair (cyHair), .data (USC-HairSalon), "
        ".obj (OBJ polylines), .gltf (glTF), .glb (binary glTF)",
        error.error().message);
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(HairFiles, MissingFolderOrBlockedTargetLeavesNoFile)
{
    const HairCurves groom = smallGroom();
    for (const char* name : { "g.hair", "g.data", "g.obj", "g.gltf", "g.glb" }) {
        SCOPED_TRACE(name);
        const fs::path missing = dir / "no-such-folder" / name;
        const Result<void> error = writeHair(missing.string(), groom);
        ASSERT_FALSE(error.ok());
        EXPECT_EQ(missing.string(), error.error().file);
        EXPECT_NE(std::string::npos, error.error().message.find("cannot write there")) << error.error().toString();
        EXPECT_FALSE(fs::exists(dir / "no-such-folder"));

        // A folder where the file should go: the rename fails and the temporary file is removed.
        fs::create_directory(dir / name);
        const Result<void> blocked = writeHair((dir / name).string(), groom);
        ASSERT_FALSE(blocked.ok());
        EXPECT_NE(std::string::npos, blocked.error().toString().find(name)) << blocked.error().toString();
        EXPECT_TRUE(fs::is_directory(dir / name));
    }
    EXPECT_EQ((std::vector<std::string>{ "g.data", "g.glb", "g.gltf", "g.hair", "g.obj" }), filesInDir());

    // Reading a folder, or a file that is not there.
    EXPECT_NE(std::string::npos, errorText(dir / "g.hair").find("folder"));
    EXPECT_NE(std::string::npos, errorText(dir / "absent.data").find("does not exist"));

    // Nothing to write.
    const Result<void> empty = writeHair((dir / "empty.hair").string(), HairCurves{});
    ASSERT_FALSE(empty.ok());
    EXPECT_NE(std::string::npos, empty.error().message.find("no strands"));
    EXPECT_FALSE(fs::exists(dir / "empty.hair"));
}

TEST_F(HairFiles, OverwritingReplacesTheOldFileWhole)
{
    const fs::path path = dir / "g.hair";
    HairCurves big = smallGroom();
    big.addStrand(40);
    for (glm::vec3& p : big.strandForWrite(3))
        p = glm::vec3(0.5f);
    ASSERT_TRUE(writeHair(path.string(), big));
    ASSERT_TRUE(writeHair(path.string(), smallGroom()));
    expectBitIdentical(smallGroom(), readOk(path));
    EXPECT_EQ(std::vector<std::string>{ "g.hair" }, filesInDir());
}

TEST_F(HairFiles, CyHairRefusesStrandsItCannotHold)
{
    HairCurves longStrand;
    longStrand.addStrand(70000);
    for (std::size_t i = 0; i < longStrand.positions.size(); ++i)
        longStrand.positions[i] = { 0.0f, float(i) * 1e-4f, 0.0f };
    const Result<void> error = writeHair((dir / "long.hair").string(), longStrand);
    ASSERT_FALSE(error.ok());
    EXPECT_NE(std::string::npos, error.error().message.find("strand 0 has 70000 points; cyHair holds at most 65,536"))
        << error.error().toString();
    EXPECT_FALSE(fs::exists(dir / "long.hair"));
    // USC has no such limit.
    ASSERT_TRUE(writeHair((dir / "long.data").string(), longStrand));
    expectBitIdentical(longStrand, readOk(dir / "long.data"));
}

// Issue 12: a non-finite point in a strand the reader skips (a single point) was never looked
// at, so a file with infinite coordinates was accepted. Any non-finite point refuses the file.
TEST_F(HairFiles, NonFinitePointInASkippedStrandIsRefused)
{
    std::string data;
    appendI32(data, 2);
    appendI32(data, 1);
    appendF32(data, std::numeric_limits<float>::infinity());
    appendF32(data, 0.0f);
    appendF32(data, 0.0f);
    appendI32(data, 2);
    for (int i = 0; i < 6; ++i)
        appendF32(data, 0.1f * static_cast<float>(i));
    spit(dir / "single-inf.data", data);
    EXPECT_EQ((dir / "single-inf.data").string() + ": byte 8: point 0 (strand 0) is not finite",
        errorText(dir / "single-inf.data"));

    std::string hair("HAIR", 4);
    appendI32(hair, 2); // strands
    appendI32(hair, 4); // points
    appendI32(hair, 3); // flags: segments and points arrays
    appendI32(hair, 0); // default segments
    for (int i = 0; i < 5; ++i)
        appendF32(hair, 1.0f); // default thickness, transparency, colour
    hair.append(88, '\0');
    ASSERT_EQ(hair.size(), 128u);
    hair.append("\0\0\x02\0", 4); // strand 0: 0 segments (1 point), strand 1: 2 segments
    appendF32(hair, 0.0f);
    appendF32(hair, -std::numeric_limits<float>::infinity());
    appendF32(hair, 0.0f);
    for (int i = 0; i < 9; ++i)
        appendF32(hair, 0.1f * static_cast<float>(i));
    spit(dir / "single-inf.hair", hair);
    EXPECT_EQ((dir / "single-inf.hair").string() + ": byte 132: point 0 (strand 0) is not finite",
        errorText(dir / "single-inf.hair"));
}
