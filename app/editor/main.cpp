// wisp: the editor. `wisp` opens the built-in head and hairstyle; `wisp PROJECT.wisp` opens a
// project; `wisp HEAD.obj` (or .ply, .off, .stl, .gltf, .glb) grooms that head.

#include "app/editor/FileMenu.h"
#include "app/editor/MainWindow.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QTimer>

int main(int argc, char** argv)
{
    QApplication app(argc, argv);
    QApplication::setOrganizationName(QStringLiteral("Wisp"));
    QApplication::setApplicationName(QStringLiteral("Wisp"));
    QApplication::setApplicationVersion(QStringLiteral("0.1"));

    QCommandLineParser parser;
    parser.setApplicationDescription(QStringLiteral("Hair styling and simulation editor"));
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addPositionalArgument(QStringLiteral("file"), QStringLiteral("a project (.wisp) or a head mesh (OBJ, PLY, OFF, STL, glTF) to open"));
    parser.process(app);

    wisp::MainWindow window;
    window.show();
    if (!parser.positionalArguments().isEmpty()) {
        const QString path = parser.positionalArguments().constFirst();
        QTimer::singleShot(0, &window, [&window, path] { window.fileMenu()->openAny(path); });
    }
    return QApplication::exec();
}
