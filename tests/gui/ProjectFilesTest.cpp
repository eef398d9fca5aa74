// The editor's files as an artist uses them: save and reopen a project exactly, the unsaved-changes
// prompt, autosave (the first change at once) and recovery (only of sessions whose process is gone,
// at the project's path), temporaries of killed saves removed at start, a head opened without
// freezing the window, hair imported as a region and exported from the running simulation.
#include "../SharedAssets.h"
#include "GuiTestSupport.h"
#include "app/editor/Document.h"
#include "app/editor/ExportHairDialog.h"
#include "app/editor/FileMenu.h"
#include "app/editor/HeadImporter.h"
#include "app/editor/MainWindow.h"
#include "app/editor/ProjectController.h"
#include "app/editor/SimulationHost.h"
#include "io/HairFiles.h"
#include "io/ProjectFile.h"
#include "sim/geometry/MeshBvh.h"
#include "widgets/Viewport.h"

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QMenu>
#include <QMessageBox>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QUndoStack>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <sys/wait.h>
#include <unistd.h>

using namespace wisp;
using namespace wisp::test;

namespace {

const std::filesystem::path kAssets = wisp::test::sharedAssetsDir();

// Presses `button` on the next message box that opens (the prompt runs its own event loop).
void answerNextMessageBox(QMessageBox::StandardButton button, bool* asked)
{
    QTimer::singleShot(50, [button, asked] {
        for (QWidget* w : QApplication::topLevelWidgets())
            if (auto* box = qobject_cast<QMessageBox*>(w); box && box->isVisible()) {
                *asked = true;
                box->button(button)->click();
                return;
            }
        answerNextMessageBox(button, asked); // not open yet
    });
}

// A pid no process has: a child that has exited and been reaped.
pid_t deadPid()
{
    const pid_t child = ::fork();
    if (child == 0)
        ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

QList<QByteArray> lockLines(const QString& lockPath)
{
    QFile lock(lockPath);
    EXPECT_TRUE(lock.open(QIODevice::ReadOnly)) << lockPath.toStdString();
    return lock.readAll().split('\n');
}
QByteArray lockPidOf(const QString& lockPath)
{
    return lockLines(lockPath).value(0);
}
QString lockProjectOf(const QString& lockPath)
{
    return QString::fromUtf8(lockLines(lockPath).value(1));
}

// Makes a session's lock say its process is gone, as after a crash or kill -9 (its project line kept).
void killSession(const QString& lockPath)
{
    QList<QByteArray> lines = lockLines(lockPath);
    lines[0] = QByteArray::number(deadPid());
    QFile lock(lockPath);
    ASSERT_TRUE(lock.open(QIODevice::WriteOnly | QIODevice::Truncate));
    lock.write(lines.join('\n'));
}

// Another editor window starting now; its recovery question is answered `answer` and kept in `asked`.
std::unique_ptr<MainWindow> startEditor(FileMenu::RecoveryAnswer answer, QStringList* asked)
{
    auto window = std::make_unique<MainWindow>();
    window->fileMenu()->setInteractive(false);
    window->fileMenu()->setRecoveryPrompt([answer, asked](const QString& question) {
        asked->append(question);
        return answer;
    });
    window->show();
    EXPECT_TRUE(QTest::qWaitForWindowExposed(window.get()));
    return window;
}

class ProjectFilesTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        QStandardPaths::setTestModeEnabled(true);
        QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).removeRecursively();
        window = newEditorWindow();
        window->show();
        ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
        window->fileMenu()->setInteractive(false);
        doc()->editRegionParameter(0, Param::Density, 2.0, false);
        doc()->undoStack()->clear();
        ASSERT_TRUE(waitForFirstFrame(*window->simulation()));
    }
    void TearDown() override
    {
        if (window)
            window->document()->undoStack()->setClean(); // close without a prompt
    }
    Document* doc() const { return window->document(); }
    ProjectController* projects() const { return window->fileMenu()->projects(); }

    std::unique_ptr<MainWindow> window;
    QTemporaryDir dir;
};

} // namespace

