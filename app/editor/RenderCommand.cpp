#include "app/editor/RenderCommand.h"

#include "app/editor/Document.h"
#include "app/editor/HeadImporter.h"
#include "app/editor/ImageFiles.h"
#include "app/editor/SettledScene.h"
#include "io/MeshReader.h"
#include "io/PresetFile.h"
#include "io/ProjectFile.h"
#include "sim/geometry/Body.h"
#include "sim/groom/GrowthMap.h"
#include "widgets/Viewport.h"

#include <QFileInfo>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

namespace wisp {

namespace {

// The value after option `arguments[i]`, or the part after '=' in "--option=value".
std::optional<QString> valueOf(const QStringList& arguments, int& i, const QString& option, QString* error)
{
    const QString& argument = arguments[i];
    if (argument.startsWith(option + QLatin1Char('=')))
        return argument.mid(option.size() + 1);
    if (i + 1 >= arguments.size()) {
        *error = option + QStringLiteral(": a value is missing");
        return std::nullopt;
    }
    return arguments[++i];
}

bool isOption(const QString& argument, const QString& option)
{
    return argument == option || argument.startsWith(option + QLatin1Char('='));
}

bool isMeshFile(const QString& path)
{
    const std::string suffix = QFileInfo(path).suffix().toLower().toStdString();
    const auto& known = io::supportedMeshExtensions();
    return std::any_of(
        known.begin(), known.end(), [&](const std::string& e) { return e == suffix || e == "." + suffix; });
}

// The built-in scene, a project, or a head with its scalp grown; `error` names the file otherwise.
bool loadInput(const QString& input, Document& document, QString* error)
{
    if (input.isEmpty())
        return true;
    const QFileInfo info(input);
    if (!info.exists()) {
        *error = input + QStringLiteral(": no such file");
        return false;
    }
    if (!info.isFile()) {
        *error = input + QStringLiteral(": not a regular file");
        return false;
    }
    if (info.suffix().compare(QStringLiteral("wisp"), Qt::CaseInsensitive) == 0) {
        io::Result<io::ProjectReadResult> read = io::readProject(input.toStdString(), io::readHeadFile);
        if (!read) {
            *error = QString::fromStdString(read.error().toString());
            return false;
        }
        document.loadProject(std::move(read).value().project);
        return true;
    }
    if (!isMeshFile(input)) {
        *error = input + QStringLiteral(": not a project (.wisp) or a head mesh (OBJ, PLY, OFF, STL, glTF, GLB)");
        return false;
    }
    HeadImporter importer(nullptr);
    std::shared_ptr<const ImportedHead> head;
    QObject::connect(&importer, &HeadImporter::imported, [&head](std::shared_ptr<const ImportedHead> h) { head = h; });
    QObject::connect(&importer, &HeadImporter::failed, [error](const QString& why) { *error = why; });
    importer.start(input);
    importer.waitForFinished();
    if (!head) {
        if (error->isEmpty())
            *error = input + QStringLiteral(": the head could not be read");
        return false;
    }
    TriangleMesh mesh = head->mesh;
    std::vector<float> weights = scalpGrowth(mesh);
    document.replaceHead(std::move(mesh), std::move(weights), info.fileName(), input, head->placement);
    return true;
}

} // namespace

bool wantsRender(const QStringList& arguments)
{
    return std::any_of(
        arguments.begin(), arguments.end(), [](const QString& a) { return isOption(a, QStringLiteral("--render")); });
}

std::optional<RenderRequest> parseRenderCommand(const QStringList& arguments, QString* error)
{
    QString scratch;
    QString& why = error ? *error : scratch;
    RenderRequest request;
    bool haveOutput = false;
    for (int i = 0; i < arguments.size(); ++i) {
        const QString& a = arguments[i];
        if (isOption(a, QStringLiteral("--render"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--render"), &why);
            if (!v)
                return std::nullopt;
            request.output = *v;
            haveOutput = true;
        } else if (isOption(a, QStringLiteral("--size"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--size"), &why);
            if (!v)
                return std::nullopt;
            request.size = parseImageSize(*v, Viewport::kMaxImageSide, &why);
            if (request.size.isEmpty())
                return std::nullopt;
        } else if (isOption(a, QStringLiteral("--turntable"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--turntable"), &why);
            if (!v)
                return std::nullopt;
            bool ok = false;
            const int frames = v->toInt(&ok);
            if (!ok || frames < 1 || frames > kMaxTurntableFrames) {
                why = QStringLiteral("--turntable %1: the number of frames must be a whole number from 1 to %2")
                          .arg(*v)
                          .arg(kMaxTurntableFrames);
                return std::nullopt;
            }
            request.turntableFrames = frames;
        } else if (isOption(a, QStringLiteral("--shadows"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--shadows"), &why);
            if (!v)
                return std::nullopt;
            if (*v != QStringLiteral("on") && *v != QStringLiteral("off")) {
                why = QStringLiteral("--shadows %1: must be on or off").arg(*v);
                return std::nullopt;
            }
            request.shadows = *v == QStringLiteral("on");
        } else if (isOption(a, QStringLiteral("--preset"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--preset"), &why);
            if (!v)
                return std::nullopt;
            request.preset = *v;
        } else if (isOption(a, QStringLiteral("--settle"))) {
            const auto v = valueOf(arguments, i, QStringLiteral("--settle"), &why);
            if (!v)
                return std::nullopt;
            bool ok = false;
            const double seconds = v->toDouble(&ok);
            if (!ok || !std::isfinite(seconds) || seconds < 0.0 || seconds > kMaxSettleSeconds) {
                why = QStringLiteral("--settle %1: must be a number of seconds from 0 to %2")
                          .arg(*v)
                          .arg(kMaxSettleSeconds);
                return std::nullopt;
            }
            request.settleSeconds = seconds;
        } else if (a == QStringLiteral("--transparent")) {
            request.transparent = true;
        } else if (a.startsWith(QLatin1Char('-')) && a.size() > 1) {
            why = QStringLiteral(
                "%1: unknown option (--render takes --size, --turntable, --shadows, --preset, --settle, "
                "--transparent)")
                      .arg(a);
            return std::nullopt;
        } else if (request.input.isEmpty()) {
            request.input = a;
        } else {
            why = QStringLiteral("%1: only one project or head can be rendered (already %2)").arg(a, request.input);
            return std::nullopt;
        }
    }
    if (!haveOutput || request.output.isEmpty()) {
        why = QStringLiteral("--render: the output PNG is missing");
        return std::nullopt;
    }
    return request;
}

int runRenderCommand(const RenderRequest& request, QTextStream& out, QTextStream& err)
{
    const auto fail = [&err](const QString& why) {
        err << "wisp --render: " << why << Qt::endl;
        return 1;
    };
    // Before the work: where it goes, then what it reads.
    if (const QString problem = checkPngOutput(request.output); !problem.isEmpty())
        return fail(problem);
    std::optional<io::Preset> preset;
    if (!request.preset.isEmpty()) {
        io::Result<io::PresetReadResult> read = io::readPreset(request.preset.toStdString());
        if (!read)
            return fail(QString::fromStdString(read.error().toString()));
        io::PresetReadResult result = std::move(read).value();
        for (const std::string& warning : result.warnings)
            err << "wisp --render: " << request.preset << ": " << QString::fromStdString(warning) << Qt::endl;
        preset = std::move(result.preset);
    }
    Document document;
    QString problem;
    if (!loadInput(request.input, document, &problem))
        return fail(problem);
    if (preset)
        document.applyPreset(*preset);

    SceneToSettle scene{ document.head(), document.regions(), document.soloRegion(), document.parameters(),
        document.style() };
    const int steps = settleStepsFor(request.settleSeconds, document.parameters().get(Param::TimeStep));
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const SettledFrame settled = settleScene(scene, steps, threads);
    if (!settled.frame)
        return fail(QString::fromStdString(settled.error));

    Viewport viewport;
    viewport.resize(request.size);
    viewport.setHead(document.head());
    viewport.setBody(
        document.parameters().get(Param::Body) != 0.0 ? defaultBody(document.head()) : std::vector<Capsule>{});
    viewport.setShowGrowthOverlay(false);
    viewport.setFrame(settled.frame);
    viewport.setShadowsEnabled(request.shadows);
    const int images = std::max(request.turntableFrames, 1);
    for (int i = 0; i < images; ++i) {
        Viewport::ImageOptions options;
        options.transparentBackground = request.transparent;
        // A turntable goes once around the head, the first frame in the view's start-up direction.
        options.turnRadians = 2.0f * std::numbers::pi_v<float> * static_cast<float>(i) / static_cast<float>(images);
        const QImage image = viewport.renderImage(request.size, options);
        if (image.isNull())
            return fail(viewport.glStatus().isEmpty() ? QStringLiteral("the view could not be drawn (no OpenGL 3.3?)")
                                                      : viewport.glStatus());
        const QString path
            = request.turntableFrames > 0 ? turntableFramePath(request.output, i, images) : request.output;
        if (const QString error = writePngAtomically(path, image); !error.isEmpty())
            return fail(error);
        out << "wrote " << path << " (" << image.width() << "x" << image.height() << ", "
            << settled.frame->strands.strandCount() << " strands settled " << steps << " steps)" << Qt::endl;
    }
    return 0;
}

} // namespace wisp
