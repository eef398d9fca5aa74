#pragma once
// What the project file tests share: projects to save (the default head, a small one), bit-for-bit
// comparison, a loader that records what it was asked for, and the fixture's scratch folder. The
// tests are split by topic: ProjectFileTest (round trips, the format), ProjectFileSavingTest
// (referenced heads, saving), ProjectFileRefusalTest (damaged files), ProjectFileStyleTest (salon edits).

#include "IoTestSupport.h"
#include "io/Base64.h"
#include "io/MeshReader.h"
#include "io/ProjectFile.h"
#include "sim/geometry/DefaultHead.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace wisp::test::project {

using namespace wisp::io;
namespace fs = std::filesystem;

inline std::uint32_t bitsOf(float f)
{
    return std::bit_cast<std::uint32_t>(f);
}

inline void expectSameBits(const glm::vec3& a, const glm::vec3& b, const char* what)
{
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(bitsOf(a[i]), bitsOf(b[i])) << what << "[" << i << "]";
}

// Bit-identical: every float compared by its bits (so -0 differs from 0 and a rounding would show).
inline void expectBitIdentical(const Project& a, const Project& b)
{
    ASSERT_EQ(a.head.positions.size(), b.head.positions.size());
    EXPECT_EQ(
        std::memcmp(a.head.positions.data(), b.head.positions.data(), a.head.positions.size() * sizeof(glm::vec3)), 0);
    ASSERT_EQ(a.head.triangles.size(), b.head.triangles.size());
    EXPECT_EQ(
        std::memcmp(a.head.triangles.data(), b.head.triangles.data(), a.head.triangles.size() * sizeof(glm::uvec3)), 0);
    EXPECT_EQ(a.headSource, b.headSource);
    EXPECT_EQ(a.headEmbedded, b.headEmbedded);
    EXPECT_EQ(bitsOf(a.headImportScale), bitsOf(b.headImportScale));
    EXPECT_EQ(a.headImportUp, b.headImportUp);
    EXPECT_EQ(a.headImportFront, b.headImportFront);
    for (const ParameterInfo& info : allParameters())
        EXPECT_EQ(std::bit_cast<std::uint64_t>(a.parameters.get(info.id)),
            std::bit_cast<std::uint64_t>(b.parameters.get(info.id)))
            << info.key;
    ASSERT_EQ(a.regions.size(), b.regions.size());
    for (std::size_t r = 0; r < a.regions.size(); ++r) {
        const GrowthRegion &x = a.regions[r], &y = b.regions[r];
        EXPECT_EQ(x.id, y.id);
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.visible, y.visible);
        ASSERT_EQ(x.weights.size(), y.weights.size());
        EXPECT_EQ(std::memcmp(x.weights.data(), y.weights.data(), x.weights.size() * sizeof(float)), 0);
        EXPECT_EQ(x.values, y.values);
        expectSameBits(x.rootColour, y.rootColour, "rootColour");
        expectSameBits(x.tipColour, y.tipColour, "tipColour");
    }
    EXPECT_EQ(a.soloRegion, b.soloRegion);
    expectSameBits(a.camera.pivot, b.camera.pivot, "pivot");
    EXPECT_EQ(bitsOf(a.camera.yawRadians), bitsOf(b.camera.yawRadians));
    EXPECT_EQ(bitsOf(a.camera.pitchRadians), bitsOf(b.camera.pitchRadians));
    EXPECT_EQ(bitsOf(a.camera.distanceMetres), bitsOf(b.camera.distanceMetres));
    EXPECT_EQ(bitsOf(a.camera.fovYDegrees), bitsOf(b.camera.fovYDegrees));
    EXPECT_EQ(a.style, b.style);
    if (a.style.size() == b.style.size())
        for (auto x = a.style.begin(), y = b.style.begin(); x != a.style.end(); ++x, ++y) {
            const StrandStyle &p = x->second, &q = y->second;
            EXPECT_EQ(x->first, y->first);
            EXPECT_EQ(bitsOf(p.lengthMetres), bitsOf(q.lengthMetres)) << x->first;
            EXPECT_EQ(bitsOf(p.curlRadiusMetres), bitsOf(q.curlRadiusMetres)) << x->first;
            EXPECT_EQ(bitsOf(p.curlTurnsPerMetre), bitsOf(q.curlTurnsPerMetre)) << x->first;
            EXPECT_EQ(bitsOf(p.stiffnessScale), bitsOf(q.stiffnessScale)) << x->first;
            EXPECT_EQ(bitsOf(p.wetness), bitsOf(q.wetness)) << x->first;
            ASSERT_EQ(p.shape.size(), q.shape.size()) << x->first;
            if (!p.shape.empty()) { // memcmp of no bytes still wants real pointers
                EXPECT_EQ(std::memcmp(p.shape.data(), q.shape.data(), p.shape.size() * sizeof(glm::vec3)), 0)
                    << x->first;
            }
        }
}

