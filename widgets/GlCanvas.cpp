#include "widgets/GlCanvas.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QWindow>

#include <algorithm>

namespace wisp {

GlCanvas::GlCanvas() = default;

GlCanvas::~GlCanvas()
{
    if (!m_context)
        return;
    // Normally its owner has released everything already (with its own GL objects).
    if (m_gl && m_frame.framebuffer && makeCurrent(nullptr))
        releaseFramebuffers();
    doneCurrent();
}

bool GlCanvas::create(const QSurfaceFormat& format)
{
    if (m_context)
        return true;
    auto context = std::make_unique<QOpenGLContext>();
    context->setFormat(format);
    if (!context->create())
        return false;
    m_context = std::move(context);
    return true;
}

bool GlCanvas::makeCurrent(QWindow* window)
{
    if (!m_context)
        return false;
    if (window && window->handle())
        return m_context->makeCurrent(window);
    if (!m_offscreen) {
        m_offscreen = std::make_unique<QOffscreenSurface>();
        m_offscreen->setFormat(m_context->format());
        m_offscreen->create();
    }
    return m_context->makeCurrent(m_offscreen.get());
}

void GlCanvas::doneCurrent()
{
    if (m_context)
        m_context->doneCurrent();
}

bool GlCanvas::prepare(GlFunctions* gl, QSize pixels, int samples, bool* remade)
{
    m_gl = gl;
    pixels = pixels.expandedTo(QSize(1, 1));
    if (remade)
        *remade = false;
    if (m_frame.framebuffer && pixels == m_size && samples == m_requestedSamples)
        return true;
    releaseFramebuffers();
    m_size = pixels;
    m_requestedSamples = samples;
    GLint maxColour = 0;
    GLint maxDepth = 0;
    gl->glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &maxColour);
    gl->glGetIntegerv(GL_MAX_DEPTH_TEXTURE_SAMPLES, &maxDepth);
    const int wanted = std::clamp(samples, 0, std::max(0, std::min<int>(maxColour, maxDepth)));
    bool made = makeTarget(m_frame, 0) && makeTarget(m_backdropCache, 0);
    // A driver that refuses multisampled depth textures: no MSAA.
    if (made && wanted > 0 && !makeTarget(m_backdrop, wanted))
        freeTarget(m_backdrop);
    if (!made) {
        releaseFramebuffers();
        return false;
    }
    m_samples = 0;
    if (m_backdrop.multisampled) {
        GLint actual = 0;
        gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, m_backdrop.colour);
        gl->glGetTexLevelParameteriv(GL_TEXTURE_2D_MULTISAMPLE, 0, GL_TEXTURE_SAMPLES, &actual);
        gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
        m_samples = std::max(1, static_cast<int>(actual));
    }
    if (remade)
        *remade = true;
    checkGlErrors(gl, "GlCanvas::prepare");
    return true;
}

bool GlCanvas::makeTarget(Target& target, int samples)
{
    GlFunctions* gl = m_gl;
    const int w = m_size.width();
    const int h = m_size.height();
    gl->glGenFramebuffers(1, &target.framebuffer);
    gl->glGenTextures(1, &target.colour);
    gl->glGenTextures(1, &target.depth);
    target.multisampled = samples > 0;
    const GLenum kind = target.multisampled ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    if (target.multisampled) {
        // Fixed sample locations: both attachments must agree, and the composite pass needs no more.
        gl->glBindTexture(kind, target.colour);
        gl->glTexImage2DMultisample(kind, samples, GL_RGBA8, w, h, GL_TRUE);
        gl->glBindTexture(kind, target.depth);
        gl->glTexImage2DMultisample(kind, samples, GL_DEPTH_COMPONENT24, w, h, GL_TRUE);
    } else {
        gl->glBindTexture(kind, target.colour);
        gl->glTexImage2D(kind, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl->glTexParameteri(kind, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(kind, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glBindTexture(kind, target.depth);
        gl->glTexImage2D(kind, 0, GL_DEPTH_COMPONENT24, w, h, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
        gl->glTexParameteri(kind, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(kind, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    gl->glBindTexture(kind, 0);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, kind, target.colour, 0);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, kind, target.depth, 0);
    const bool complete = gl->glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_context->defaultFramebufferObject());
    if (!complete)
        freeTarget(target);
    return complete;
}

void GlCanvas::makeColourTarget(Target& target)
{
    GlFunctions* gl = m_gl;
    gl->glGenFramebuffers(1, &target.framebuffer);
    gl->glGenTextures(1, &target.colour);
    gl->glBindTexture(GL_TEXTURE_2D, target.colour);
    gl->glTexImage2D(
        GL_TEXTURE_2D, 0, GL_RGBA8, m_size.width(), m_size.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.colour, 0);
    const bool complete = gl->glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_context->defaultFramebufferObject());
    if (!complete)
        freeTarget(target);
}

void GlCanvas::freeTarget(Target& target)
{
    if (!m_gl)
        return;
    if (target.framebuffer)
        m_gl->glDeleteFramebuffers(1, &target.framebuffer);
    const GLuint textures[2] = { target.colour, target.depth };
    m_gl->glDeleteTextures(2, textures); // zeros are ignored
    target = Target{};
}

void GlCanvas::releaseFramebuffers()
{
    freeTarget(m_frame);
    freeTarget(m_backdrop);
    freeTarget(m_backdropCache);
    freeTarget(m_grab);
    m_size = QSize();
    m_requestedSamples = -1;
    m_samples = 0;
}

void GlCanvas::bindFrame()
{
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, m_frame.framebuffer);
}

void GlCanvas::bindBackdrop()
{
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, m_backdrop.framebuffer ? m_backdrop.framebuffer : m_frame.framebuffer);
}

void GlCanvas::bindBackdropCache()
{
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, m_backdropCache.framebuffer);
}

void GlCanvas::copyBackdropCacheToFrame()
{
    // Same size and format, single-sampled: a plain copy (about a millisecond on a software
    // rasteriser for the editor's view, where drawing the backdrop takes ten).
    GlFunctions* gl = m_gl;
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, m_backdropCache.framebuffer);
    gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m_frame.framebuffer);
    const int w = m_size.width();
    const int h = m_size.height();
    gl->glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_frame.framebuffer);
}

void GlCanvas::bindWindow()
{
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, m_context->defaultFramebufferObject());
}

void GlCanvas::swap(QWindow* window)
{
    if (window && window->handle())
        m_context->swapBuffers(window);
}

void GlCanvas::bindGrab()
{
    if (!m_grab.framebuffer)
        makeColourTarget(m_grab);
    m_gl->glBindFramebuffer(GL_FRAMEBUFFER, m_grab.framebuffer);
}

QImage GlCanvas::readGrab(bool keepAlpha)
{
    if (!m_grab.framebuffer)
        return {};
    GlFunctions* gl = m_gl;
    QImage image(m_size, keepAlpha ? QImage::Format_RGBA8888_Premultiplied : QImage::Format_RGBX8888);
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_grab.framebuffer);
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glReadPixels(0, 0, image.width(), image.height(), GL_RGBA, GL_UNSIGNED_BYTE, image.bits());
    bindWindow();
    if (keepAlpha)
        return image.mirrored();
    // The composite pass writes opaque pixels; make sure of it, as the screen ignores alpha.
    for (int y = 0; y < image.height(); ++y) {
        uchar* row = image.scanLine(y);
        for (int x = 0; x < image.width(); ++x)
            row[4 * x + 3] = 255;
    }
    return image.mirrored();
}

} // namespace wisp
