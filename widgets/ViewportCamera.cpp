// Viewport's camera: projection and picking rays, and the mouse, wheel and key input that moves it.
#include "widgets/Viewport.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QWheelEvent>

namespace wisp {

float Viewport::aspect() const
{
    if (m_image)
        return static_cast<float>(m_image->pixels.width()) / static_cast<float>(m_image->pixels.height());
    return height() > 0 ? static_cast<float>(width()) / static_cast<float>(height()) : 1.0f;
}

glm::vec2 Viewport::project(const glm::vec3& worldMetres) const
{
    return m_camera.project(worldMetres, glm::vec2(width(), height()));
}

ViewRay Viewport::rayAt(QPointF logicalPixel) const
{
    // The same size and aspect that project() uses, so the two are exact inverses.
    const glm::vec2 size(static_cast<float>(width()), static_cast<float>(height()));
    const float rayAspect = size.y > 0.0f ? size.x / size.y : 1.0f;
    const glm::vec2 ndc = size.x > 0.0f && size.y > 0.0f
        ? glm::vec2(2.0f * static_cast<float>(logicalPixel.x()) / size.x - 1.0f,
            1.0f - 2.0f * static_cast<float>(logicalPixel.y()) / size.y)
        : glm::vec2(0.0f);
    // In view space the ray through NDC (x, y) runs along (x / P00, y / P11, -1) from the eye.
    const glm::mat4 projection = m_camera.projection(rayAspect);
    const glm::vec3 directionView{ ndc.x / projection[0][0], ndc.y / projection[1][1], -1.0f };
    const glm::mat4 viewToWorld = glm::inverse(m_camera.view());
    return { glm::vec3(viewToWorld[3]), glm::normalize(glm::mat3(viewToWorld) * directionView) };
}

void Viewport::frameHead()
{
    m_camera.frame(m_headBounds, aspect());
    scheduleFrame();
}

void Viewport::cameraMovedByUser()
{
    m_cameraTouched = true;
    scheduleFrame();
}

void Viewport::mousePressEvent(QMouseEvent* event)
{
    const Qt::KeyboardModifiers mods = event->modifiers();
    Drag drag = Drag::None;
    if (event->button() == Qt::MiddleButton) {
        // Blender: middle orbits, Shift pans, Ctrl zooms. Maya: Alt + middle pans.
        if (mods & Qt::ShiftModifier || mods & Qt::AltModifier)
            drag = Drag::Pan;
        else if (mods & Qt::ControlModifier)
            drag = Drag::Dolly;
        else
            drag = Drag::Orbit;
    } else if (event->button() == Qt::LeftButton && (mods & Qt::AltModifier)) {
        drag = Drag::Orbit; // Maya
    } else if (event->button() == Qt::RightButton && (mods & Qt::AltModifier)) {
        drag = Drag::Dolly; // Maya
    }
    if (drag == Drag::None) {
        event->ignore(); // for the editor's tools
        return;
    }
    m_drag = drag;
    m_dragButton = event->button();
    m_lastMouse = event->position();
    event->accept();
}

void Viewport::mouseMoveEvent(QMouseEvent* event)
{
    if (m_drag == Drag::None) {
        event->ignore();
        return;
    }
    const QPointF delta = event->position() - m_lastMouse;
    m_lastMouse = event->position();
    switch (m_drag) {
    case Drag::Orbit:
        m_camera.orbit(static_cast<float>(delta.x()), static_cast<float>(delta.y()));
        break;
    case Drag::Pan:
        m_camera.pan(static_cast<float>(delta.x()), static_cast<float>(delta.y()), static_cast<float>(height()));
        break;
    case Drag::Dolly:
        m_camera.dolly(static_cast<float>(delta.y()));
        break;
    case Drag::None:
        break;
    }
    cameraMovedByUser();
    event->accept();
}

void Viewport::mouseReleaseEvent(QMouseEvent* event)
{
    if (m_drag != Drag::None && event->button() == m_dragButton) {
        m_drag = Drag::None;
        m_dragButton = Qt::NoButton;
        event->accept();
        return;
    }
    event->ignore();
}

void Viewport::wheelEvent(QWheelEvent* event)
{
    // angleDelta is in eighths of a degree; a notch of a common mouse wheel is 15 degrees.
    const QPoint angle = event->angleDelta();
    const int eighths = angle.y() != 0 ? angle.y() : angle.x();
    if (eighths == 0) {
        event->ignore();
        return;
    }
    m_camera.zoom(static_cast<float>(eighths) / 120.0f);
    cameraMovedByUser();
    event->accept();
}

void Viewport::keyPressEvent(QKeyEvent* event)
{
    if (event->key() == Qt::Key_F && !(event->modifiers() & (Qt::ControlModifier | Qt::AltModifier))) {
        frameHead();
        event->accept();
        return;
    }
    QWidget::keyPressEvent(event);
}

} // namespace wisp