TEST_F(ProjectFilesTest, SavedProjectReopensExactlyWithItsCamera)
{
    doc()->editParameter(Param::Gravity, 4.5, false);
    const int added = doc()->addRegion(QStringLiteral("Fringe"));
    doc()->editRegionParameter(added, Param::CurlRadius, 0.012, false);
    doc()->beginStroke();
    doc()->strokeWeights()[10] = 0.75f;
    doc()->strokeUpdated();
    doc()->endStroke(QStringLiteral("Paint"));
    window->viewport()->camera().setOrientation(1.1f, 0.3f);
    window->viewport()->camera().setDistance(0.9f);
    const std::vector<GrowthRegion> regions = doc()->regions();
    EXPECT_TRUE(window->isWindowModified());

    const QString path = dir.filePath(QStringLiteral("look.wisp"));
    ASSERT_TRUE(projects()->saveAs(path)) << projects()->lastError().toStdString();
    EXPECT_FALSE(window->isWindowModified());
    EXPECT_TRUE(window->windowTitle().contains(QStringLiteral("look.wisp")));

    ASSERT_TRUE(projects()->newProject());
    EXPECT_EQ(doc()->regionCount(), 1);
    EXPECT_DOUBLE_EQ(doc()->parameters().get(Param::Gravity), 9.81);

    ASSERT_TRUE(projects()->open(path)) << projects()->lastError().toStdString();
    EXPECT_DOUBLE_EQ(doc()->parameters().get(Param::Gravity), 4.5);
    ASSERT_EQ(doc()->regionCount(), 2);
    for (int i = 0; i < 2; ++i) {
        EXPECT_EQ(doc()->region(i).weights, regions[static_cast<std::size_t>(i)].weights);
        EXPECT_EQ(doc()->region(i).values, regions[static_cast<std::size_t>(i)].values);
        EXPECT_EQ(doc()->region(i).name, regions[static_cast<std::size_t>(i)].name);
    }
    EXPECT_FLOAT_EQ(window->viewport()->camera().yaw(), 1.1f);
    EXPECT_FLOAT_EQ(window->viewport()->camera().distance(), 0.9f);
    EXPECT_FALSE(window->isWindowModified());
    EXPECT_EQ(projects()->recentFiles().value(0), QFileInfo(path).absoluteFilePath());
    EXPECT_TRUE(waitUntil([&] { return window->simulation()->latestFrame()->looks.size() == 2u; }))
        << "the reopened regions grow hair";

    // A broken project is refused with the file named, and nothing changes.
    QFile broken(dir.filePath(QStringLiteral("broken.wisp")));
    ASSERT_TRUE(broken.open(QIODevice::WriteOnly));
    broken.write("{\"format\": \"wisp-project\", \"version\": 1, \"head\": ");
    broken.close();
    EXPECT_FALSE(projects()->open(broken.fileName()));
    EXPECT_TRUE(projects()->lastError().contains(QStringLiteral("broken.wisp")));
    EXPECT_EQ(doc()->regionCount(), 2);
}

TEST_F(ProjectFilesTest, ClosingWithUnsavedChangesAsksAndCancelKeepsTheWindow)
{
    window->fileMenu()->setInteractive(true);
    doc()->editParameter(Param::Gravity, 3.0, false);
    bool asked = false;
    answerNextMessageBox(QMessageBox::Cancel, &asked);
    window->close();
    EXPECT_TRUE(asked);
    EXPECT_TRUE(window->isVisible());
    EXPECT_DOUBLE_EQ(doc()->parameters().get(Param::Gravity), 3.0);

    asked = false;
    answerNextMessageBox(QMessageBox::Discard, &asked);
    window->close();
    EXPECT_TRUE(asked);
    EXPECT_FALSE(window->isVisible());
}

