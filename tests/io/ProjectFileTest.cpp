// Projects: a saved project reopens bit for bit; a referenced head is found relative to the
// project file; saving keeps the previous file as .bak and never leaves half a file; damaged and
// inconsistent files are refused with the key path, never a crash.

#include "io/ProjectFile.h"
#include "IoTestSupport.h"
#include "io/Base64.h"
#include "io/MeshReader.h"
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

using namespace wisp;
using namespace wisp::io;
namespace fs = std::filesystem;

namespace {

std::uint32_t bitsOf(float f)
{
    return std::bit_cast<std::uint32_t>(f);
}

void expectSameBits(const glm::vec3& a, const glm::vec3& b, const char* what)
{
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(bitsOf(a[i]), bitsOf(b[i])) << what << "[" << i << "]";
}

// Bit-identical: every float compared by its bits (so -0 differs from 0 and a rounding would show).
void expectBitIdentical(const Project& a, const Project& b)
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
Project makeProject(TriangleMesh head, std::vector<float> scalpWeights)
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
    fringe.weights.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        fringe.weights[i] = std::fmod(static_cast<float>(i) / 3.0f, 1.0f);
    fringe.weights[0] = 1e-40f; // subnormal
    fringe.weights[n - 1] = 1.0f;
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

Project defaultHeadProject()
{
    DefaultHead head = makeDefaultHead();
    return makeProject(std::move(head.mesh), std::move(head.growthWeights));
}

// A small closed mesh: an octahedron, 6 vertices and 8 triangles.
TriangleMesh octahedron(float radius)
{
    TriangleMesh mesh;
    mesh.positions = { { radius, 0, 0 }, { -radius, 0, 0 }, { 0, radius, 0 }, { 0, -radius, 0 }, { 0, 0, radius },
        { 0, 0, -radius } };
    mesh.triangles
        = { { 0, 2, 4 }, { 2, 1, 4 }, { 1, 3, 4 }, { 3, 0, 4 }, { 2, 0, 5 }, { 1, 2, 5 }, { 3, 1, 5 }, { 0, 3, 5 } };
    return mesh;
}

Project smallProject()
{
    TriangleMesh mesh = octahedron(0.1f);
    return makeProject(mesh, std::vector<float>(mesh.vertexCount(), 0.5f));
}

void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>() };
}

// The OBJ text of `mesh`, its coordinates divided by `scale` (a head modelled in centimetres).
std::string objText(const TriangleMesh& mesh, float scale)
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

} // namespace

TEST_F(ProjectFileTest, RoundTripOfTheDefaultHeadIsBitIdentical)
{
    const Project project = defaultHeadProject();
    const std::string path = (m_dir / "scene.wisp").string();
    const Result<void> written = writeProject(path, project);
    ASSERT_TRUE(written) << written.error().toString();
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    expectBitIdentical(read.value().project, project);
    // Saving what was opened writes the same text.
    EXPECT_EQ(projectToJson(read.value().project, path), readText(path));
}

TEST_F(ProjectFileTest, TheBodyToggleRoundTrips)
{
    for (bool on : { false, true }) {
        Project project = smallProject();
        ASSERT_EQ(project.parameters.set(Param::Body, on ? 1 : 0), "");
        const std::string path = (m_dir / "body.wisp").string();
        ASSERT_TRUE(writeProject(path, project));
        const Result<ProjectReadResult> read = readProject(path);
        ASSERT_TRUE(read) << read.error().toString();
        EXPECT_EQ(read.value().project.parameters.get(Param::Body), on ? 1.0 : 0.0);
        EXPECT_EQ(nlohmann::json::parse(readText(path))["parameters"]["body"], on);
    }
}

TEST_F(ProjectFileTest, ImportedStrandsComeBackBitIdentical)
{
    Project project = defaultHeadProject();
    auto strands = std::make_shared<HairCurves>();
    for (int s = 0; s < 3; ++s) {
        const auto points = strands->strandForWrite(strands->addStrand(static_cast<std::uint32_t>(4 + s)));
        for (std::size_t j = 0; j < points.size(); ++j)
            points[j] = glm::vec3(0.1f * s, 0.3f - 0.017f * j, 1.0f / 3.0f);
    }
    project.regions.back().importedStrands = strands;
    const std::string path = (m_dir / "imported.wisp").string();
    ASSERT_TRUE(writeProject(path, project));
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    const auto& back = read.value().project.regions.back().importedStrands;
    ASSERT_TRUE(back);
    EXPECT_EQ(back->offsets, strands->offsets);
    EXPECT_EQ(back->positions, strands->positions); // exact: floats travel as their bits

    // Offsets that do not describe the points are refused with their key path.
    std::string text = readText(path);
    const std::string good = "\"offsets\": \"";
    const std::size_t at = text.find(good);
    ASSERT_NE(at, std::string::npos);
    text.replace(at + good.size(), 4, "AQAA"); // first offset 1 instead of 0
    const Result<ProjectReadResult> broken = parseProject(text, path);
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().toString().find("imported_strands.offsets"), std::string::npos)
        << broken.error().toString();
}

