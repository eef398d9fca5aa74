#include "widgets/ViewportOverlay.h"

#include <QFont>
#include <QFontDatabase>
#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <array>
#include <cmath>

namespace wisp {

QString composeHudText(const Frame* frame, double framesPerSecond, double drawnFraction, bool preview)
{
    const double fps = std::isfinite(framesPerSecond) ? std::max(framesPerSecond, 0.0) : 0.0;
    QString text = QStringLiteral("fps %1").arg(std::lround(fps));
    if (!frame)
        return text + QStringLiteral(" · no hair");
    const double stepMs = std::isfinite(frame->stepMilliseconds) ? frame->stepMilliseconds : 0.0;
    text += QStringLiteral(" · sim %1 ms/step · %2 strands · %3 particles")
                .arg(stepMs, 0, 'f', 2)
                .arg(frame->strands.strandCount())
                .arg(frame->simulatedParticles);
    if (std::isfinite(frame->timeScale) && frame->timeScale < 1.0)
        text += QStringLiteral(" · slow motion x%1").arg(frame->timeScale, 0, 'g', 3);
    if (frame->fallingBehind)
        text += QStringLiteral(" · falling behind");
    if (preview && std::isfinite(drawnFraction) && drawnFraction < 0.995)
        text += QStringLiteral(" · preview %1%").arg(std::lround(std::max(drawnFraction, 0.0) * 100.0));
    else if (preview)
        text += QStringLiteral(" · preview");
    return text;
}

namespace {

QFont hudFont()
{
    QFont font = QFontDatabase::systemFont(QFontDatabase::FixedFont);
    font.setPointSizeF(std::max(font.pointSizeF(), 9.0));
    return font;
}

QRectF hudPanel(const QFont& font, const QString& text)
{
    const QFontMetricsF metrics(font);
    const QPointF origin(10.0, 8.0);
    return QRectF(origin, QSizeF(metrics.horizontalAdvance(text) + 12.0, metrics.height() + 6.0));
}

QImage transparentImage(QSizeF logical, double ratio)
{
    QImage image((logical * ratio).toSize().expandedTo(QSize(1, 1)), QImage::Format_RGBA8888_Premultiplied);
    image.setDevicePixelRatio(ratio);
    image.fill(Qt::transparent);
    return image;
}

} // namespace

void drawHud(QPainter& painter, const QString& text)
{
    painter.save();
    const QFont font = hudFont();
    painter.setFont(font);
    const QRectF panel = hudPanel(font, text);
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 110));
    painter.drawRoundedRect(panel, 4.0, 4.0);
    painter.setPen(QColor(230, 232, 236));
    painter.drawText(panel.adjusted(6.0, 3.0, -6.0, -3.0), Qt::AlignLeft | Qt::AlignVCenter, text);
    painter.restore();
}

void drawAxisGizmo(QPainter& painter, const QRectF& area, const glm::mat4& view)
{
    struct Axis {
        glm::vec3 direction; // view space
        QColor colour;
        QChar label;
    };
    std::array<Axis, 3> axes{ {
        { glm::vec3(view[0]), QColor(230, 70, 70), QLatin1Char('X') },
        { glm::vec3(view[1]), QColor(110, 205, 80), QLatin1Char('Y') },
        { glm::vec3(view[2]), QColor(80, 140, 240), QLatin1Char('Z') },
    } };
    // Painter's algorithm: the axis most away from the viewer (most negative view z) first.
    std::sort(axes.begin(), axes.end(), [](const Axis& a, const Axis& b) { return a.direction.z < b.direction.z; });

    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    const QPointF centre = area.center();
    const double radius = 0.5 * std::min(area.width(), area.height());
    const double length = radius - 9.0;
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 50));
    painter.drawEllipse(centre, radius, radius);

    QFont font = painter.font();
    font.setPixelSize(10);
    font.setBold(true);
    painter.setFont(font);
    for (const Axis& axis : axes) {
        // View space has y up; the painter's y runs down.
        const QPointF end = centre + QPointF(axis.direction.x, -axis.direction.y) * length;
        QColor colour = axis.colour;
        if (axis.direction.z < 0.0f)
            colour = colour.darker(150);
        painter.setPen(QPen(colour, 2.0, Qt::SolidLine, Qt::RoundCap));
        painter.drawLine(centre, end);
        painter.setPen(Qt::NoPen);
        painter.setBrush(colour);
        painter.drawEllipse(end, 7.0, 7.0);
        painter.setPen(QColor(20, 20, 24));
        painter.drawText(QRectF(end.x() - 7.0, end.y() - 7.0, 14.0, 14.0), Qt::AlignCenter, QString(axis.label));
    }
    painter.restore();
}

QImage paintHudImage(const QString& text, double ratio)
{
    const QRectF panel = hudPanel(hudFont(), text);
    QImage image = transparentImage(QSizeF(std::ceil(panel.right()) + 1.0, std::ceil(panel.bottom()) + 1.0), ratio);
    QPainter painter(&image);
    drawHud(painter, text);
    return image;
}

QImage paintGizmoImage(const glm::mat4& view, double ratio)
{
    const double size = kGizmoImageSize;
    QImage image = transparentImage(QSizeF(size, size), ratio);
    QPainter painter(&image);
    const double margin = 8.0;
    drawAxisGizmo(painter, QRectF(margin, margin, size - 2.0 * margin, size - 2.0 * margin), view);
    return image;
}

} // namespace wisp