TEST_F(ProjectFilesTest, ASecondEditorIsNotOfferedTheWorkOfALiveOne)
{
    doc()->editParameter(Param::WindSpeed, 7.0, false);
    ASSERT_TRUE(waitUntil([&] { return QFileInfo::exists(projects()->autosavePath()); }));
    ASSERT_EQ(lockPidOf(projects()->sessionLockPath()), QByteArray::number(::getpid())) << "a lock holds its pid";

    // Another editor starts while this one runs (its lock holds a live pid: this process's).
    QStringList asked;
    auto other = startEditor(FileMenu::RecoveryAnswer::Discard, &asked);
    other->fileMenu()->offerRecovery(); // as its first show did: nothing to offer
    EXPECT_FALSE(other->fileMenu()->projects()->recoveryAvailable());
    EXPECT_TRUE(asked.isEmpty()) << asked.value(0).toStdString();
    EXPECT_NE(other->fileMenu()->projects()->autosavePath(), projects()->autosavePath()) << "each session its own";
    other.reset(); // a clean exit removes only its own files
    EXPECT_TRUE(QFileInfo::exists(projects()->autosavePath())) << "the live session's autosave stays";
    EXPECT_TRUE(QFileInfo::exists(projects()->sessionLockPath()));
}

TEST_F(ProjectFilesTest, AnEditorThatDiedIsOfferedItsWorkBackAtItsPath)
{
    const QString path = dir.filePath(QStringLiteral("look.wisp"));
    ASSERT_TRUE(projects()->saveAs(path)) << projects()->lastError().toStdString();
    doc()->editParameter(Param::WindSpeed, 7.0, false);
    ASSERT_TRUE(waitUntil([&] { return QFileInfo::exists(projects()->autosavePath()); }));
    doc()->addRegion(QStringLiteral("Nape"));
    ASSERT_TRUE(projects()->autosaveNow()) << "the region came after the first autosave";
    EXPECT_FALSE(projects()->autosaveNow()) << "nothing changed since";
    const QString lostAutosave = projects()->autosavePath();
    const QString lostLock = projects()->sessionLockPath();
    killSession(lostLock);

    QStringList asked;
    auto next = startEditor(FileMenu::RecoveryAnswer::Recover, &asked);
    ASSERT_TRUE(waitUntil([&] { return !asked.isEmpty(); }));
    EXPECT_EQ(asked.size(), 1);
    EXPECT_TRUE(asked.front().contains(QStringLiteral("look.wisp"))) << asked.front().toStdString();
    ProjectController* recovered = next->fileMenu()->projects();
    EXPECT_DOUBLE_EQ(next->document()->parameters().get(Param::WindSpeed), 7.0);
    EXPECT_EQ(next->document()->regionCount(), 2);
    EXPECT_EQ(recovered->currentPath(), path) << "the recovered project keeps its file";
    EXPECT_TRUE(recovered->isModified()) << "recovered work is not saved anywhere yet";
    EXPECT_TRUE(next->isWindowModified());
    EXPECT_TRUE(next->windowTitle().contains(QStringLiteral("look.wisp"))) << next->windowTitle().toStdString();
    // The work moved into the new session: its autosave protects it, the lost session's files go.
    EXPECT_TRUE(QFileInfo::exists(recovered->autosavePath()));
    EXPECT_FALSE(QFileInfo::exists(lostAutosave));
    EXPECT_FALSE(QFileInfo::exists(lostLock));
    EXPECT_EQ(lockProjectOf(recovered->sessionLockPath()), path);

    // Save goes to the project's file without asking where; then the autosave is not needed.
    next->fileMenu()->setInteractive(false);
    ASSERT_TRUE(recovered->save()) << recovered->lastError().toStdString();
    EXPECT_FALSE(QFileInfo::exists(recovered->autosavePath()));
    doc()->undoStack()->setClean(); // the first window stands in for the session that died
    ASSERT_TRUE(projects()->open(path)) << projects()->lastError().toStdString();
    EXPECT_DOUBLE_EQ(doc()->parameters().get(Param::WindSpeed), 7.0);
    EXPECT_EQ(doc()->regionCount(), 2);
}