TEST_F(ProjectFileTest, FileIsVersionedJsonWithBase64Arrays)
{
    const Project project = smallProject();
    const nlohmann::json json = nlohmann::json::parse(projectToJson(project, (m_dir / "p.wisp").string()));
    EXPECT_EQ(json["format"], "wisp-project");
    EXPECT_EQ(json["version"], 1);
    EXPECT_EQ(json["head"]["vertex_count"], 6);
    EXPECT_EQ(json["head"]["triangle_count"], 8);
    // Little-endian float32: 0.1f is 0x3DCCCCCD, stored CD CC CC 3D.
    const auto positions = base64Decode(json["head"]["positions"].get<std::string>());
    ASSERT_TRUE(positions);
    ASSERT_EQ(positions->size(), 6u * 3u * 4u);
    EXPECT_EQ((std::vector<std::uint8_t>(positions->begin(), positions->begin() + 4)),
        (std::vector<std::uint8_t>{ 0xCD, 0xCC, 0xCC, 0x3D }));
    EXPECT_EQ(json["regions"][1]["id"], 7);
    EXPECT_EQ(json["regions"][1]["visible"], false);
    EXPECT_EQ(json["regions"][1]["wisp"]["wisp_size"], 3);
    EXPECT_FALSE(json["regions"][1]["wisp"].contains("gravity"));
    EXPECT_EQ(json["parameters"].size(), kParamCount);
    EXPECT_EQ(json["solo_region"], 7);
    EXPECT_EQ(json["camera"]["fov_y_degrees"], 37.5);
    EXPECT_EQ(json["regions"][1]["tip_colour"][0].dump(), "0.1"); // shortest text that gives 0.1f back

    Project noSolo = project;
    noSolo.soloRegion = kNoSolo;
    EXPECT_TRUE(nlohmann::json::parse(projectToJson(noSolo, "p.wisp"))["solo_region"].is_null());
}

TEST_F(ProjectFileTest, ReferencedHeadResolvesRelativeToTheProjectFile)
{
    // A lopsided head modelled in centimetres with +Z up, beside a project in a sibling folder;
    // imported at 0.01, turned upright and moved, as io/HeadPlacement does.
    TriangleMesh file = octahedron(10.0f);
    file.positions[0].x = 14.0f;
    file.positions[2].y = 12.0f;
    file.positions[4].z = 11.0f;
    fs::create_directories(m_dir / "heads");
    fs::create_directories(m_dir / "shots");
    const fs::path headPath = m_dir / "heads" / "octa.obj";
    writeText(headPath, objText(file, 1.0f));
    Project project = makeProject(file, std::vector<float>(6, 0.25f));
    project.headImportScale = 0.01f;
    project.headImportOffset = { 0.0f, -0.02f, 0.005f };
    project.headImportUp = io::Axis::PosZ;
    project.headImportFront = io::Axis::NegY;
    for (glm::vec3& p : project.head.positions)
        p = glm::vec3(p.x, p.z, -p.y) * 0.01f + project.headImportOffset;
    project.headEmbedded = false;
    project.headSource = headPath.string();

    const fs::path projectPath = m_dir / "shots" / "take1.wisp";
    ASSERT_TRUE(writeProject(projectPath.string(), project));
    const nlohmann::json json = nlohmann::json::parse(readText(projectPath));
    EXPECT_EQ(json["head"]["source"], "../heads/octa.obj");
    EXPECT_EQ(json["head"]["absolute_source"], headPath.string());
    EXPECT_FALSE(json["head"].contains("positions"));

    // Move the whole folder: the relative path still finds the head.
    const fs::path moved = m_dir / "moved";
    fs::create_directories(moved);
    fs::rename(m_dir / "heads", moved / "heads");
    fs::rename(m_dir / "shots", moved / "shots");
    RecordingLoader recording;
    const Result<ProjectReadResult> read = readProject((moved / "shots" / "take1.wisp").string(), recording.loader());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    ASSERT_EQ(recording.asked.size(), 1u);
    EXPECT_EQ(recording.asked[0], (moved / "heads" / "octa.obj").string());
    EXPECT_TRUE(fs::path(recording.asked[0]).is_absolute());

    // The head is placed again as the import placed it (to rounding: the file holds 9 digits).
    Project got = read.value().project;
    ASSERT_EQ(got.head.vertexCount(), project.head.vertexCount());
    for (std::size_t v = 0; v < got.head.vertexCount(); ++v)
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(got.head.positions[v][i], project.head.positions[v][i], 1e-7) << v;
    EXPECT_NEAR(got.head.positions[0].x, 0.14, 1e-7); // x stays x
    EXPECT_NEAR(got.head.positions[4].y, 0.11 - 0.02, 1e-7); // file +Z is +Y
    got.head.positions = project.head.positions;
    Project expected = project;
    expected.headSource = (moved / "heads" / "octa.obj").string();
    expectBitIdentical(got, expected);
}

