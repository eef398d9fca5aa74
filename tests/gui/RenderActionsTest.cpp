// File ▸ Render Image… and Render Turntable… in the editor: the prompt is replaced (no dialog is
// left open), the actions are triggered as the menu does, and the files they write are read back.
// The turntable's Cancel is clicked on its progress dialog.

#include "GuiTestSupport.h"

#include "app/editor/RenderActions.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QDir>
#include <QImage>
#include <QProgressDialog>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>

namespace wisp {
namespace {

RenderActions::Prompt answer(RenderActions::ImageRequest request, int* asked = nullptr)
{
    return [request, asked](const RenderActions::ImageRequest&, bool) {
        if (asked)
            ++*asked;
        return std::optional(request);
    };
}

int pngCount(const QString& folder)
{
    return static_cast<int>(QDir(folder).entryList({ QStringLiteral("*.png") }, QDir::Files).size());
}

TEST(RenderActions, RenderImageWritesAPngOfTheChosenSizeWithATransparentBackground)
{
    auto window = test::openEditor();
    ASSERT_TRUE(test::waitForFirstFrame(*window->simulation()));
    QTemporaryDir dir;
    RenderActions* render = window->fileMenu()->renderActions();
    int asked = 0;
    render->setPrompt(answer({ dir.filePath(QStringLiteral("still.png")), QSize(320, 200), true, 1 }, &asked));
    const std::uint64_t paintsBefore = window->viewport()->paintCount();
    render->renderImageAction()->trigger();
    EXPECT_EQ(asked, 1);
    const QImage image = QImage(dir.filePath(QStringLiteral("still.png"))).convertToFormat(QImage::Format_ARGB32);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.size(), QSize(320, 200));
    EXPECT_EQ(qAlpha(image.pixel(1, 1)), 0); // background left out
    EXPECT_EQ(qAlpha(image.pixel(160, 100)), 255); // the head
    // An image is not one of the view's paints (its frame rate and detail are left alone), and the
    // view keeps drawing at its own size afterwards.
    EXPECT_EQ(window->viewport()->paintCount(), paintsBefore);
    ASSERT_TRUE(test::waitUntil([&] { return window->viewport()->paintCount() > paintsBefore; }));
    EXPECT_EQ(window->viewport()->grabFramebuffer().size(),
        window->viewport()->size() * window->viewport()->devicePixelRatioF());
}

TEST(RenderActions, ABadFileIsRefusedAndNamed)
{
    auto window = test::openEditor();
    QTemporaryDir dir;
    RenderActions* render = window->fileMenu()->renderActions();
    const QString error
        = render->renderImage({ dir.filePath(QStringLiteral("no/such/x.png")), QSize(64, 64), false, 1 });
    EXPECT_TRUE(error.contains(dir.filePath(QStringLiteral("no/such")))) << error.toStdString();
    EXPECT_EQ(pngCount(dir.path()), 0);
}

TEST(RenderActions, RenderTurntableWritesNFrames)
{
    auto window = test::openEditor();
    ASSERT_TRUE(test::waitForFirstFrame(*window->simulation()));
    QTemporaryDir dir;
    RenderActions* render = window->fileMenu()->renderActions();
    QSignalSpy finished(render, &RenderActions::turntableFinished);
    render->setPrompt(answer({ dir.filePath(QStringLiteral("turn.png")), QSize(80, 64), false, 5 }));
    render->renderTurntableAction()->trigger();
    ASSERT_TRUE(render->turntableRunning());
    ASSERT_NE(render->progressDialog(), nullptr);
    EXPECT_TRUE(render->progressDialog()->isVisible());
    ASSERT_TRUE(test::waitUntil([&] { return finished.count() == 1; }));
    EXPECT_EQ(finished.at(0).at(0).toInt(), 5);
    EXPECT_FALSE(finished.at(0).at(1).toBool());
    EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files, QDir::Name),
        (QStringList{ "turn_0001.png", "turn_0002.png", "turn_0003.png", "turn_0004.png", "turn_0005.png" }));
    EXPECT_EQ(QImage(dir.filePath(QStringLiteral("turn_0003.png"))).size(), QSize(80, 64));
    EXPECT_NE(
        QImage(dir.filePath(QStringLiteral("turn_0001.png"))), QImage(dir.filePath(QStringLiteral("turn_0002.png"))));
    EXPECT_FALSE(render->turntableRunning());
    EXPECT_EQ(render->progressDialog(), nullptr);
}

TEST(RenderActions, CancelOnTheProgressDialogStopsTheTurntable)
{
    auto window = test::openEditor();
    ASSERT_TRUE(test::waitForFirstFrame(*window->simulation()));
    QTemporaryDir dir;
    RenderActions* render = window->fileMenu()->renderActions();
    QSignalSpy finished(render, &RenderActions::turntableFinished);
    constexpr int kFrames = 400;
    render->setPrompt(answer({ dir.filePath(QStringLiteral("long.png")), QSize(64, 64), false, kFrames }));
    render->renderTurntableAction()->trigger();
    ASSERT_TRUE(test::waitUntil([&] { return pngCount(dir.path()) >= 2; }));
    QProgressDialog* progress = render->progressDialog();
    ASSERT_NE(progress, nullptr);
    QPushButton* cancel = progress->findChild<QPushButton*>();
    ASSERT_NE(cancel, nullptr);
    QTest::mouseClick(cancel, Qt::LeftButton);
    ASSERT_TRUE(test::waitUntil([&] { return finished.count() == 1; }));
    EXPECT_TRUE(finished.at(0).at(1).toBool()); // cancelled
    const int written = finished.at(0).at(0).toInt();
    EXPECT_GE(written, 2);
    EXPECT_LT(written, kFrames);
    // Nothing more is written after Cancel: let the event loop turn many times.
    for (int i = 0; i < 20; ++i)
        QTest::qWait(5);
    EXPECT_EQ(pngCount(dir.path()), written);
    EXPECT_FALSE(render->turntableRunning());
}

} // namespace
} // namespace wisp
