// `wisp --render`: the real binary, run under the tests' X server, writes a PNG of the requested
// size with hair in it, a turntable of N frames, and refuses bad arguments and files with exit
// status 1 and a message naming them, before any work and without leaving a file behind.

#include "app/editor/RenderCommand.h"
#include "app/editor/ImageFiles.h"

#include <QDir>
#include <QFile>
#include <QImage>
#include <QProcess>
#include <QTemporaryDir>

#include <gtest/gtest.h>

namespace wisp {
namespace {

// A generous bound for one render (groom, drape, settle, draw) on a busy machine; a hang guard.
constexpr int kRenderWaitMs = 120000 * WISP_SLOW_BUILD_FACTOR;

struct ProcessRun {
    int exitCode = -1;
    QString output; // stdout and stderr together
};

ProcessRun runWisp(const QStringList& arguments)
{
    QProcess process;
    process.setProcessChannelMode(QProcess::MergedChannels);
#if defined(__SANITIZE_ADDRESS__)
    // The sanitizer build: the child's leak check at exit is off. Mesa's DRI driver (llvmpipe) is
    // unloaded when the X display closes, and the 112 bytes it still holds then look leaked (their
    // only pointers were in the unmapped driver), which would turn every render's exit status to 1.
    // Keeping the driver loaded (RTLD_NODELETE) crashes the leak checker's thread tracer instead.
    // The same drawing code runs inside this test binary (RenderActions, PresetThumbnails), whose
    // own leak check stays on.
    QProcessEnvironment environment = QProcessEnvironment::systemEnvironment();
    const QString asan = environment.value(QStringLiteral("ASAN_OPTIONS"));
    environment.insert(QStringLiteral("ASAN_OPTIONS"),
        asan.isEmpty() ? QStringLiteral("detect_leaks=0") : asan + QStringLiteral(":detect_leaks=0"));
    process.setProcessEnvironment(environment);
#endif
    process.start(QStringLiteral(WISP_EDITOR_PATH), arguments);
    ProcessRun run;
    if (!process.waitForFinished(kRenderWaitMs)) {
        process.kill();
        process.waitForFinished(5000);
        run.output = QStringLiteral("(did not finish)");
        return run;
    }
    run.exitCode = process.exitStatus() == QProcess::NormalExit ? process.exitCode() : -2;
    run.output = QString::fromUtf8(process.readAll());
    return run;
}

// The bundled straight preset with green hair, so hair pixels are told from skin, background and grid.
QString writeGreenPreset(const QTemporaryDir& dir)
{
    QFile source(QStringLiteral(WISP_PRESETS_DIR "/straight.json"));
    EXPECT_TRUE(source.open(QIODevice::ReadOnly));
    QString text = QString::fromUtf8(source.readAll());
    text.replace(QStringLiteral("[0.16, 0.1, 0.06]"), QStringLiteral("[0.05, 0.45, 0.06]"));
    text.replace(QStringLiteral("[0.45, 0.3, 0.17]"), QStringLiteral("[0.08, 0.6, 0.1]"));
    const QString path = dir.filePath(QStringLiteral("green.json"));
    QFile out(path);
    EXPECT_TRUE(out.open(QIODevice::WriteOnly));
    out.write(text.toUtf8());
    return path;
}

double greenFraction(const QImage& image)
{
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    qint64 green = 0;
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x) {
            const QColor c = QColor::fromRgb(rgb.pixel(x, y));
            green += c.green() > c.red() + 20 && c.green() > c.blue() + 20 ? 1 : 0;
        }
    return static_cast<double>(green) / (static_cast<double>(rgb.width()) * rgb.height());
}

TEST(RenderCommand, WritesA640SquarePngWithHair)
{
    QTemporaryDir dir;
    ASSERT_TRUE(dir.isValid());
    const QString out = dir.filePath(QStringLiteral("x.png"));
    const ProcessRun run
        = runWisp({ QStringLiteral("--render"), out, QStringLiteral("--size"), QStringLiteral("640x640"),
            QStringLiteral("--preset"), writeGreenPreset(dir), QStringLiteral("--settle"), QStringLiteral("0.5") });
    ASSERT_EQ(run.exitCode, 0) << run.output.toStdString();
    const QImage image(out);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.width(), 640);
    EXPECT_EQ(image.height(), 640);
    // The default view frames the whole head: its hair covers a good part of the image.
    const double hair = greenFraction(image);
    EXPECT_GT(hair, 0.04) << "green (hair) pixels: " << hair;
    EXPECT_LT(hair, 0.6);
    // Nothing but the image is left in the folder (no temporary).
    EXPECT_EQ(QDir(dir.path()).entryList(QDir::Files).size(), 2); // green.json, x.png
}

TEST(RenderCommand, ATransparentBackgroundIsTransparentAroundTheHead)
{
    QTemporaryDir dir;
    const QString out = dir.filePath(QStringLiteral("t.png"));
    const ProcessRun run = runWisp({ QStringLiteral("--render"), out, QStringLiteral("--size"),
        QStringLiteral("200x160"), QStringLiteral("--settle"), QStringLiteral("0"), QStringLiteral("--transparent") });
    ASSERT_EQ(run.exitCode, 0) << run.output.toStdString();
    const QImage image = QImage(out).convertToFormat(QImage::Format_ARGB32);
    ASSERT_EQ(image.size(), QSize(200, 160));
    EXPECT_EQ(qAlpha(image.pixel(2, 2)), 0); // a corner: background
    EXPECT_EQ(qAlpha(image.pixel(100, 80)), 255); // the middle: the head
}