TEST_F(ProjectFileTest, ProjectMovedAloneFallsBackToTheHeadsAbsolutePathWithAWarning)
{
    const fs::path headPath = m_dir / "octa.obj";
    writeText(headPath, objText(octahedron(0.1f), 1.0f));
    Project project = smallProject();
    project.headEmbedded = false;
    project.headSource = headPath.string();
    project.headImportScale = 1.0f; // a 0.2 m head; smallProject's 0.001 would make it 0.2 mm, which is refused
    fs::create_directories(m_dir / "a" / "b");
    ASSERT_TRUE(writeProject((m_dir / "p.wisp").string(), project));
    fs::rename(m_dir / "p.wisp", m_dir / "a" / "b" / "p.wisp");
    RecordingLoader recording;
    const Result<ProjectReadResult> read = readProject((m_dir / "a" / "b" / "p.wisp").string(), recording.loader());
    ASSERT_TRUE(read) << read.error().toString();
    ASSERT_EQ(read.value().warnings.size(), 1u);
    EXPECT_EQ(read.value().warnings[0].rfind(
                  "head.source: \"octa.obj\" is not at " + (m_dir / "a" / "b" / "octa.obj").string(), 0),
        0u)
        << read.value().warnings[0];
    EXPECT_EQ(read.value().project.headSource, headPath.string());
}

TEST_F(ProjectFileTest, MissingReferencedHeadNamesBothPaths)
{
    const fs::path headPath = m_dir / "heads" / "gone.obj";
    fs::create_directories(headPath.parent_path());
    writeText(headPath, objText(octahedron(0.1f), 1.0f));
    Project project = smallProject();
    project.headEmbedded = false;
    project.headSource = headPath.string();
    const fs::path projectPath = m_dir / "p.wisp";
    ASSERT_TRUE(writeProject(projectPath.string(), project));
    fs::remove(headPath);

    RecordingLoader recording;
    const Result<ProjectReadResult> read = readProject(projectPath.string(), recording.loader());
    ASSERT_FALSE(read);
    EXPECT_TRUE(recording.asked.empty());
    EXPECT_EQ(read.error().file, projectPath.string());
    EXPECT_EQ(read.error().location, "head.source");
    EXPECT_EQ(read.error().message,
        "cannot find the head file " + headPath.string() + " (\"heads/gone.obj\" next to the project "
            + projectPath.string() + ")");

    // A loader's own error is passed on, with the head's file named.
    writeText(headPath, "v 0 0 0\nf 1 2 3\n");
    const Result<ProjectReadResult> broken = readProject(projectPath.string(), recording.loader());
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().message.find(headPath.string()), std::string::npos) << broken.error().message;
    // And without a loader, a referenced head cannot be read.
    EXPECT_FALSE(readProject(projectPath.string()));
}

TEST_F(ProjectFileTest, ReferencedHeadThatChangedIsRefused)
{
    const fs::path headPath = m_dir / "octa.obj";
    writeText(headPath, objText(octahedron(0.1f), 1.0f));
    Project project = smallProject();
    project.headEmbedded = false;
    project.headSource = headPath.string();
    ASSERT_TRUE(writeProject((m_dir / "p.wisp").string(), project));
    TriangleMesh bigger = octahedron(0.1f);
    bigger.positions.push_back({ 0.2f, 0.2f, 0.2f });
    writeText(headPath, objText(bigger, 1.0f));
    RecordingLoader recording;
    const Result<ProjectReadResult> read = readProject((m_dir / "p.wisp").string(), recording.loader());
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().location, "head.source");
    EXPECT_NE(read.error().message.find("has 7 vertices, but the project was painted on 6"), std::string::npos);
}

TEST_F(ProjectFileTest, SavingOverAProjectKeepsTheOldOneAsBak)
{
    const std::string path = (m_dir / "p.wisp").string();
    const Project first = smallProject();
    Project second = first;
    second.regions[0].name = "Renamed";
    second.camera.yawRadians = 1.25f;
    ASSERT_TRUE(writeProject(path, first));
    EXPECT_FALSE(fs::exists(path + ".bak"));
    ASSERT_TRUE(writeProject(path, second));
    const Result<ProjectReadResult> now = readProject(path);
    const Result<ProjectReadResult> backup = readProject(path + ".bak");
    ASSERT_TRUE(now);
    ASSERT_TRUE(backup);
    expectBitIdentical(now.value().project, second);
    expectBitIdentical(backup.value().project, first);
    // A third save replaces the backup with the second version.
    ASSERT_TRUE(writeProject(path, first));
    expectBitIdentical(readProject(path + ".bak").value().project, second);
    // Nothing else is left beside them.
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(m_dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{ "p.wisp", "p.wisp.bak" }));
}

