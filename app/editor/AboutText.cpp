#include "app/editor/AboutText.h"

#include "sim/util/CpuName.h"
#include "sim/util/SimdTarget.h"

#include <QCoreApplication>
#include <QtGlobal>

namespace wisp {

QString aboutText(const QString& glDescription)
{
    auto tr = [](const char* text) { return QCoreApplication::translate("AboutText", text); };
    const QString solver = tr("%1 (%2 floats a register), chosen for this CPU when Wisp started")
                               .arg(QString::fromLatin1(solverSimdTarget()))
                               .arg(solverVectorFloats());
    const QString gl = glDescription.isEmpty() ? tr("not started yet") : glDescription.toHtmlEscaped();
    return tr("<b>Wisp</b> — hair styling and simulation.<br>Paint where hair grows, shape it into wisps, and "
              "watch it move under gravity and wind while you edit.")
        + QStringLiteral("<p>")
        + tr("CPU: %1<br>Solver kernels: %2<br>Qt: %3<br>OpenGL: %4")
              .arg(QString::fromStdString(cpuModelName()).toHtmlEscaped(), solver, QString::fromLatin1(qVersion()), gl)
        + QStringLiteral("</p>");
}

} // namespace wisp
