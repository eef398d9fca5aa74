#include "widgets/ViewportWindow.h"

#include <QCoreApplication>
#include <QEnterEvent>
#include <QExposeEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPlatformSurfaceEvent>
#include <QWheelEvent>

namespace wisp {

ViewportWindow::ViewportWindow(QWidget* inputTarget)
    : m_target(inputTarget)
{
    setSurfaceType(QSurface::OpenGLSurface);
}

void ViewportWindow::exposeEvent(QExposeEvent*)
{
    if (isExposed())
        emit exposed();
}

bool ViewportWindow::event(QEvent* event)
{
    switch (event->type()) {
    case QEvent::PlatformSurface:
        if (static_cast<QPlatformSurfaceEvent*>(event)->surfaceEventType()
            == QPlatformSurfaceEvent::SurfaceAboutToBeDestroyed)
            emit surfaceAboutToBeDestroyed();
        break;
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    case QEvent::MouseMove:
    case QEvent::Wheel:
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
    case QEvent::ShortcutOverride:
    case QEvent::Enter:
    case QEvent::Leave:
        return forward(event);
    default:
        break;
    }
    return QWindow::event(event);
}

bool ViewportWindow::forward(QEvent* event)
{
    QWidget* target = m_target.data();
    if (!target || !target->isEnabled())
        return false;
    switch (event->type()) {
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    case QEvent::MouseMove: {
        auto* e = static_cast<QMouseEvent*>(event);
        if (e->type() == QEvent::MouseMove && e->buttons() == Qt::NoButton && !target->hasMouseTracking())
            return true;
        const QPointF global = e->globalPosition();
        QMouseEvent copy(e->type(), target->mapFromGlobal(global), target->window()->mapFromGlobal(global), global,
            e->button(), e->buttons(), e->modifiers(), e->pointingDevice());
        copy.setTimestamp(e->timestamp());
        QCoreApplication::sendEvent(target, &copy);
        event->setAccepted(copy.isAccepted());
        return true;
    }
    case QEvent::Wheel: {
        auto* e = static_cast<QWheelEvent*>(event);
        const QPointF global = e->globalPosition();
        QWheelEvent copy(target->mapFromGlobal(global), global, e->pixelDelta(), e->angleDelta(), e->buttons(),
            e->modifiers(), e->phase(), e->inverted(), e->source(), e->pointingDevice());
        copy.setTimestamp(e->timestamp());
        QCoreApplication::sendEvent(target, &copy);
        event->setAccepted(copy.isAccepted());
        return true;
    }
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
    case QEvent::ShortcutOverride: {
        auto* e = static_cast<QKeyEvent*>(event);
        QKeyEvent copy(e->type(), e->key(), e->modifiers(), e->nativeScanCode(), e->nativeVirtualKey(),
            e->nativeModifiers(), e->text(), e->isAutoRepeat(), static_cast<quint16>(e->count()));
        copy.setTimestamp(e->timestamp());
        // Unaccepted, a shortcut override lets the shortcut run, as it does for a widget.
        copy.setAccepted(event->type() != QEvent::ShortcutOverride);
        QCoreApplication::sendEvent(target, &copy);
        event->setAccepted(copy.isAccepted());
        return true;
    }
    case QEvent::Enter: {
        auto* e = static_cast<QEnterEvent*>(event);
        const QPointF global = e->globalPosition();
        QEnterEvent copy(target->mapFromGlobal(global), target->window()->mapFromGlobal(global), global);
        QCoreApplication::sendEvent(target, &copy);
        return true;
    }
    case QEvent::Leave: {
        QEvent copy(QEvent::Leave);
        QCoreApplication::sendEvent(target, &copy);
        return true;
    }
    default:
        return false;
    }
}

} // namespace wisp