// Two regions over `head`, with awkward numbers everywhere: thirds, tiny and negative zeros.
inline Project makeProject(TriangleMesh head, std::vector<float> scalpWeights)
{
    Project project;
    const std::size_t n = head.vertexCount();
    project.head = std::move(head);
    EXPECT_EQ(project.parameters.set(Param::Gravity, 0.1 + 0.2), "");
    EXPECT_EQ(project.parameters.set(Param::WindAzimuth, 1.0 / 3.0), "");
    EXPECT_EQ(project.parameters.set(Param::Segments, 33), "");
    EXPECT_EQ(project.parameters.set(Param::SimulateAllStrands, 1), "");
    EXPECT_EQ(project.parameters.set(Param::Length, 0.123456789012345), ""); // a Wisp key in the globals too

    GrowthRegion scalp;
    scalp.id = 0;
    scalp.name = "Scalp";
    scalp.weights = std::move(scalpWeights);
    EXPECT_EQ(scalp.values.set(Param::CurlRadius, 0.007), "");
    GrowthRegion fringe;
    fringe.id = 7;
    fringe.name = "Fringe «front»";
    fringe.visible = false;
    std::vector<float>& fringeWeights = fringe.weights.forWrite();
    fringeWeights.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        fringeWeights[i] = std::fmod(static_cast<float>(i) / 3.0f, 1.0f);
    fringeWeights[0] = 1e-40f; // subnormal
    fringeWeights[n - 1] = 1.0f;
    EXPECT_EQ(fringe.values.set(Param::ClumpDegree, -0.25), "");
    EXPECT_EQ(fringe.values.set(Param::WispSize, 3), "");
    fringe.rootColour = { 1.0f / 3.0f, 0.0f, 1.0f };
    fringe.tipColour = { 0.1f, 0.2f, 0.7f };
    project.regions = { scalp, fringe };
    project.soloRegion = 7;
    project.camera = { { 0.01f, 1.6f, -0.0f }, 2.5f / 3.0f, -0.2f, 0.85f, 37.5f };
    project.headImportScale = 0.001f; // embedded: kept as it was, not applied again
    project.headImportOffset = { 0.0f, -1.0f / 3.0f, 0.0125f };
    project.headImportUp = io::Axis::PosX; // CT2Hair's heads are +X up, the face -Y
    project.headImportFront = io::Axis::NegY;
    return project;
}

inline Project defaultHeadProject()
{
    DefaultHead head = makeDefaultHead();
    return makeProject(std::move(head.mesh), std::move(head.growthWeights));
}

// A small closed mesh: an octahedron, 6 vertices and 8 triangles.
inline TriangleMesh octahedron(float radius)
{
    TriangleMesh mesh;
    mesh.positions = { { radius, 0, 0 }, { -radius, 0, 0 }, { 0, radius, 0 }, { 0, -radius, 0 }, { 0, 0, radius },
        { 0, 0, -radius } };
    mesh.triangles
        = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };
    return mesh;
}

inline Project smallProject()
{
    TriangleMesh mesh = octahedron(0.1f);
    return makeProject(mesh, std::vector<float>(mesh.vertexCount(), 0.5f));
}

inline void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

inline std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

// The OBJ text of `mesh`, its coordinates divided by `scale` (a head modelled in centimetres).
inline std::string objText(const TriangleMesh& mesh, float scale)
{
    std::string text = "# test head\n";
    char line[128];
    for (const glm::vec3& p : mesh.positions) {
        std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x / scale, p.y / scale, p.z / scale);
        text += line;
    }
    for (const glm::uvec3& t : mesh.triangles)
        text += "f " + std::to_string(t.x + 1) + " " + std::to_string(t.y + 1) + " " + std::to_string(t.z + 1) + "\n";
    return text;
}

// The editor's loader: readMesh, warnings dropped. Records the paths it was asked for.
struct RecordingLoader {
    std::vector<std::string> asked;
    HeadLoader loader()
    {
        return [this](const std::string& absolutePath) -> Result<TriangleMesh> {
            asked.push_back(absolutePath);
            Result<MeshReadResult> read = readMesh(absolutePath);
            if (!read)
                return read.error();
            return std::move(read).value().mesh;
        };
    }
};

class ProjectFileTest : public ::testing::Test {
protected:
    void SetUp() override { m_dir = wisp::test::freshTestFolder("wisp-project"); }
    void TearDown() override { fs::remove_all(m_dir); }

    // The error reading `text` as a project gives; "" when it loads.
    std::string errorOf(const std::string& text)
    {
        const fs::path path = m_dir / "edited.wisp";
        writeText(path, text);
        const Result<ProjectReadResult> result = readProject(path.string());
        return result ? std::string() : result.error().location + ": " + result.error().message;
    }

    // A valid project's JSON, to damage one key at a time.
    nlohmann::json validJson()
    {
        const fs::path path = m_dir / "valid.wisp";
        EXPECT_TRUE(writeProject(path.string(), smallProject()));
        return nlohmann::json::parse(readText(path));
    }

    fs::path m_dir;
};

} // namespace wisp::test::project