TEST_F(ProjectFileTest, SavingThroughASymbolicLinkKeepsTheLinkAndAPrivateFileStaysPrivate)
{
    fs::create_directories(m_dir / "real");
    const fs::path real = m_dir / "real" / "p.wisp";
    const fs::path link = m_dir / "p.wisp";
    const Project first = smallProject();
    Project second = first;
    second.regions[0].name = "Renamed";
    ASSERT_TRUE(writeProject(real.string(), first));
    ASSERT_EQ(::chmod(real.c_str(), 0600), 0);
    fs::create_symlink("real/p.wisp", link);

    ASSERT_TRUE(writeProject(link.string(), second));
    EXPECT_TRUE(fs::is_symlink(link));
    expectBitIdentical(readProject(real.string()).value().project, second);
    // The backup is beside the file the link leads to, and as private as it.
    expectBitIdentical(readProject(real.string() + ".bak").value().project, first);
    EXPECT_EQ(fs::status(real).permissions(), fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_EQ(fs::status(real.string() + ".bak").permissions(), fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_EQ(std::distance(fs::directory_iterator(m_dir / "real"), fs::directory_iterator()), 2);
}

TEST_F(ProjectFileTest, SavingIntoAMissingFolderFailsCleanly)
{
    const std::string path = (m_dir / "nowhere" / "p.wisp").string();
    const Result<void> result = writeProject(path, smallProject());
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().file, path);
    EXPECT_FALSE(result.error().message.empty());
    EXPECT_FALSE(fs::exists(m_dir / "nowhere"));
    EXPECT_TRUE(fs::is_empty(m_dir));
}

TEST_F(ProjectFileTest, AProjectThatCouldNotBeReadBackIsNotSaved)
{
    const std::string path = (m_dir / "p.wisp").string();
    Project project = smallProject();
    project.regions[0].weights.pop_back();
    const Result<void> result = writeProject(path, project);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().location, "regions[0].weights");
    EXPECT_EQ(result.error().message, "not saved: 5 weights for a head of 6 vertices");
    EXPECT_FALSE(fs::exists(path));

    project = smallProject();
    project.camera.distanceMetres = std::nanf("");
    EXPECT_EQ(writeProject(path, project).error().location, "camera.distance_metres");
    project = smallProject();
    project.regions[1].id = 0;
    EXPECT_EQ(writeProject(path, project).error().message, "not saved: 0 is already the id of regions[0]");
    EXPECT_TRUE(fs::is_empty(m_dir));
}

TEST_F(ProjectFileTest, TruncatedProjectsAreRefusedAtEveryLength)
{
    const std::string path = (m_dir / "p.wisp").string();
    ASSERT_TRUE(writeProject(path, smallProject()));
    const std::string text = readText(path);
    const std::size_t end = text.find_last_not_of(" \n") + 1;
    for (std::size_t length = 0; length < end; ++length) {
        const Result<ProjectReadResult> result = parseProject(std::string_view(text).substr(0, length), path);
        ASSERT_FALSE(result) << "length " << length;
        EXPECT_FALSE(result.error().message.empty());
        EXPECT_LT(result.error().toString().size(), 600u) << "length " << length; // no kilobytes of quoted text
    }
    EXPECT_TRUE(parseProject(std::string_view(text).substr(0, end), path));
    // And through files, at a few lengths (writing a file per length is slow on a busy disk).
    const std::string cutPath = (m_dir / "cut.wisp").string();
    for (std::size_t length : { std::size_t(0), std::size_t(1), end / 3, end / 2, end - 1 }) {
        writeText(cutPath, text.substr(0, length));
        EXPECT_FALSE(readProject(cutPath)) << "length " << length;
    }
}

