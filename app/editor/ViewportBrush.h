#pragma once
// What every brush on the viewport shares (the growth brush, the salon brushes): an event filter
// that turns a left drag without Alt into a stroke (begin, continue, finish), keeps the brush
// ring under the mouse, hides it when the mouse leaves, and redraws it when a modifier key changes
// what the stroke would do. Alt + drag and the middle button are left to the viewport's camera.
//
// Thread: GUI.

#include <QObject>
#include <QPointF>

class QKeyEvent;

namespace wisp {

class Viewport;

class ViewportBrush : public QObject {
    Q_OBJECT
public:
    bool isStroking() const { return m_stroking; }

protected:
    ViewportBrush(Viewport* viewport, QObject* parent);

    Viewport* viewport() const { return m_viewport; }
    // Where the mouse was last seen over the viewport; false before it was.
    bool hasCursor() const { return m_lastCursor.x() >= 0.0; }
    QPointF lastCursor() const { return m_lastCursor; }
    // A stroke ends without the mouse (the tool put down, the head replaced).
    void stopStroking() { m_stroking = false; }

    // Whether the brush takes the viewport's events now. Not pure: the viewport sends events while
    // this base is being built and taken down, when the derived tool does not exist.
    virtual bool brushEnabled() const { return false; }
    // A left press: true if a stroke began (false lets the click through).
    virtual bool beginStroke(QPointF position, Qt::KeyboardModifiers modifiers) = 0;
    virtual void continueStroke(QPointF position, Qt::KeyboardModifiers modifiers) = 0;
    // The button released; isStroking() is already false.
    virtual void finishStroke(QPointF position, Qt::KeyboardModifiers modifiers) = 0;
    // Puts the brush ring where the mouse is (or hides it); `position` is then lastCursor().
    virtual void showCursor(QPointF position, Qt::KeyboardModifiers modifiers) = 0;
    // A key the brush uses ([ and ] resize); true when taken.
    virtual bool keyPressed(const QKeyEvent* event) = 0;

private:
    bool eventFilter(QObject* watched, QEvent* event) final;
    void moveCursor(QPointF position, Qt::KeyboardModifiers modifiers);

    Viewport* m_viewport;
    bool m_stroking = false;
    QPointF m_lastCursor{ -1.0, -1.0 };
};

} // namespace wisp
