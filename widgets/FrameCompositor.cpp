#include "widgets/FrameCompositor.h"

#include <algorithm>
#include <span>
#include <vector>

namespace wisp {

FrameCompositor::~FrameCompositor() = default;

bool FrameCompositor::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_composite = loadShaderProgram(QStringLiteral("composite"), &m_error);
    m_overlay = m_composite ? loadShaderProgram(QStringLiteral("overlay"), &m_error) : nullptr;
    m_resolve
        = m_overlay ? loadShaderProgram(QStringLiteral("composite"), QStringLiteral("resolve"), &m_error) : nullptr;
    m_compositeWithHair = m_resolve
        ? loadShaderProgram(QStringLiteral("composite"), QStringLiteral("present_hair"), &m_error)
        : nullptr;
    if (!m_composite || !m_overlay || !m_resolve || !m_compositeWithHair) {
        m_composite.reset();
        return false;
    }
    gl->glGenVertexArrays(1, &m_vao);
    m_composite->bind();
    m_composite->setUniformValue("u_frame", 0);
    m_composite->setUniformValue("u_frameSingle", 1);
    m_overlay->bind();
    m_overlay->setUniformValue("u_image", 0);
    m_resolve->bind();
    m_resolve->setUniformValue("u_colour", 0);
    m_resolve->setUniformValue("u_depth", 1);
    m_compositeWithHair->bind();
    m_compositeWithHair->setUniformValue("u_frameSingle", 0);
    m_compositeWithHair->release();
    for (Overlay& overlay : m_overlays) {
        gl->glGenTextures(1, &overlay.texture);
        gl->glBindTexture(GL_TEXTURE_2D, overlay.texture);
        // Drawn pixel for pixel: nearest keeps the text as QPainter antialiased it.
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        overlay.size = QSize();
    }
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    checkGlErrors(gl, "FrameCompositor::initialize");
    return true;
}

void FrameCompositor::release()
{
    if (!m_gl)
        return;
    for (Overlay& overlay : m_overlays) {
        m_gl->glDeleteTextures(1, &overlay.texture);
        overlay = Overlay{};
    }
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_vao = 0;
    m_composite.reset();
    m_compositeWithHair.reset();
    m_overlay.reset();
    m_resolve.reset();
    m_gl = nullptr;
}

void FrameCompositor::setOverlay(Slot slot, const QImage& image, QPoint topLeftPixels)
{
    if (!m_composite)
        return;
    Overlay& overlay = m_overlays[static_cast<std::size_t>(slot)];
    overlay.topLeft = topLeftPixels;
    if (image.isNull()) {
        overlay.size = QSize();
        return;
    }
    const QImage pixels = image.convertToFormat(QImage::Format_RGBA8888_Premultiplied);
    GlFunctions* gl = m_gl;
    gl->glBindTexture(GL_TEXTURE_2D, overlay.texture);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4); // RGBA rows are whole 32-bit words
    if (pixels.size() == overlay.size) {
        gl->glTexSubImage2D(
            GL_TEXTURE_2D, 0, 0, 0, pixels.width(), pixels.height(), GL_RGBA, GL_UNSIGNED_BYTE, pixels.constBits());
    } else {
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, pixels.width(), pixels.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
            pixels.constBits());
        overlay.size = pixels.size();
    }
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    checkGlErrors(gl, "FrameCompositor::setOverlay");
}