TEST_F(ProjectFilesTest, RecoveryLaterKeepsTheWorkForTheNextStartAndDiscardRemovesIt)
{
    doc()->editParameter(Param::WindSpeed, 5.0, false);
    ASSERT_TRUE(waitUntil([&] { return QFileInfo::exists(projects()->autosavePath()); }));
    const QString lostAutosave = projects()->autosavePath();
    const QString lostLock = projects()->sessionLockPath();
    killSession(lostLock);

    QStringList asked;
    auto later = startEditor(FileMenu::RecoveryAnswer::Later, &asked);
    ASSERT_TRUE(waitUntil([&] { return !asked.isEmpty(); }));
    EXPECT_TRUE(asked.front().contains(QStringLiteral("untitled"))) << asked.front().toStdString();
    EXPECT_DOUBLE_EQ(later->document()->parameters().get(Param::WindSpeed), ParameterValues().get(Param::WindSpeed));
    later.reset();
    EXPECT_TRUE(QFileInfo::exists(lostAutosave));

    asked.clear();
    auto discard = startEditor(FileMenu::RecoveryAnswer::Discard, &asked);
    ASSERT_TRUE(waitUntil([&] { return !asked.isEmpty(); }));
    EXPECT_FALSE(QFileInfo::exists(lostAutosave));
    EXPECT_FALSE(QFileInfo::exists(lostLock));
    discard.reset();

    asked.clear();
    auto third = startEditor(FileMenu::RecoveryAnswer::Recover, &asked);
    third->fileMenu()->offerRecovery();
    EXPECT_TRUE(asked.isEmpty()) << "nothing is left to offer";
}

TEST_F(ProjectFilesTest, TheFirstChangeIsAutosavedAtOnceThenOncePerInterval)
{
    projects()->setAutosaveIntervalMs(3600 * 1000); // no tick during the first part
    QSignalSpy autosaved(projects(), &ProjectController::autosaved);
    window->activateWindow();
    ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
    typeValue(window->forcePanel(), Param::Gravity, QStringLiteral("2"));
    ASSERT_TRUE(waitUntil([&] { return autosaved.count() == 1; })) << "the first change is protected at once";
    EXPECT_EQ(autosaved.front().front().toString(), projects()->autosavePath());
    EXPECT_DOUBLE_EQ(
        io::readProject(projects()->autosavePath().toStdString()).value().project.parameters.get(Param::Gravity), 2.0);

    // More changes wait for the interval: after 100 rounds of the event loop, still one autosave.
    typeValue(window->forcePanel(), Param::Gravity, QStringLiteral("3"));
    for (int i = 0; i < 100; ++i)
        QCoreApplication::processEvents();
    EXPECT_EQ(autosaved.count(), 1);
    projects()->setAutosaveIntervalMs(1);
    ASSERT_TRUE(waitUntil([&] { return autosaved.count() == 2; })) << "the interval's tick saves them";
    EXPECT_DOUBLE_EQ(
        io::readProject(projects()->autosavePath().toStdString()).value().project.parameters.get(Param::Gravity), 3.0);

    // A quiet interval (ticks with nothing to save): the next change goes at once again.
    for (int i = 0; i < 20; ++i)
        QTest::qWait(2);
    projects()->setAutosaveIntervalMs(3600 * 1000);
    EXPECT_EQ(autosaved.count(), 2);
    typeValue(window->forcePanel(), Param::Gravity, QStringLiteral("4"));
    ASSERT_TRUE(waitUntil([&] { return autosaved.count() == 3; }));
    EXPECT_FALSE(QFileInfo::exists(projects()->autosavePath() + QStringLiteral(".bak"))) << "an autosave keeps no .bak";

    // Saving makes the autosave stale: it goes, so a crash never offers it over the newer file.
    ASSERT_TRUE(projects()->saveAs(dir.filePath(QStringLiteral("saved.wisp"))));
    EXPECT_FALSE(QFileInfo::exists(projects()->autosavePath()));
    EXPECT_EQ(ProjectController::kAutosaveIntervalMs, 60 * 1000);
}