TEST_F(ProjectFileTest, InconsistentProjectsAreRefusedWithTheKeyPath)
{
    const nlohmann::json valid = validJson();
    auto damaged = [&](auto edit) {
        nlohmann::json json = valid;
        edit(json);
        return errorOf(json.dump());
    };
    EXPECT_EQ(errorOf(valid.dump()), "");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][0]["weights"] = encodeFloat32Array(std::vector<float>(5, 0.5f));
    }),
        "regions[0].weights: 5 weights for a head of 6 vertices");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][1]["weights"] = encodeFloat32Array(std::vector<float>{ 0, 0, 1.5f, 0, 0, 0 });
    }),
        "regions[1].weights: the weight of vertex 2 is 1.500000; weights are 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][0]["weights"] = encodeFloat32Array(std::vector<float>{ 0, 0, 0, std::nanf(""), 0, 0 });
    }),
        "regions[0].weights: the weight of vertex 3 is nan; weights are 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["weights"] = "not base64!"; }),
        "regions[0].weights: not valid base64 of little-endian 32-bit floats");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["head"]["triangles"] = encodeUint32Array(std::vector<std::uint32_t>(24, 9));
    }),
        "head.triangles: triangle 0 refers to vertex 9; the head has 6");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"]["vertex_count"] = 7; }),
        "head.positions: 18 numbers where the 7 vertices need 21");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"]["vertex_count"] = 1e12; }),
        "head.vertex_count: 1000000000000.0 is not a whole number 0..4294967295");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][1]["id"] = 0; }),
        "regions[1].id: 0 is already the id of regions[0]");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][1]["id"] = 4294967295u; }),
        "regions[1].id: 4294967295 is reserved (it means \"no region\")");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["solo_region"] = 3; }), "solo_region: 3 is the id of no region");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["wisp"]["clump_degree"] = 3.0; }),
        "regions[0].wisp.clump_degree: 3.0 is outside -1..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["parameters"]["gravity"] = "strong"; }),
        "parameters.gravity: \"strong\" is not a number");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"][1]["root_colour"] = { 0.5, 2, 0 };
    }),
        "regions[1].root_colour: expected 3 numbers 0..1");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0]["visible"] = 1; }),
        "regions[0].visible: 1 is not true or false");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["camera"]["distance_metres"] = 0; }),
        "camera.distance_metres: the distance must be a positive number");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["camera"]["pivot"] = { 0, 1e300, 0 };
    }),
        "camera.pivot: expected 3 finite numbers");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["head"].erase("positions"); }), "head.positions: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["regions"][0].erase("id"); }), "regions[0].id: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j.erase("head"); }), "head: missing");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["head"]["embedded"] = false;
        j["head"]["source"] = "";
    }),
        "head.source: a head that is not stored in the project needs the file it comes from");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["version"] = 2; }), ": version 2 is newer than this Wisp reads (1)");
    EXPECT_EQ(damaged([](nlohmann::json& j) { j["format"] = "wisp-preset"; }),
        "format: this is a Wisp preset, not a project");
    EXPECT_EQ(damaged([](nlohmann::json& j) {
        j["regions"] = nlohmann::json::array();
        for (int i = 0; i < 300; ++i)
            j["regions"].push_back(nlohmann::json::object());
    }),
        "regions: 300 regions; at most 256 are allowed");
}

TEST_F(ProjectFileTest, UnknownKeysWarnAndMissingOptionalKeysTakeDefaults)
{
    nlohmann::json json = validJson();
    json["thumbnail"] = "png";
    json["camera"]["roll_radians"] = 0.1;
    json["regions"][0]["wisp"]["sheen"] = 1;
    json["regions"][0].erase("name");
    json["regions"][0].erase("tip_colour");
    json.erase("solo_region");
    const fs::path path = m_dir / "extra.wisp";
    writeText(path, json.dump());
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().warnings,
        (std::vector<std::string>{ "thumbnail: unknown key, ignored", "regions[0].wisp.sheen: unknown key, ignored",
            "camera.roll_radians: unknown key, ignored" }));
    EXPECT_EQ(read.value().project.regions[0].name, "Region 1");
    expectSameBits(read.value().project.regions[0].tipColour, GrowthRegion{}.tipColour, "tip");
    EXPECT_EQ(read.value().project.soloRegion, kNoSolo);
}

TEST_F(ProjectFileTest, MalformedAndEmptyFilesAreRefused)
{
    EXPECT_EQ(errorOf(""), ": the file is empty");
    EXPECT_EQ(errorOf("{\"format\": \"wisp-project\",\n \"version\": 1,,}"),
        "line 2, column 15: syntax error while parsing object key - unexpected ','; expected string literal");
    const Result<ProjectReadResult> missing = readProject((m_dir / "none.wisp").string());
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message, "the file does not exist");
}

// An identity above 2^53 (a double would round it) with the top bit set: region 7 | pore 123456789 | 2^63.
constexpr std::uint64_t kHighStrand = (std::uint64_t(7) << 32 | 123456789u) | (std::uint64_t(1) << 63);

// Salon edits with awkward numbers: every field set, one shape only, one wetness only.
StyleEdits sampleStyle()
{
    StyleEdits edits;
    StrandStyle& all = edits[kHighStrand];
    all.lengthMetres = 0.2f;
    all.curlRadiusMetres = 0.01f;
    all.curlTurnsPerMetre = 6.0f;
    all.stiffnessScale = 3.0f;
    all.wetness = 0.5f;
    // (push_back, not a braced list: GCC 12 warns about the list's temporaries)
    all.shape.push_back(glm::vec3(0.0f, 1.6f, 0.1f));
    all.shape.push_back(glm::vec3(0.01f, 1.5f, 1.0f / 3.0f));
    all.shape.push_back(glm::vec3(-0.0f, 1.4f, 1e-30f));
    StrandStyle& combed = edits[5];
    combed.lengthMetres = 0.123456789f;
    combed.curlRadiusMetres = 0.0f; // straightened: 0 differs from the default -1
    combed.shape = { glm::vec3(0.1f, 1.7f, 0.0f), glm::vec3(0.1f, 1.6f, 0.0f), glm::vec3(0.11f, 1.5f, 0.01f),
        glm::vec3(0.12f, 1.4f, 2.0f / 3.0f) };
    edits[4294967298u].wetness = 1.0f / 3.0f;
    return edits;
}

