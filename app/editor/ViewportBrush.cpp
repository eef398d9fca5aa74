#include "app/editor/ViewportBrush.h"

#include "widgets/Viewport.h"

#include <QKeyEvent>
#include <QMouseEvent>

namespace wisp {

ViewportBrush::ViewportBrush(Viewport* viewport, QObject* parent)
    : QObject(parent)
    , m_viewport(viewport)
{
    m_viewport->installEventFilter(this);
    m_viewport->setMouseTracking(true); // the ring follows the cursor without a button held
}

void ViewportBrush::moveCursor(QPointF position, Qt::KeyboardModifiers modifiers)
{
    m_lastCursor = position;
    showCursor(position, modifiers);
}

bool ViewportBrush::eventFilter(QObject* watched, QEvent* event)
{
    if (watched != m_viewport || !brushEnabled())
        return QObject::eventFilter(watched, event);
    switch (event->type()) {
    case QEvent::MouseButtonPress: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (e->button() != Qt::LeftButton || (e->modifiers() & Qt::AltModifier))
            return false; // Alt + drag belongs to the camera
        moveCursor(e->position(), e->modifiers());
        m_stroking = beginStroke(e->position(), e->modifiers());
        return m_stroking;
    }
    case QEvent::MouseMove: {
        auto* e = static_cast<QMouseEvent*>(event);
        moveCursor(e->position(), e->modifiers());
        if (!m_stroking)
            return false; // camera drags pass through
        continueStroke(e->position(), e->modifiers());
        return true;
    }
    case QEvent::MouseButtonRelease: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (e->button() != Qt::LeftButton || !m_stroking)
            return false;
        m_stroking = false;
        finishStroke(e->position(), e->modifiers());
        return true;
    }
    case QEvent::Leave:
        m_viewport->setBrushCursor(std::nullopt);
        return false;
    case QEvent::KeyPress:
    case QEvent::KeyRelease: {
        auto* e = static_cast<QKeyEvent*>(event);
        if (keyPressed(e))
            return true;
        if ((e->key() == Qt::Key_Control || e->key() == Qt::Key_Shift) && hasCursor())
            showCursor(m_lastCursor, e->modifiers()); // the ring shows what a held key changes
        return false;
    }
    default:
        return false;
    }
}

} // namespace wisp