TEST_F(ProjectFilesTest, TemporariesOfKilledSavesAreRemovedAtStartButNotThoseOfLiveOnes)
{
    const QString path = dir.filePath(QStringLiteral("look.wisp"));
    ASSERT_TRUE(projects()->saveAs(path)); // its folder is a recent project's
    const QString data = QFileInfo(projects()->autosavePath()).absolutePath();
    const QString dead = QString::number(deadPid());
    const QString live = QString::number(::getpid());
    const QStringList stale = { data + QStringLiteral("/autosave-1-0.wisp.0123456789abcdef.tmp-") + dead,
        path + QStringLiteral(".fedcba9876543210.tmp-") + dead,
        path + QStringLiteral(".bak.00000000ffffffff.tmp-") + dead };
    const QStringList kept = { data + QStringLiteral("/autosave-1-0.wisp.0123456789abcdef.tmp-") + live,
        path + QStringLiteral(".fedcba9876543210.tmp-") + live };
    for (const QString& name : stale + kept) {
        QFile file(name);
        ASSERT_TRUE(file.open(QIODevice::WriteOnly)) << name.toStdString();
        file.write("half a save");
    }
    QStringList asked;
    auto next = startEditor(FileMenu::RecoveryAnswer::Later, &asked);
    for (const QString& name : stale)
        EXPECT_FALSE(QFileInfo::exists(name)) << name.toStdString();
    for (const QString& name : kept)
        EXPECT_TRUE(QFileInfo::exists(name)) << name.toStdString();
    EXPECT_TRUE(QFileInfo::exists(path));
}

