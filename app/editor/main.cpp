// wisp: the editor. `wisp` opens the built-in head and hairstyle; `wisp PROJECT.wisp` opens a
// project; `wisp HEAD.obj` (or .ply, .off, .stl, .gltf, .glb) grooms that head.
// `wisp --render OUT.png [PROJECT_OR_HEAD] [--size WxH] …` draws an image without a window and
// exits (see app/editor/RenderCommand.h).

#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"
#include "app/editor/RenderCommand.h"
#include "widgets/HeapPolicy.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QTextStream>
#include <QTimer>

int main(int argc, char** argv)
{
    wisp::keepFreedHeapForReuse(); // the software rasteriser's per-paint memory (widgets/HeapPolicy.h)
    QApplication app(argc, argv);
    QApplication::setOrganizationName(QStringLiteral("Wisp"));
    QApplication::setApplicationName(QStringLiteral("Wisp"));
    QApplication::setApplicationVersion(QStringLiteral("0.1"));

    const QStringList arguments = QApplication::arguments().mid(1);
    if (wisp::wantsRender(arguments)) {
        QTextStream out(stdout);
        QTextStream err(stderr);
        QString error;
        const std::optional<wisp::RenderRequest> request = wisp::parseRenderCommand(arguments, &error);
        if (!request) {
            err << "wisp --render: " << error << Qt::endl;
            return 1;
        }
        return wisp::runRenderCommand(*request, out, err);
    }

    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral("Hair styling and simulation editor"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument(
        QStringLiteral("file"), QStringLiteral("a project (.wisp) or a head mesh (OBJ, PLY, OFF, STL, glTF) to open"));
    parser.process(app);

    wisp::MainWindow window;
    window.show();
    if (!parser.positionalArguments().isEmpty()) {
        const QString path = parser.positionalArguments().constFirst();
        QTimer::singleShot(0, &window, [&window, path] { window.fileMenu()->openAny(path); });
    }
    return QApplication::exec();
}