TEST_F(ProjectFileTest, StyleEditsComeBackExactly)
{
    Project project = smallProject();
    project.style = sampleStyle();
    project.style[9] = StrandStyle{}; // nothing changed: not saved
    const std::string path = (m_dir / "styled.wisp").string();
    const Result<void> written = writeProject(path, project);
    ASSERT_TRUE(written) << written.error().toString();
    const Result<ProjectReadResult> read = readProject(path);
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_TRUE(read.value().warnings.empty());
    Project expected = project;
    expected.style.erase(9);
    EXPECT_TRUE(read.value().project.style == expected.style);
    expectBitIdentical(read.value().project, expected);
    EXPECT_EQ(projectToJson(read.value().project, path), readText(path));

    // In identity order; identities as decimal text; only the changed fields.
    const nlohmann::json json = nlohmann::json::parse(readText(path));
    ASSERT_TRUE(json.contains("style"));
    ASSERT_EQ(json["style"].size(), 3u);
    EXPECT_EQ(json["style"][0]["strand"], "5");
    EXPECT_EQ(json["style"][1].size(), 2u);
    EXPECT_EQ(json["style"][1]["strand"], "4294967298");
    EXPECT_EQ(json["style"][1]["wetness"].dump(), "0.33333334");
    EXPECT_EQ(json["style"][2]["strand"], std::to_string(kHighStrand));
    EXPECT_EQ(json["style"][2]["strand"], "9223372067043003669");
    EXPECT_EQ(json["style"][2]["curl_turns"], 6);
    EXPECT_EQ(json["style"][2]["length"].dump(), "0.2"); // the shortest text that gives 0.2f back
    EXPECT_FALSE(json["style"][0].contains("wetness"));
    EXPECT_FALSE(json["style"][0].contains("stiffness_scale"));
    EXPECT_EQ(json["style"][0]["curl_radius"], 0);
    const auto shape = decodeFloat32Array(json["style"][0]["shape"].get<std::string>());
    ASSERT_TRUE(shape);
    EXPECT_EQ(shape->size(), 12u);

    // Without edits there is no "style" at all.
    project.style.clear();
    project.style[3] = StrandStyle{};
    EXPECT_FALSE(nlohmann::json::parse(projectToJson(project, path)).contains("style"));
}

TEST_F(ProjectFileTest, ProjectsWithoutStyleLoadWithNoEdits)
{
    nlohmann::json json = validJson();
    EXPECT_FALSE(json.contains("style"));
    const Result<ProjectReadResult> old = parseProject(json.dump(), (m_dir / "old.wisp").string());
    ASSERT_TRUE(old) << old.error().toString();
    EXPECT_TRUE(old.value().project.style.empty());
    EXPECT_TRUE(old.value().warnings.empty());

    json["style"] = nlohmann::json::array();
    const Result<ProjectReadResult> empty = parseProject(json.dump(), (m_dir / "empty.wisp").string());
    ASSERT_TRUE(empty) << empty.error().toString();
    EXPECT_TRUE(empty.value().project.style.empty());

    // An entry that changes nothing is no edit; an unknown key in an entry is a warning.
    json["style"] = nlohmann::json::array({ nlohmann::json{ { "strand", "12" } },
        nlohmann::json{ { "strand", "13" }, { "wetness", 0.25 }, { "comb", "left" } } });
    const Result<ProjectReadResult> read = parseProject(json.dump(), (m_dir / "warn.wisp").string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().warnings, (std::vector<std::string>{ "style[1].comb: unknown key, ignored" }));
    ASSERT_EQ(read.value().project.style.size(), 1u);
    EXPECT_EQ(read.value().project.style.at(13).wetness, 0.25f);
}

