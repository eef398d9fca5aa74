#include "app/editor/HeadMoveTool.h"

#include "app/editor/Document.h"
#include "app/editor/SimulationHost.h"
#include "sim/motion/FrameTime.h"
#include "widgets/Viewport.h"

#include <QMouseEvent>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace wisp {

double keySecondsFor(const HeadMotion& motion, double timeSeconds, double fps)
{
    return motion.keys().empty() ? 0.0 : snappedToFrame(timeSeconds, fps);
}

HeadMotion keyedMotion(HeadMotion motion, double timeSeconds, double fps, const HeadPose& pose)
{
    motion.setKey(keySecondsFor(motion, timeSeconds, fps), pose);
    return motion;
}

HeadMoveTool::HeadMoveTool(Document* document, Viewport* viewport, SimulationHost* simulation, QObject* parent)
    : QObject(parent)
    , m_document(document)
    , m_viewport(viewport)
    , m_simulation(simulation)
{
    m_viewport->installEventFilter(this);
}

double HeadMoveTool::currentSeconds() const
{
    if (m_timelineSeconds)
        if (const std::optional<double> onTimeline = m_timelineSeconds())
            return *onTimeline;
    const FramePtr frame = m_simulation->latestFrame();
    return frame ? frame->simulatedSeconds : 0.0;
}

bool HeadMoveTool::eventFilter(QObject* watched, QEvent* event)
{
    if (watched != m_viewport)
        return false;
    switch (event->type()) {
    case QEvent::MouseButtonPress: {
        auto* e = static_cast<QMouseEvent*>(event);
        const Qt::KeyboardModifiers mods = e->modifiers();
        if (m_drag || !(mods & Qt::ControlModifier) || !(mods & Qt::AltModifier))
            return false;
        Kind kind;
        if (e->button() == Qt::LeftButton)
            kind = (mods & Qt::ShiftModifier) ? Kind::Move : Kind::Turn;
        else if (e->button() == Qt::MiddleButton)
            kind = Kind::Move;
        else
            return false;
        Drag drag;
        drag.kind = kind;
        drag.start = drag.last = e->position();
        drag.motion = m_document->headMotion();
        drag.keySeconds = keySecondsFor(drag.motion, currentSeconds(), m_document->timeline().fps);
        drag.startPose = drag.pose = drag.motion.keyedPoseAt(drag.keySeconds);
        m_drag = drag;
        return true;
    }
    case QEvent::MouseMove:
        if (!m_drag)
            return false;
        update(static_cast<QMouseEvent*>(event)->position());
        m_simulation->setHeadMotion(draggedMotion());
        return true;
    case QEvent::MouseButtonRelease: {
        if (!m_drag)
            return false;
        update(static_cast<QMouseEvent*>(event)->position());
        const bool moved = m_drag->pose != m_drag->startPose;
        const HeadMotion motion = draggedMotion();
        const Kind kind = m_drag->kind;
        m_drag.reset();
        if (!moved) {
            m_simulation->setHeadMotion(m_document->headMotion());
            return true;
        }
        const QString refused
            = m_document->setHeadMotion(motion, kind == Kind::Turn ? tr("Turn Head") : tr("Move Head"));
        if (!refused.isEmpty()) {
            m_simulation->setHeadMotion(m_document->headMotion()); // back to what the document has
            emit message(refused);
        }
        return true;
    }
    default:
        return false;
    }
}

void HeadMoveTool::update(QPointF position)
{
    Drag& d = *m_drag;
    const QPointF delta = position - d.last;
    d.last = position;
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::vec3 viewDirection
        = m_viewport->rayAt(QPointF(m_viewport->width() / 2.0, m_viewport->height() / 2.0)).direction;
    if (d.kind == Kind::Turn) {
        // Blender's trackball feel: sideways turns about the world's vertical, up/down about the
        // view's horizontal axis; both applied in world space, about the pivot.
        glm::vec3 right = glm::cross(viewDirection, up);
        right = glm::length(right) > 1e-4f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
        const float yaw = glm::radians(kDegreesPerPixel * static_cast<float>(delta.x()));
        const float pitch = glm::radians(kDegreesPerPixel * static_cast<float>(delta.y()));
        d.pose.rotation = glm::normalize(glm::angleAxis(yaw, up) * glm::angleAxis(pitch, right) * d.pose.rotation);
    } else {
        // The head follows the cursor in the plane through its pivot that faces the camera.
        const glm::mat4 toWorld = headToWorld(d.pose, pivotOf(m_document->head()));
        const glm::vec3 pivotWorld = glm::vec3(toWorld * glm::vec4(pivotOf(m_document->head()), 1.0f));
        const auto onPlane = [&](QPointF p) {
            const ViewRay ray = m_viewport->rayAt(p);
            const float along = glm::dot(ray.direction, viewDirection);
            if (std::abs(along) < 1e-6f)
                return pivotWorld;
            const float t = glm::dot(pivotWorld - ray.origin, viewDirection) / along;
            return ray.origin + t * ray.direction;
        };
        d.pose.translationMetres += onPlane(position) - onPlane(position - delta);
    }
}

HeadMotion HeadMoveTool::draggedMotion() const
{
    HeadMotion motion = m_drag->motion;
    motion.setKey(m_drag->keySeconds, m_drag->pose);
    return motion;
}

} // namespace wisp
