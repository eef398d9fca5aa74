// Help > About Wisp says what the editor runs on here, for a bug report (issue 15: one binary picks
// its SIMD target at run time): the solver's target, Qt, and the OpenGL the view draws with. Opened
// as an artist does, from the Help menu with the keyboard; the box is read and closed by a timer,
// every wait bounded.
#include "GuiTestSupport.h"
#include "app/editor/AboutText.h"
#include "app/editor/MainWindow.h"
#include "sim/util/CpuName.h"
#include "sim/util/SimdTarget.h"
#include "widgets/Viewport.h"

#include <QAction>
#include <QApplication>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QTest>
#include <QTimer>

#include <gtest/gtest.h>

using namespace wisp;
using namespace wisp::test;

TEST(AboutBox, NamesTheSolversSimdTargetQtAndTheViewsOpenGl)
{
    auto window = openEditor();
    ASSERT_FALSE(::testing::Test::HasFailure()) << "the window did not open";
    // The view makes its context on its first paint.
    EXPECT_TRUE(QTest::qWaitFor([&] { return !window->viewport()->glDescription().isEmpty(); }, kWaitMs))
        << "the view has no OpenGL context after " << kWaitMs << " ms";
    const QString gl = window->viewport()->glDescription();

    QMenu* help = menuNamed(*window, QStringLiteral("Help"));
    ASSERT_NE(help, nullptr);
    // The box is modal (its own event loop): a timer reads it and closes it.
    QString shown, title;
    int boxes = 0;
    QTimer reader;
    QObject::connect(&reader, &QTimer::timeout, [&] {
        if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
            ++boxes;
            shown = box->text();
            title = box->windowTitle();
            box->accept();
        }
    });
    reader.start(50);
    help->popup(window->mapToGlobal(QPoint(40, 40)));
    ASSERT_TRUE(QTest::qWaitForWindowExposed(help));
    QTest::keyClick(help, Qt::Key_A); // "&About Wisp": returns once the box is closed
    EXPECT_TRUE(QTest::qWaitFor([&] { return boxes > 0; }, kWaitMs)) << "no About box";
    reader.stop();

    EXPECT_EQ(boxes, 1);
    EXPECT_EQ(title, QStringLiteral("About Wisp"));
    EXPECT_TRUE(shown.contains(QStringLiteral("Solver kernels: %1 (%2 floats a register)")
                                   .arg(QString::fromLatin1(solverSimdTarget()))
                                   .arg(solverVectorFloats())))
        << shown.toStdString();
    EXPECT_TRUE(shown.contains(QStringLiteral("CPU: ") + QString::fromStdString(cpuModelName()).toHtmlEscaped()))
        << shown.toStdString();
    EXPECT_TRUE(shown.contains(QStringLiteral("Qt: ") + QString::fromLatin1(qVersion()))) << shown.toStdString();
    EXPECT_TRUE(shown.contains(QStringLiteral("OpenGL: ") + gl.toHtmlEscaped())) << shown.toStdString();
    EXPECT_EQ(shown, aboutText(gl));
}

TEST(AboutBox, SaysWhenTheViewHasNoOpenGlYet)
{
    const QString text = aboutText(QString());
    EXPECT_TRUE(text.contains(QStringLiteral("OpenGL: not started yet"))) << text.toStdString();
    // A renderer's name is text, not markup.
    EXPECT_TRUE(aboutText(QStringLiteral("<b>x</b> & y")).contains(QStringLiteral("&lt;b&gt;x&lt;/b&gt; &amp; y")));
    EXPECT_TRUE(text.contains(QString::fromLatin1(solverSimdTarget())));
}
