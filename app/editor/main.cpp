// wisp: the editor. `wisp` opens the built-in head and hairstyle; `wisp HEAD.obj` grooms that head.

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
    parser.addPositionalArgument(QStringLiteral("file"), QStringLiteral("a head mesh to open (OBJ, PLY, OFF, STL)"));
    parser.process(app);

    wisp::MainWindow window;
    window.show();
    if (!parser.positionalArguments().isEmpty()) {
        const QString path = parser.positionalArguments().constFirst();
        QTimer::singleShot(0, &window, [&window, path] { window.openHead(path); });
    }
    return QApplication::exec();
}