TEST(RenderCommand, ATurntableWritesNFramesThatDiffer)
{
    QTemporaryDir dir;
    const QString out = dir.filePath(QStringLiteral("turn.png"));
    const ProcessRun run = runWisp({ QStringLiteral("--render"), out, QStringLiteral("--size"), QStringLiteral("96x80"),
        QStringLiteral("--turntable"), QStringLiteral("3"), QStringLiteral("--settle"), QStringLiteral("0") });
    ASSERT_EQ(run.exitCode, 0) << run.output.toStdString();
    QStringList frames = QDir(dir.path()).entryList(QDir::Files, QDir::Name);
    EXPECT_EQ(frames, (QStringList{ "turn_0001.png", "turn_0002.png", "turn_0003.png" }));
    QImage first(dir.filePath(QStringLiteral("turn_0001.png")));
    QImage second(dir.filePath(QStringLiteral("turn_0002.png")));
    EXPECT_EQ(first.size(), QSize(96, 80));
    EXPECT_EQ(second.size(), QSize(96, 80));
    EXPECT_NE(first, second); // turned a third of the way round
}

TEST(RenderCommand, BadArgumentsAreNamed)
{
    struct Case {
        QStringList arguments;
        QString named;
    };
    const std::vector<Case> cases{
        { { "--render", "x.png", "--size", "640" }, "--size 640" },
        { { "--render", "x.png", "--size", "0x10" }, "--size 0x10" },
        { { "--render", "x.png", "--size", "9000x10" }, "--size 9000x10" },
        { { "--render", "x.png", "--turntable", "0" }, "--turntable 0" },
        { { "--render", "x.png", "--turntable", "two" }, "--turntable two" },
        { { "--render", "x.png", "--shadows", "maybe" }, "--shadows maybe" },
        { { "--render", "x.png", "--settle", "-1" }, "--settle -1" },
        { { "--render", "x.png", "--settle", "nan" }, "--settle nan" },
        { { "--render", "x.png", "--sise", "5x5" }, "--sise" },
        { { "--render", "x.png", "a.wisp", "b.obj" }, "b.obj" },
        { { "--render" }, "--render" },
        { { "--render", "x.png", "--preset" }, "--preset" },
    };
    for (const Case& c : cases) {
        QString error;
        EXPECT_FALSE(parseRenderCommand(c.arguments, &error)) << c.arguments.join(' ').toStdString();
        EXPECT_TRUE(error.contains(c.named)) << error.toStdString();
    }
    QString error;
    const std::optional<RenderRequest> good = parseRenderCommand(
        { "head.obj", "--render=o.png", "--size", "64x48", "--turntable", "8", "--shadows", "off", "--settle", "1.5" },
        &error);
    ASSERT_TRUE(good) << error.toStdString();
    EXPECT_EQ(good->output, "o.png");
    EXPECT_EQ(good->input, "head.obj");
    EXPECT_EQ(good->size, QSize(64, 48));
    EXPECT_EQ(good->turntableFrames, 8);
    EXPECT_FALSE(good->shadows);
    EXPECT_DOUBLE_EQ(good->settleSeconds, 1.5);
}

TEST(RenderCommand, BadFilesExitOneNamingThemAndWriteNothing)
{
    QTemporaryDir dir;
    const QString out = dir.filePath(QStringLiteral("x.png"));
    QFile garbage(dir.filePath(QStringLiteral("broken.wisp")));
    ASSERT_TRUE(garbage.open(QIODevice::WriteOnly));
    garbage.write("{ \"format\": \"wisp-project\", \"version\": ");
    garbage.close();
    QFile badPreset(dir.filePath(QStringLiteral("bad.json")));
    ASSERT_TRUE(badPreset.open(QIODevice::WriteOnly));
    badPreset.write("{ \"format\": \"wisp-preset\", \"version\": 2, \"parameters\": { \"gravity\": \"down\" } }");
    badPreset.close();
    QDir(dir.path()).mkdir(QStringLiteral("folder.png"));
    struct Case {
        QStringList arguments;
        QString named;
    };
    const std::vector<Case> cases{
        { { "--render", dir.filePath("missing/x.png") }, dir.filePath("missing") },
        { { "--render", dir.filePath("x.jpg") }, ".png" },
        { { "--render", dir.filePath("folder.png") }, "folder.png" },
        { { "--render", out, dir.filePath("nothing.wisp") }, "nothing.wisp" },
        { { "--render", out, dir.filePath("broken.wisp") }, "broken.wisp" },
        { { "--render", out, dir.filePath("bad.json") }, "bad.json" }, // not a head or project
        { { "--render", out, "--preset", dir.filePath("bad.json") }, "gravity" },
        { { "--render", out, "--preset", dir.filePath("none.json") }, "none.json" },
    };
    for (const Case& c : cases) {
        const ProcessRun run = runWisp(c.arguments);
        EXPECT_EQ(run.exitCode, 1) << c.arguments.join(' ').toStdString() << "\n" << run.output.toStdString();
        EXPECT_TRUE(run.output.contains(c.named)) << run.output.toStdString();
        EXPECT_FALSE(QFile::exists(out));
    }
}

TEST(RenderCommand, TurntableFramesAreNumberedToSortByName)
{
    EXPECT_EQ(turntableFramePath(QStringLiteral("/a/out.png"), 0, 24), QStringLiteral("/a/out_0001.png"));
    EXPECT_EQ(turntableFramePath(QStringLiteral("/a/out.png"), 23, 24), QStringLiteral("/a/out_0024.png"));
    EXPECT_EQ(turntableFramePath(QStringLiteral("out.png"), 99999, 100000), QStringLiteral("out_100000.png"));
}

} // namespace
} // namespace wisp
