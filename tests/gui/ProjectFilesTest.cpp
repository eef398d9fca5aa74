// The editor's files as an artist uses them: save and reopen a project exactly, the unsaved-changes
// prompt, autosave and recovery, a head opened without freezing the window, hair imported as a
// region and exported from the running simulation.
#include "app/editor/Document.h"
#include "app/editor/ExportHairDialog.h"
#include "app/editor/FileMenu.h"
#include "app/editor/HeadImporter.h"
#include "app/editor/MainWindow.h"
#include "app/editor/ProjectController.h"
#include "app/editor/SimulationHost.h"
#include "GuiTestSupport.h"
#include "io/HairFiles.h"
#include "widgets/Viewport.h"

#include <QAbstractButton>
#include <QApplication>
#include <QDir>
#include <QFile>
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

using namespace wisp;
using namespace wisp::test;

namespace {

const std::filesystem::path kAssets = WISP_SHARED_ASSETS;

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
        answerNextMessageBox(button, asked);  // not open yet
    });
}

class ProjectFilesTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        QStandardPaths::setTestModeEnabled(true);
        QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)).removeRecursively();
        window = std::make_unique<MainWindow>();
        window->show();
        ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
        window->fileMenu()->setInteractive(false);
        doc()->editRegionParameter(0, Param::Density, 2.0, false);
        doc()->undoStack()->clear();
        ASSERT_TRUE(waitUntil([&] { return window->simulation()->latestFrame() != nullptr; }));
    }
    void TearDown() override
    {
        if (window)
            window->document()->undoStack()->setClean();  // close without a prompt
    }
    Document* doc() const { return window->document(); }
    ProjectController* projects() const { return window->fileMenu()->projects(); }

    std::unique_ptr<MainWindow> window;
    QTemporaryDir dir;
};

}  // namespace

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

TEST_F(ProjectFilesTest, AutosaveIsOfferedBackAfterASessionThatDidNotClose)
{
    doc()->editParameter(Param::WindSpeed, 7.0, false);
    doc()->addRegion(QStringLiteral("Nape"));
    ASSERT_TRUE(projects()->autosaveNow());
    EXPECT_FALSE(projects()->autosaveNow()) << "nothing changed since";
    ASSERT_TRUE(QFileInfo::exists(projects()->autosavePath()));

    // This session is still running (its lock is there), as after a crash: the next start sees it.
    Document recovered;
    Viewport view;
    ProjectController next(&recovered, &view, nullptr);
    next.setInteractive(false);
    ASSERT_TRUE(next.recoveryAvailable());
    ASSERT_TRUE(next.recover());
    EXPECT_DOUBLE_EQ(recovered.parameters().get(Param::WindSpeed), 7.0);
    EXPECT_EQ(recovered.regionCount(), 2);
    EXPECT_TRUE(next.isModified()) << "recovered work is not saved anywhere yet";
    EXPECT_TRUE(next.currentPath().isEmpty());
}