TEST_F(ProjectFilesTest, AHeadOpensOnAWorkerThreadAtItsUnitAndTheWindowKeepsDrawing)
{
    const std::string planck = (kAssets / "heads/max_planck_decimated.obj").string();
    REQUIRE_SHARED_ASSET(planck);
    const std::uint64_t groomBefore = window->simulation()->latestFrame()->groomVersion;
    QSignalSpy headChanged(doc(), &Document::headChanged);
    QSignalSpy refused(window->fileMenu()->headImporter(), &HeadImporter::failed);
    const std::uint64_t paints = window->viewport()->paintCount();
    ASSERT_TRUE(window->fileMenu()->openAny(QString::fromStdString(planck)));
    ASSERT_TRUE(
        waitUntil([&] { return headChanged.count() > 0 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    ASSERT_EQ(refused.count(), 0) << refused.front().front().toString().toStdString();
    EXPECT_EQ(doc()->head().positions.size(), 5272u);
    const Aabb box = boundsOf(doc()->head());
    const float extent = std::max({ box.size().x, box.size().y, box.size().z });
    EXPECT_GT(extent, 0.15f);
    EXPECT_LT(extent, 0.4f);
    EXPECT_NEAR(box.center().y, 0.0f, 1e-4f) << "centred";
    EXPECT_FLOAT_EQ(doc()->headPlacement().scale, 0.001f) << "a head in millimetres";
    EXPECT_TRUE(window->viewport()->paintCount() > paints);
    ASSERT_TRUE(waitUntil([&] { return window->simulation()->latestFrame()->groomVersion > groomBefore; }));
    EXPECT_GT(window->simulation()->latestFrame()->strands.strandCount(), 100u) << "the new head has hair";

    // Head Scale: the same file at twice the metres per unit is twice the size; undo returns.
    const float height = box.size().y;
    ASSERT_TRUE(window->fileMenu()->placeAgain(0.002f, std::nullopt));
    EXPECT_NEAR(boundsOf(doc()->head()).size().y, 2.0f * height, 1e-4f);
    ASSERT_TRUE(window->fileMenu()->placeAgain(0.001f, io::Axis::PosZ)); // Z-up: the file's z becomes height
    EXPECT_EQ(doc()->headPlacement().up, io::Axis::PosZ);
    EXPECT_EQ(doc()->headPlacement().front, io::Axis::NegY);
    doc()->undoStack()->undo();
    doc()->undoStack()->undo();
    EXPECT_NEAR(boundsOf(doc()->head()).size().y, height, 1e-5f);
    // A scale that makes the head 0.2 mm tall is refused like such a file, and the head stays.
    {
        QSignalSpy scaleSaid(window->fileMenu(), &FileMenu::message);
        EXPECT_FALSE(window->fileMenu()->placeAgain(1e-6f, std::nullopt));
        ASSERT_EQ(scaleSaid.count(), 1);
        const QString text = scaleSaid.front().front().toString();
        EXPECT_TRUE(text.contains(QStringLiteral("max_planck_decimated.obj: the placed head is")))
            << text.toStdString();
        EXPECT_NEAR(boundsOf(doc()->head()).size().y, height, 1e-5f);
    }

    // A file that is not a head says so, naming it, and the head stays.
    QSignalSpy said(window->fileMenu(), &FileMenu::message);
    EXPECT_TRUE(window->fileMenu()->openAny(dir.filePath(QStringLiteral("missing.obj"))));
    ASSERT_TRUE(said.wait(10000));
    EXPECT_TRUE(said.back().front().toString().contains(QStringLiteral("missing.obj")));
    EXPECT_EQ(doc()->head().positions.size(), 5272u);
}

TEST_F(ProjectFilesTest, ImportedHairBecomesASimulatedRegionAndExportsBack)
{
    const std::string bangs = (kAssets / "hair/ct2hair_bangs100.data").string();
    REQUIRE_SHARED_ASSET(bangs);
    ASSERT_EQ(window->fileMenu()->importHair(QString::fromStdString(bangs)), QString());
    ASSERT_EQ(doc()->regionCount(), 2);
    ASSERT_TRUE(doc()->region(1).importedStrands);
    EXPECT_EQ(doc()->region(1).importedStrands->strandCount(), 100u);
    // The frame's strands of the second region (look 1) are the imported ones.
    EXPECT_TRUE(waitUntil([&] {
        const FramePtr f = window->simulation()->latestFrame();
        return std::count(f->lookOfStrand.begin(), f->lookOfStrand.end(), std::uint16_t{ 1 }) == 100;
    }));

    // Export the rest pose, key hairs only, and read it back.
    const FramePtr frame = window->simulation()->latestFrame();
    const QString path = dir.filePath(QStringLiteral("keys.hair"));
    ASSERT_EQ(window->fileMenu()->exportHair(path, true, true), QString());
    const auto back = io::readHair(path.toStdString());
    ASSERT_TRUE(back);
    const HairCurves expected = strandsForExport(*frame, { true, true });
    EXPECT_EQ(back.value().strands.strandCount(), frame->groomShape->keyStrands.size());
    ASSERT_EQ(back.value().strands.positions.size(), expected.positions.size());
    for (std::size_t i = 0; i < expected.positions.size(); ++i)
        ASSERT_LT(glm::distance(back.value().strands.positions[i], expected.positions[i]), 1e-6f);

    doc()->undoStack()->undo();
    EXPECT_EQ(doc()->regionCount(), 1);
    EXPECT_NE(window->fileMenu()->exportHair(dir.filePath(QStringLiteral("x.abc")), false, false), QString());
}

// The editor's path for a head and the strands made on it: the head is turned upright from its
// shape (CT2Hair's is +X up), the status line says so, and Import Hair moves the strands with it,
// so every root lies within a few millimetres of the head's surface (checked against a BVH of the
// document's head). The same placement as wisp-cli simulate --head --hair.
TEST_F(ProjectFilesTest, HairImportedAfterItsHeadLandsOnItsScalp)
{
    const std::string head = (kAssets / "hair/ct2hair_bangs_head.ply").string();
    const std::string bangs = (kAssets / "hair/ct2hair_bangs100.data").string();
    REQUIRE_SHARED_ASSET(head);
    REQUIRE_SHARED_ASSET(bangs);
    QSignalSpy said(window->fileMenu(), &FileMenu::message);
    QSignalSpy headChanged(doc(), &Document::headChanged);
    QSignalSpy refused(window->fileMenu()->headImporter(), &HeadImporter::failed);
    ASSERT_TRUE(window->fileMenu()->openAny(QString::fromStdString(head)));
    ASSERT_TRUE(
        waitUntil([&] { return headChanged.count() > 0 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    ASSERT_EQ(refused.count(), 0) << refused.front().front().toString().toStdString();
    EXPECT_EQ(doc()->headPlacement().up, io::Axis::PosX);
    ASSERT_GT(said.count(), 0);
    EXPECT_TRUE(said.back().front().toString().contains(QStringLiteral("+X up, face -Y (from its shape)")))
        << said.back().front().toString().toStdString();

    ASSERT_EQ(window->fileMenu()->importHair(QString::fromStdString(bangs)), QString());
    EXPECT_TRUE(said.back().front().toString().contains(QStringLiteral("strands placed with their head")))
        << said.back().front().toString().toStdString();
    ASSERT_EQ(doc()->regionCount(), 2);
    const HairCurves& strands = *doc()->region(1).importedStrands;
    const MeshBvh bvh(doc()->head());
    float worst = 0.0f;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        worst = std::max(worst, bvh.closestPoint(strands.positions[strands.offsets[s]]).distance);
    EXPECT_LT(worst, 0.006f) << "roots within a few millimetres of the scalp";

    // A head that needs a word: the status line carries the placement's warning.
    const std::string woman = (kAssets / "heads/cy_woman_head.ply").string();
    ASSERT_TRUE(window->fileMenu()->openAny(QString::fromStdString(woman)));
    ASSERT_TRUE(
        waitUntil([&] { return headChanged.count() > 1 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    EXPECT_TRUE(said.back().front().toString().contains(QStringLiteral("check: the skull is 64.7")))
        << said.back().front().toString().toStdString();
    // Head Up Axis ▸ +Y keeps the file's axes (the head lies on its back), one undo step.
    QAction* plusY = nullptr;
    for (QAction* a : window->fileMenu()->menu()->findChildren<QAction*>())
        if (a->text() == QStringLiteral("+Y"))
            plusY = a;
    ASSERT_NE(plusY, nullptr);
    plusY->trigger();
    EXPECT_EQ(doc()->headPlacement().up, io::Axis::PosY);
    EXPECT_FALSE(doc()->headPlacement().turned());
    doc()->undoStack()->undo();
    EXPECT_EQ(doc()->headPlacement().up, io::Axis::PosZ);
}

// Issue 12: a nearly flat OBJ (a subnormal extent in z) crashed File > Open Head in the BVH
// build. It is refused on the worker thread, naming the file and why, and the head stays.
TEST_F(ProjectFilesTest, AFlatHeadIsRefusedAndTheHeadStays)
{
    QString obj;
    constexpr int n = 20;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            obj += QStringLiteral("v %1 %2 %3\n")
                       .arg(0.01 * i)
                       .arg(0.01 * j)
                       .arg(i == n - 1 ? QStringLiteral("1e-42") : QStringLiteral("0"));
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j + 1, b = a + 1, c = a + n, d = c + 1;
            obj += QStringLiteral("f %1 %2 %3\nf %1 %3 %4\n").arg(a).arg(b).arg(d).arg(c);
        }
    const QString path = dir.filePath(QStringLiteral("flat.obj"));
    {
        QFile file(path);
        ASSERT_TRUE(file.open(QIODevice::WriteOnly));
        file.write(obj.toUtf8());
    }
    const std::size_t vertices = doc()->head().positions.size();
    QSignalSpy headChanged(doc(), &Document::headChanged);
    QSignalSpy refused(window->fileMenu()->headImporter(), &HeadImporter::failed);
    ASSERT_TRUE(window->fileMenu()->openAny(path));
    ASSERT_TRUE(
        waitUntil([&] { return headChanged.count() > 0 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    ASSERT_EQ(refused.count(), 1);
    const QString message = refused.front().front().toString();
    EXPECT_TRUE(message.contains(QStringLiteral("flat.obj"))) << message.toStdString();
    EXPECT_TRUE(message.contains(QStringLiteral("flat along z"))) << message.toStdString();
    EXPECT_EQ(headChanged.count(), 0);
    EXPECT_EQ(doc()->head().positions.size(), vertices);
}
