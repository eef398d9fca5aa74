// Projects: a referenced head is found relative to the project file; saving keeps the previous
// file as .bak and never leaves half a file.
#include "ProjectFileTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::project;

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
    project.regions[0].weights.forWrite().pop_back();
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