TEST_F(ProjectFilesTest, AHeadOpensOnAWorkerThreadAtItsUnitAndTheWindowKeepsDrawing)
{
    const std::string planck = (kAssets / "heads/max_planck_decimated.obj").string();
    if (!std::filesystem::exists(planck))
        GTEST_SKIP() << "the shared assets are not at " << kAssets;
    const std::uint64_t groomBefore = window->simulation()->latestFrame()->groomVersion;
    QSignalSpy headChanged(doc(), &Document::headChanged);
    QSignalSpy refused(window->fileMenu()->headImporter(), &HeadImporter::failed);
    const std::uint64_t paints = window->viewport()->paintCount();
    ASSERT_TRUE(window->fileMenu()->openAny(QString::fromStdString(planck)));
    ASSERT_TRUE(waitUntil([&] { return headChanged.count() > 0 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    ASSERT_EQ(refused.count(), 0) << refused.front().front().toString().toStdString();
    EXPECT_EQ(doc()->head().positions.size(), 5272u);
    const Aabb box = boundsOf(doc()->head());
    const float extent = std::max({box.size().x, box.size().y, box.size().z});
    EXPECT_GT(extent, 0.15f);
    EXPECT_LT(extent, 0.4f);
    EXPECT_NEAR(box.center().y, 0.0f, 1e-4f) << "centred";
    EXPECT_FLOAT_EQ(doc()->headPlacement().scale, 0.001f) << "a head in millimetres";
    EXPECT_TRUE(window->viewport()->paintCount() > paints);
    ASSERT_TRUE(waitUntil([&] { return window->simulation()->latestFrame()->groomVersion > groomBefore; }));
    EXPECT_GT(window->simulation()->latestFrame()->strands.strandCount(), 100u) << "the new head has hair";

    // Head Scale: the same file at twice the metres per unit is twice the size; undo returns.
    const float height = box.size().y;
    ASSERT_TRUE(window->fileMenu()->placeAgain(0.002f, false));
    EXPECT_NEAR(boundsOf(doc()->head()).size().y, 2.0f * height, 1e-4f);
    ASSERT_TRUE(window->fileMenu()->placeAgain(0.001f, true));  // Z-up: the file's z becomes height
    EXPECT_TRUE(doc()->headPlacement().rotatedUpright);
    doc()->undoStack()->undo();
    doc()->undoStack()->undo();
    EXPECT_NEAR(boundsOf(doc()->head()).size().y, height, 1e-5f);

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
    if (!std::filesystem::exists(bangs))
        GTEST_SKIP() << "the shared assets are not at " << kAssets;
    ASSERT_EQ(window->fileMenu()->importHair(QString::fromStdString(bangs)), QString());
    ASSERT_EQ(doc()->regionCount(), 2);
    ASSERT_TRUE(doc()->region(1).importedStrands);
    EXPECT_EQ(doc()->region(1).importedStrands->strandCount(), 100u);
    // The frame's strands of the second region (look 1) are the imported ones.
    EXPECT_TRUE(waitUntil([&] {
        const FramePtr f = window->simulation()->latestFrame();
        return std::count(f->lookOfStrand.begin(), f->lookOfStrand.end(), std::uint16_t{1}) == 100;
    }));

    // Export the rest pose, key hairs only, and read it back.
    const FramePtr frame = window->simulation()->latestFrame();
    const QString path = dir.filePath(QStringLiteral("keys.hair"));
    ASSERT_EQ(window->fileMenu()->exportHair(path, true, true), QString());
    const auto back = io::readHair(path.toStdString());
    ASSERT_TRUE(back);
    const HairCurves expected = strandsForExport(*frame, {true, true});
    EXPECT_EQ(back.value().strands.strandCount(), frame->groomShape->keyStrands.size());
    ASSERT_EQ(back.value().strands.positions.size(), expected.positions.size());
    for (std::size_t i = 0; i < expected.positions.size(); ++i)
        ASSERT_LT(glm::distance(back.value().strands.positions[i], expected.positions[i]), 1e-6f);

    doc()->undoStack()->undo();
    EXPECT_EQ(doc()->regionCount(), 1);
    EXPECT_NE(window->fileMenu()->exportHair(dir.filePath(QStringLiteral("x.abc")), false, false), QString());
}

// Issue 12: a nearly flat OBJ (a subnormal extent in z) crashed File > Open Head in the BVH
// build. It is refused on the worker thread, naming the file and why, and the head stays.
TEST_F(ProjectFilesTest, AFlatHeadIsRefusedAndTheHeadStays)
{
    QString obj;
    constexpr int n = 20;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            obj += QStringLiteral("v %1 %2 %3\n").arg(0.01 * i).arg(0.01 * j).arg(i == n - 1 ? QStringLiteral("1e-42") : QStringLiteral("0"));
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
    ASSERT_TRUE(waitUntil([&] { return headChanged.count() > 0 || refused.count() > 0; }, 20000 * WISP_SLOW_BUILD_FACTOR));
    ASSERT_EQ(refused.count(), 1);
    const QString message = refused.front().front().toString();
    EXPECT_TRUE(message.contains(QStringLiteral("flat.obj"))) << message.toStdString();
    EXPECT_TRUE(message.contains(QStringLiteral("flat along z"))) << message.toStdString();
    EXPECT_EQ(headChanged.count(), 0);
    EXPECT_EQ(doc()->head().positions.size(), vertices);
}