TEST_F(ProjectFileTest, BrokenStyleEntriesAreRefusedWithTheKeyPath)
{
    const nlohmann::json valid = validJson();
    const nlohmann::json good = { { "strand", "4294967298" }, { "wetness", 0.5 } };
    // The error of a project whose style is a good entry then `entry`.
    auto errorWith = [&](const nlohmann::json& entry) {
        nlohmann::json json = valid;
        json["style"] = nlohmann::json::array({ good, entry });
        const Result<ProjectReadResult> result = parseProject(json.dump(), (m_dir / "broken.wisp").string());
        return result ? std::string() : result.error().location + ": " + result.error().message;
    };
    auto contains
        = [](const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; };
    auto shapeOf = [](std::vector<float> xyz) { return encodeFloat32Array(xyz); };

    EXPECT_EQ(errorWith({ { "strand", "77" }, { "stiffness_scale", 2 } }), "");

    std::string error = errorWith({ { "strand", 77 }, { "wetness", 0.5 } });
    EXPECT_TRUE(contains(error, "style[1].strand: 77 is not a strand identity")) << error;
    error = errorWith({ { "strand", 4294967298.0 } });
    EXPECT_TRUE(contains(error, "style[1].strand: ")) << error;
    EXPECT_EQ(errorWith({ { "strand", "abc" }, { "wetness", 0.5 } }),
        "style[1].strand: \"abc\" is not a strand identity (a decimal number)");
    for (const char* text : { "", "-5", "+5", "12x", " 12", "1e9", "0x10" }) {
        error = errorWith({ { "strand", text }, { "wetness", 0.5 } });
        EXPECT_TRUE(contains(error, "style[1].strand: ") && contains(error, "is not a strand identity"))
            << text << ": " << error;
    }
    error = errorWith({ { "strand", "18446744073709551616" }, { "wetness", 0.5 } }); // 2^64
    EXPECT_TRUE(contains(error, "style[1].strand: \"18446744073709551616\" is too large for a strand identity"))
        << error;
    EXPECT_EQ(errorWith({ { "strand", "18446744073709551615" }, { "wetness", 0.5 } }), "");
    EXPECT_EQ(errorWith({ { "wetness", 0.5 } }), "style[1].strand: missing");

    EXPECT_EQ(errorWith({ { "strand", "9" }, { "wetness", 3 } }), "style[1]: strand 9: wetness 3 is outside 0..1");
    error = errorWith({ { "strand", "9" }, { "length", -0.1 } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: length -0.1 is outside")) << error;
    error = errorWith({ { "strand", "9" }, { "stiffness_scale", 0.5 } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: stiffness scale 0.5 is outside 1..50")) << error;
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "wetness", "wet" } }), "style[1].wetness: \"wet\" is not a number");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "curl_radius", 1e300 } }), "style[1].curl_radius: 1e+300 is too large");

    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0, 0, 2, 0, 1 }) } }),
        "style[1].shape: 7 numbers are not whole points");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0, 0, std::nanf(""), 0 }) } }),
        "style[1].shape: point 1 is not finite");
    EXPECT_EQ(errorWith({ { "strand", "9" },
                  { "shape", shapeOf({ 0, 1, 0, std::numeric_limits<float>::infinity(), 2, 0 }) } }),
        "style[1].shape: point 1 is not finite");
    EXPECT_EQ(errorWith({ { "strand", "9" }, { "shape", "not base64!" } }),
        "style[1].shape: not valid base64 of little-endian 32-bit floats");
    error = errorWith({ { "strand", "9" }, { "shape", shapeOf({ 0, 1, 0 }) } });
    EXPECT_TRUE(contains(error, "style[1]: strand 9: shape has 1 points")) << error;

    EXPECT_EQ(errorWith({ { "strand", "4294967298" }, { "wetness", 0.25 } }),
        "style[1].strand: 4294967298 is already the strand of style[0]");
    EXPECT_EQ(errorWith({ { "strand", "04294967298" }, { "wetness", 0.25 } }),
        "style[1].strand: 4294967298 is already the strand of style[0]");

    error = errorWith(nlohmann::json::array({ 1, 2 }));
    EXPECT_TRUE(contains(error, "style[1]: ")) << error;
    nlohmann::json json = valid;
    json["style"] = good;
    const Result<ProjectReadResult> notAList = parseProject(json.dump(), (m_dir / "broken.wisp").string());
    ASSERT_FALSE(notAList);
    EXPECT_EQ(notAList.error().location, "style");
    EXPECT_TRUE(contains(notAList.error().message, "expected a list")) << notAList.error().message;
}

TEST_F(ProjectFileTest, AProjectWithAnInvalidStyleEditIsNotSaved)
{
    const std::string path = (m_dir / "p.wisp").string();
    Project project = smallProject();
    project.style = sampleStyle();
    project.style[4].wetness = 3.0f; // the first entry in the file (identity order)
    const Result<void> result = writeProject(path, project);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().location, "style[0]");
    EXPECT_EQ(result.error().message, "not saved: strand 4: wetness 3 is outside 0..1");

    project.style = sampleStyle();
    project.style[2] = StrandStyle{}; // not written, so not counted
    project.style[kHighStrand].shape.push_back(project.style[kHighStrand].shape.back()); // coincident points
    const Result<void> coincident = writeProject(path, project);
    ASSERT_FALSE(coincident);
    EXPECT_EQ(coincident.error().location, "style[2]");
    EXPECT_EQ(coincident.error().message,
        "not saved: strand " + std::to_string(kHighStrand) + ": shape points 2 and 3 coincide");
    EXPECT_TRUE(fs::is_empty(m_dir));
}

