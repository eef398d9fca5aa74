#include "widgets/ViewportOverlay.h"

#include <QFont>
#include <QFontDatabase>
#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>
#include <QPolygonF>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace wisp {

QString composeHudText(const Frame* frame, double framesPerSecond, double drawnFraction, bool preview, bool paused)
{
    if (paused) {
        if (!frame)
            return QStringLiteral("paused · no hair");
        return QStringLiteral("paused · %1 strands · %2 particles")
            .arg(frame->strands.strandCount())
            .arg(frame->simulatedParticles);
    }
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

QImage paintGizmoImage(const glm::mat4& view, double ratio, const glm::vec3& windMetresPerSecond)
{
    const double size = kGizmoImageSize;
    const float speed = glm::length(windMetresPerSecond);
    const bool wind = std::isfinite(speed) && speed > 1e-3f;
    QImage image = transparentImage(QSizeF(size + (wind ? kWindIndicatorWidth : 0), size), ratio);
    QPainter painter(&image);
    const double margin = 8.0;
    drawAxisGizmo(painter, QRectF(margin, margin, size - 2.0 * margin, size - 2.0 * margin), view);
    if (wind)
        drawWindIndicator(painter, QRectF(size, margin, kWindIndicatorWidth - margin, size - 2.0 * margin), view,
            windMetresPerSecond);
    return image;
}

void drawWindIndicator(
    QPainter& painter, const QRectF& area, const glm::mat4& view, const glm::vec3& windMetresPerSecond)
{
    const float speed = glm::length(windMetresPerSecond);
    if (!std::isfinite(speed) || speed <= 1e-3f)
        return;
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    const QColor blue(70, 150, 245);
    const double radius = 0.5 * std::min(area.width(), area.height() - 14.0);
    const QPointF centre(area.center().x(), area.top() + radius);
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(0, 0, 0, 50));
    painter.drawEllipse(centre, radius, radius);
    // The wind's direction in view space; the painter's y runs down. Toward or away from the viewer
    // it shrinks on screen, as the axes do.
    const glm::vec3 direction = glm::mat3(view) * (windMetresPerSecond / speed);
    const QPointF half = QPointF(direction.x, -direction.y) * (radius - 6.0);
    const QPointF tail = centre - half;
    const QPointF tip = centre + half;
    painter.setPen(QPen(direction.z < 0.0f ? blue.darker(140) : blue, 3.0, Qt::SolidLine, Qt::RoundCap));
    painter.drawLine(tail, tip);
    const double length = std::hypot(half.x(), half.y());
    if (length > 2.0) {
        const QPointF along = half / length;
        const QPointF across(-along.y(), along.x());
        const QPolygonF head{ tip + along * 3.0, tip - along * 7.0 + across * 5.0, tip - along * 7.0 - across * 5.0 };
        painter.setPen(Qt::NoPen);
        painter.setBrush(blue);
        painter.drawPolygon(head);
    } else {
        painter.setPen(Qt::NoPen);
        painter.setBrush(blue);
        painter.drawEllipse(centre, 4.0, 4.0); // straight along the view
    }
    QFont font = painter.font();
    font.setPixelSize(10);
    painter.setFont(font);
    painter.setPen(QColor(225, 228, 235));
    painter.drawText(QRectF(area.left(), area.bottom() - 12.0, area.width(), 14.0), Qt::AlignCenter,
        QStringLiteral("%1 m/s").arg(static_cast<double>(speed), 0, 'g', 3));
    painter.restore();
}

} // namespace wisp
