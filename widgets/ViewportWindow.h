#pragma once
// The native child window the viewport draws into, embedded with QWidget::createWindowContainer.
//
// Why a window of its own rather than a QOpenGLWidget: Qt draws a QOpenGLWidget into a texture and
// then composes the whole top-level window with OpenGL for every frame (docks, panels and all). On
// a software rasteriser (Mesa llvmpipe) composing the 1400x900 editor window cost about half as much
// as drawing the scene. A native child window is presented on its own (one blit and a swap of the
// view's pixels); the rest of the window is drawn by the raster engine, and only when it changes.
//
// It keeps no state of the view. Input that reaches it is sent on to `inputTarget` (the Viewport
// widget), in that widget's coordinates, so the widget's handlers and the event filters installed
// on it (the paint tool's) see the same events as if the widget had received them. Moves without a
// button go only where the target tracks the mouse, as for widgets.
//
// Thread: GUI.

#include <QPointer>
#include <QWidget>
#include <QWindow>

namespace wisp {

class ViewportWindow : public QWindow {
    Q_OBJECT
public:
    explicit ViewportWindow(QWidget* inputTarget);
    QWidget* inputTarget() const { return m_target.data(); }

signals:
    // Exposed (shown, uncovered, resized): a frame must be presented now.
    void exposed();
    // Its native surface is going away: make no context current on it any more.
    void surfaceAboutToBeDestroyed();

protected:
    bool event(QEvent* event) override;
    void exposeEvent(QExposeEvent* event) override;

private:
    bool forward(QEvent* event);

    QPointer<QWidget> m_target;
};

} // namespace wisp