TEST(Base64, KnownVectorsAndStrictDecoding)
{
    auto encode = [](std::string_view s) {
        return base64Encode({ reinterpret_cast<const std::uint8_t*>(s.data()), s.size() });
    };
    // RFC 4648, section 10.
    EXPECT_EQ(encode(""), "");
    EXPECT_EQ(encode("f"), "Zg==");
    EXPECT_EQ(encode("fo"), "Zm8=");
    EXPECT_EQ(encode("foo"), "Zm9v");
    EXPECT_EQ(encode("foob"), "Zm9vYg==");
    EXPECT_EQ(encode("fooba"), "Zm9vYmE=");
    EXPECT_EQ(encode("foobar"), "Zm9vYmFy");
    std::vector<std::uint8_t> all(256);
    for (int i = 0; i < 256; ++i)
        all[i] = static_cast<std::uint8_t>(i);
    for (std::size_t n = 0; n <= all.size(); ++n) {
        const std::span<const std::uint8_t> bytes(all.data(), n);
        const auto decoded = base64Decode(base64Encode(bytes));
        ASSERT_TRUE(decoded) << n;
        EXPECT_TRUE(std::equal(decoded->begin(), decoded->end(), bytes.begin(), bytes.end())) << n;
    }
    std::size_t bad = 0;
    EXPECT_FALSE(base64Decode("Zm9", &bad));
    EXPECT_EQ(bad, 3u);
    EXPECT_FALSE(base64Decode("Zm 9", &bad));
    EXPECT_EQ(bad, 2u);
    EXPECT_FALSE(base64Decode("Zg=A"));
    EXPECT_FALSE(base64Decode("Z==="));
    EXPECT_FALSE(base64Decode("Zh==")); // unused bits set: "Zg==" is the one text for "f"
    EXPECT_FALSE(base64Decode("Zg==Zg=="));
    EXPECT_FALSE(decodeFloat32Array("Zm9v")); // 3 bytes: not whole floats
    const std::vector<float> floats = { 0.0f, -0.0f, 1e-40f, std::numeric_limits<float>::infinity(), 0.1f };
    const auto back = decodeFloat32Array(encodeFloat32Array(floats));
    ASSERT_TRUE(back);
    EXPECT_EQ(std::memcmp(back->data(), floats.data(), sizeof(float) * floats.size()), 0);
}

// The head's up and front axes are stored by name; a project from before them (import_z_up) reads
// as the Z-up turn; a name that is no axis, or a front along the up axis, is refused by key.
TEST_F(ProjectFileTest, TheHeadsImportAxesAreStoredAndOldZUpFilesStillRead)
{
    nlohmann::json json = validJson();
    EXPECT_EQ(json["head"]["import_up"], "+X"); // smallProject's
    EXPECT_EQ(json["head"]["import_front"], "-Y");

    json["head"]["import_up"] = "-Z";
    json["head"]["import_front"] = "+x";
    const fs::path path = m_dir / "axes.wisp";
    writeText(path, json.dump());
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_TRUE(read) << read.error().toString();
    EXPECT_EQ(read.value().project.headImportUp, io::Axis::NegZ);
    EXPECT_EQ(read.value().project.headImportFront, io::Axis::PosX);

    nlohmann::json old = validJson();
    old["head"].erase("import_up");
    old["head"].erase("import_front");
    old["head"]["import_z_up"] = true;
    writeText(path, old.dump());
    const Result<ProjectReadResult> oldRead = readProject(path.string());
    ASSERT_TRUE(oldRead) << oldRead.error().toString();
    EXPECT_EQ(oldRead.value().project.headImportUp, io::Axis::PosZ);
    EXPECT_EQ(oldRead.value().project.headImportFront, io::Axis::NegY);

    nlohmann::json bad = validJson();
    bad["head"]["import_up"] = "up";
    EXPECT_EQ(errorOf(bad.dump()), "head.import_up: \"up\" is no axis (+X, -X, +Y, -Y, +Z or -Z)");
    bad = validJson();
    bad["head"]["import_front"] = "-X";
    EXPECT_EQ(errorOf(bad.dump()), "head.import_front: -X is not perpendicular to head.import_up +X");
}

// Issue 12: nlohmann's raw "[json.exception.out_of_range.406]" text, with no place, is translated.
TEST_F(ProjectFileTest, NumberOverflowNamesTheLineAndColumn)
{
    EXPECT_EQ(errorOf("{\"format\": \"wisp-project\",\n \"version\": 1e400}"),
        "line 2, column 13: the number 1e400 is too large to hold (it overflows a double)");
}

// Issue 12: a project is a way to bring a head in too; a flat one (which crashed the BVH build)
// is refused at load, with the same words as Open Head.
TEST_F(ProjectFileTest, FlatEmbeddedHeadIsRefused)
{
    TriangleMesh flat = octahedron(0.1f);
    for (glm::vec3& p : flat.positions)
        p.z *= 1e-40f;
    const fs::path path = m_dir / "flat.wisp";
    ASSERT_TRUE(writeProject(path.string(), makeProject(flat, std::vector<float>(flat.vertexCount(), 0.5f))));
    const Result<ProjectReadResult> read = readProject(path.string());
    ASSERT_FALSE(read);
    EXPECT_EQ(read.error().location, "head");
    EXPECT_NE(read.error().message.find("flat along z"), std::string::npos) << read.error().toString();
}
