// Viewport's frames: when one is drawn, the context and framebuffers it is drawn into, and reading
// it back (grabFramebuffer, renderImage).
#include "widgets/Viewport.h"

#include "widgets/ViewportSupport.h"
#include "widgets/ViewportWindow.h"

#include <QPaintEvent>
#include <QResizeEvent>

namespace wisp {

bool Viewport::event(QEvent* event)
{
    // The child window shows its own cursor: give it ours (the paint tool's cross).
    if (event->type() == QEvent::CursorChange && m_window)
        m_window->setCursor(cursor());
    return QWidget::event(event);
}

void Viewport::paintEvent(QPaintEvent*)
{
    if (m_glFailed) {
        paintUnavailable();
        return;
    }
    presentFrame();
}

void Viewport::resizeEvent(QResizeEvent* event)
{
    QWidget::resizeEvent(event);
    // Until the artist takes the camera, keep the head framed as the window takes its size.
    if (!m_cameraTouched)
        m_camera.reset(m_headBounds, aspect());
    scheduleFrame();
}

void Viewport::scheduleFrame()
{
    // A zero timer rather than QWindow::requestUpdate, which waits 5 ms on X11 before every frame.
    if (!m_glFailed && !m_frameTimer.isActive())
        m_frameTimer.start();
}

void Viewport::presentFrame()
{
    m_frameTimer.stop();
    // Hidden or covered: the window's next expose draws the frame.
    if (m_glFailed || !m_window->isExposed())
        return;
    if (!drawFrame())
        return;
    m_canvas.bindWindow();
    finishFrame(FrameCompositor::Finish::Screen);
    m_passTimes.presentMs += m_passClock.lap();
    m_canvas.swap(m_window);
}

QImage Viewport::grabFramebuffer()
{
    m_grabbing = true;
    const bool drawn = drawFrame();
    m_grabbing = false;
    if (!drawn)
        return {};
    m_canvas.bindGrab();
    finishFrame(FrameCompositor::Finish::Screen);
    QImage image = m_canvas.readGrab();
    image.setDevicePixelRatio(frameRatio());
    return image;
}

QImage Viewport::renderImage(QSize pixels, const ImageOptions& options)
{
    if (pixels.isEmpty() || pixels.width() > kMaxImageSide || pixels.height() > kMaxImageSide)
        return {};
    ImageRender render{ pixels, m_camera, options.transparentBackground, options.previewFraction,
        options.hairAtHalfResolution, options.backdropSingleSampled };
    const float imageAspect = static_cast<float>(pixels.width()) / static_cast<float>(pixels.height());
    if (options.frameBounds && finiteBounds(*options.frameBounds))
        render.camera.reset(*options.frameBounds, imageAspect);
    else if (!m_cameraTouched)
        render.camera.reset(m_headBounds, imageAspect);
    render.camera.setOrientation(render.camera.yaw() + options.turnRadians, render.camera.pitch());
    m_image = render;
    QImage image;
    if (drawFrame()) {
        m_canvas.bindGrab();
        finishFrame(render.transparent ? FrameCompositor::Finish::ImageWithAlpha : FrameCompositor::Finish::Image);
        image = m_canvas.readGrab(render.transparent);
    }
    m_image.reset();
    scheduleFrame(); // the view's own framebuffers are made again at its size
    return image;
}

QSize Viewport::framePixels() const
{
    if (m_image)
        return m_image->pixels;
    // The window's size once it has one (the frame is copied into it unscaled), else this widget's.
    const QSize logical = m_window->handle() && !m_window->size().isEmpty() ? m_window->size() : size();
    return (QSizeF(logical) * frameRatio()).toSize().expandedTo(QSize(1, 1));
}

double Viewport::frameRatio() const
{
    return m_window->handle() ? m_window->devicePixelRatio() : devicePixelRatioF();
}

bool Viewport::makeCurrent()
{
    return m_canvas.makeCurrent(m_window);
}

bool Viewport::drawFrame()
{
    if (m_glFailed)
        return false;
    if (!m_canvas.context()) {
        if (!m_canvas.create(viewportFormat())) {
            glUnavailable(tr("The 3D view needs OpenGL 3.3 core; this system has no OpenGL."));
            return false;
        }
    }
    if (!makeCurrent()) {
        qWarning("Viewport: cannot make the OpenGL context current");
        return false;
    }
    if (!m_gl) {
        initializeGL();
        if (!m_gl) {
            glUnavailable(m_glStatus);
            return false;
        }
    }
    bool remade = false;
    if (!m_canvas.prepare(m_gl, framePixels(), m_requestedSamples, &remade)) {
        qWarning("Viewport: cannot make a %dx%d framebuffer", framePixels().width(), framePixels().height());
        return false;
    }
    paintGL(remade);
    return true;
}

void Viewport::glUnavailable(const QString& why)
{
    // Drawn by this widget (paintUnavailable), where the child window was.
    m_glFailed = true;
    m_glStatus = why;
    m_frameTimer.stop();
    m_container->hide();
    update();
}

} // namespace wisp