void FrameCompositor::drawRect(QRect rect, QSize pixels, QOpenGLShaderProgram& program)
{
    // Not clipped here (GL clips): an overlay's image keeps its scale where it overhangs.
    if ((rect & QRect(QPoint(0, 0), pixels)).isEmpty())
        return;
    const float w = static_cast<float>(pixels.width());
    const float h = static_cast<float>(pixels.height());
    const glm::vec4 clip{ 2.0f * static_cast<float>(rect.x()) / w - 1.0f,
        2.0f * static_cast<float>(rect.y()) / h - 1.0f, 2.0f * static_cast<float>(rect.x() + rect.width()) / w - 1.0f,
        2.0f * static_cast<float>(rect.y() + rect.height()) / h - 1.0f };
    setUniform(program, "u_rect", clip);
    m_gl->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

void FrameCompositor::copyFrame(
    GLuint frameTexture, int samples, QSize pixels, int keepAlpha, std::span<const QRect> rects)
{
    GlFunctions* gl = m_gl;
    m_composite->bind();
    setUniform(*m_composite, "u_samples", std::max(samples, 0));
    setUniform(*m_composite, "u_keepAlpha", keepAlpha);
    const GLenum kind = samples > 0 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    gl->glActiveTexture(samples > 0 ? GL_TEXTURE0 : GL_TEXTURE1);
    gl->glBindTexture(kind, frameTexture);
    for (const QRect& rect : rects)
        drawRect(rect, pixels, *m_composite);
    gl->glBindTexture(kind, 0);
    gl->glActiveTexture(GL_TEXTURE0);
}

void FrameCompositor::draw(GLuint frameTexture, int samples, QSize pixels, Finish finish, const LowResHairLayer* hair)
{
    if (!m_composite || pixels.isEmpty())
        return;
    GlFunctions* gl = m_gl;
    gl->glViewport(0, 0, pixels.width(), pixels.height());
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glBindVertexArray(m_vao);

    // The frame, resolved: every pixel of the target.
    const int keepAlpha = finish == Finish::ImageWithAlpha ? 1 : 0;
    if (hair && samples <= 0) {
        // Where the hair is known, the frame is copied around it and laid with it only over it (a
        // software rasteriser pays per pixel for the hair's ten texel reads, and the hair fills a
        // fraction of the frame); every rectangle is drawn once.
        const QRect whole(QPoint(0, 0), pixels);
        std::vector<QRect> plain;
        std::vector<QRect> withHair;
        if (hair->inkedSpans) {
            int below = 0; // rows under this one are covered
            for (const QRect& span : *hair->inkedSpans) {
                const QRect band = (span & whole);
                if (band.isEmpty() || band.y() < below)
                    continue; // outside; or overlapping (inkedSpans gives bands apart, bottom up)
                if (band.y() > below)
                    plain.emplace_back(0, below, pixels.width(), band.y() - below);
                plain.emplace_back(0, band.y(), band.x(), band.height());
                plain.emplace_back(
                    band.x() + band.width(), band.y(), pixels.width() - band.x() - band.width(), band.height());
                withHair.push_back(band);
                below = band.y() + band.height();
            }
            if (below < pixels.height())
                plain.emplace_back(0, below, pixels.width(), pixels.height() - below);
        } else {
            withHair.push_back(whole);
        }
        // The frame at unit 0, the hair's three textures at 1..3.
        m_compositeWithHair->bind();
        setUniform(*m_compositeWithHair, "u_keepAlpha", keepAlpha);
        bindLowResHair(gl, *m_compositeWithHair, *hair, 1);
        gl->glBindTexture(GL_TEXTURE_2D, frameTexture);
        for (const QRect& rect : withHair)
            drawRect(rect, pixels, *m_compositeWithHair);
        gl->glBindTexture(GL_TEXTURE_2D, 0);
        unbindLowResHair(gl, 1);
        copyFrame(frameTexture, 0, pixels, keepAlpha, plain);
    } else {
        const QRect whole(QPoint(0, 0), pixels);
        copyFrame(frameTexture, samples, pixels, keepAlpha, { &whole, 1 });
    }

    if (finish != Finish::Screen) {
        gl->glBindVertexArray(0);
        checkGlErrors(gl, "FrameCompositor::draw");
        return;
    }
    // The overlays over it, placed from the top left as QPainter painted them.
    gl->glEnable(GL_BLEND);
    gl->glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA); // premultiplied
    m_overlay->bind();
    for (const Overlay& overlay : m_overlays) {
        if (overlay.size.isEmpty())
            continue;
        const QRect rect(
            QPoint(overlay.topLeft.x(), pixels.height() - overlay.topLeft.y() - overlay.size.height()), overlay.size);
        gl->glBindTexture(GL_TEXTURE_2D, overlay.texture);
        drawRect(rect, pixels, *m_overlay);
    }
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    m_overlay->release();
    gl->glDisable(GL_BLEND);
    gl->glBindVertexArray(0);
    checkGlErrors(gl, "FrameCompositor::draw");
}

void FrameCompositor::resolveWithDepth(
    GLuint colourTexture, GLuint depthTexture, int samples, QSize pixels, const std::optional<Gradient>& under)
{
    if (!m_composite || pixels.isEmpty() || samples <= 0)
        return;
    GlFunctions* gl = m_gl;
    gl->glViewport(0, 0, pixels.width(), pixels.height());
    gl->glEnable(GL_DEPTH_TEST); // depth is written only with the test on
    gl->glDepthFunc(GL_ALWAYS);
    gl->glDepthMask(GL_TRUE);
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glBindVertexArray(m_vao);
    m_resolve->bind();
    setUniform(*m_resolve, "u_samples", samples);
    setUniform(*m_resolve, "u_gradient", under ? 1.0f : 0.0f);
    if (under) {
        setUniform(*m_resolve, "u_top", under->topSrgb);
        setUniform(*m_resolve, "u_bottom", under->bottomSrgb);
        setUniform(*m_resolve, "u_heightPixels", static_cast<float>(pixels.height()));
    }
    gl->glActiveTexture(GL_TEXTURE1);
    gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, depthTexture);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, colourTexture);
    drawRect(QRect(QPoint(0, 0), pixels), pixels, *m_resolve);
    gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    gl->glActiveTexture(GL_TEXTURE1);
    gl->glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    gl->glActiveTexture(GL_TEXTURE0);
    m_resolve->release();
    gl->glBindVertexArray(0);
    gl->glDepthFunc(GL_LESS);
    checkGlErrors(gl, "FrameCompositor::resolveWithDepth");
}

} // namespace wisp
