#include "widgets/HairLowResTarget.h"

#include <QOpenGLContext>

namespace wisp {

HairLowResTarget::~HairLowResTarget() = default;

bool HairLowResTarget::initialize(GlFunctions* gl)
{
    m_gl = gl;
    m_depthProgram = loadShaderProgram(QStringLiteral("composite"), QStringLiteral("lowres_depth"), &m_error);
    m_compositeProgram = loadShaderProgram(QStringLiteral("composite"), QStringLiteral("lowres_composite"), &m_error);
    if (!m_depthProgram || !m_compositeProgram) {
        m_depthProgram.reset();
        m_compositeProgram.reset();
        return false;
    }
    m_depthProgram->bind();
    m_depthProgram->setUniformValue("u_frameDepth", 0);
    m_depthProgram->release();
    m_compositeProgram->bind();
    m_compositeProgram->setUniformValue("u_hair", 0);
    m_compositeProgram->setUniformValue("u_hairDepth", 1);
    m_compositeProgram->setUniformValue("u_frameDepth", 2);
    m_compositeProgram->release();
    gl->glGenVertexArrays(1, &m_vao);
    m_size = QSize();
    checkGlErrors(gl, "HairLowResTarget::initialize");
    return true;
}

void HairLowResTarget::release()
{
    if (!m_gl)
        return;
    freeTarget();
    m_gl->glDeleteVertexArrays(1, &m_vao);
    m_vao = 0;
    m_depthProgram.reset();
    m_compositeProgram.reset();
    m_gl = nullptr;
}

void HairLowResTarget::freeTarget()
{
    if (m_framebuffer)
        m_gl->glDeleteFramebuffers(1, &m_framebuffer);
    const GLuint textures[2] = { m_colour, m_depth };
    m_gl->glDeleteTextures(2, textures); // zeros are ignored
    m_framebuffer = m_colour = m_depth = 0;
    m_size = QSize();
}

QSize HairLowResTarget::sizeFor(QSize framePixels)
{
    return QSize((framePixels.width() + 1) / 2, (framePixels.height() + 1) / 2).expandedTo(QSize(1, 1));
}

bool HairLowResTarget::begin(QSize framePixels, GLuint frameDepthTexture, const ClipRect& region)
{
    if (!m_gl || !m_depthProgram || framePixels.isEmpty())
        return false;
    GlFunctions* gl = m_gl;
    const QSize wanted = sizeFor(framePixels);
    if (wanted != m_size || !m_framebuffer) {
        freeTarget();
        gl->glGenFramebuffers(1, &m_framebuffer);
        gl->glGenTextures(1, &m_colour);
        gl->glGenTextures(1, &m_depth);
        gl->glBindTexture(GL_TEXTURE_2D, m_colour);
        gl->glTexImage2D(
            GL_TEXTURE_2D, 0, GL_RGBA8, wanted.width(), wanted.height(), 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glBindTexture(GL_TEXTURE_2D, m_depth);
        gl->glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, wanted.width(), wanted.height(), 0, GL_DEPTH_COMPONENT,
            GL_UNSIGNED_INT, nullptr);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl->glBindTexture(GL_TEXTURE_2D, 0);
        gl->glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, m_colour, 0);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, m_depth, 0);
        if (gl->glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            freeTarget();
            return false;
        }
        m_size = wanted;
    }
    gl->glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer);
    gl->glViewport(0, 0, m_size.width(), m_size.height());
    // One pass writes both: transparent colour, the block's farthest depth.
    gl->glDisable(GL_BLEND);
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glEnable(GL_DEPTH_TEST); // depth is written only with the test on
    gl->glDepthFunc(GL_ALWAYS);
    gl->glDepthMask(GL_TRUE);
    gl->glBindVertexArray(m_vao);
    m_depthProgram->bind();
    // An ivec2: glUniform2i (QOpenGLShaderProgram's two-number setter is glUniform2f, which GL
    // refuses for an integer uniform, leaving it 0: the depth fetch then clamped to texel -1).
    gl->glUniform2i(m_depthProgram->uniformLocation("u_framePixels"), framePixels.width(), framePixels.height());
    // Only the region: outside it the target keeps old texels that nothing reads (composite()
    // covers less than this, and its bilinear reads reach one texel beyond what it covers).
    m_depthProgram->setUniformValue("u_rect", region.x, region.y, region.z, region.w);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, frameDepthTexture);
    gl->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    m_depthProgram->release();
    gl->glBindVertexArray(0);
    gl->glDepthFunc(GL_LESS);
    checkGlErrors(gl, "HairLowResTarget::begin");
    return true;
}

void HairLowResTarget::readDepth(const PixelRect& rect, std::vector<float>& depth)
{
    depth.resize(static_cast<std::size_t>(rect.width()) * static_cast<std::size_t>(rect.height()));
    if (!m_gl || !m_framebuffer || depth.empty())
        return;
    GlFunctions* gl = m_gl;
    gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, m_framebuffer);
    gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    gl->glReadPixels(rect.x0, rect.y0, rect.width(), rect.height(), GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    checkGlErrors(gl, "HairLowResTarget::readDepth");
}

void HairLowResTarget::writeColour(const PixelRect& rect, std::span<const std::uint8_t> rgba)
{
    if (!m_gl || !m_colour || rect.width() == 0 || rect.height() == 0
        || rgba.size() != 4 * static_cast<std::size_t>(rect.width()) * static_cast<std::size_t>(rect.height()))
        return;
    GlFunctions* gl = m_gl;
    gl->glBindTexture(GL_TEXTURE_2D, m_colour);
    gl->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    gl->glTexSubImage2D(
        GL_TEXTURE_2D, 0, rect.x0, rect.y0, rect.width(), rect.height(), GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    checkGlErrors(gl, "HairLowResTarget::writeColour");
}

void HairLowResTarget::composite(
    QSize framePixels, GLuint frameDepthTexture, const glm::mat4& projection, const ClipRect& region)
{
    if (!m_gl || !m_compositeProgram || !m_framebuffer || clipRectEmpty(region))
        return;
    GlFunctions* gl = m_gl;
    gl->glViewport(0, 0, framePixels.width(), framePixels.height());
    // The frame's depth is read here while it is attached: nothing may write it.
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glEnable(GL_BLEND);
    gl->glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->glBindVertexArray(m_vao);
    m_compositeProgram->bind();
    m_compositeProgram->setUniformValue("u_rect", region.x, region.y, region.z, region.w);
    m_compositeProgram->setUniformValue(
        "u_framePixels", static_cast<float>(framePixels.width()), static_cast<float>(framePixels.height()));
    m_compositeProgram->setUniformValue(
        "u_hairPixels", static_cast<float>(m_size.width()), static_cast<float>(m_size.height()));
    m_compositeProgram->setUniformValue("u_p22", projection[2][2]);
    m_compositeProgram->setUniformValue("u_p32", projection[3][2]);
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, frameDepthTexture);
    gl->glActiveTexture(GL_TEXTURE1);
    gl->glBindTexture(GL_TEXTURE_2D, m_depth);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_2D, m_colour);
    gl->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE1);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE2);
    gl->glBindTexture(GL_TEXTURE_2D, 0);
    gl->glActiveTexture(GL_TEXTURE0);
    m_compositeProgram->release();
    gl->glBindVertexArray(0);
    gl->glDisable(GL_BLEND);
    gl->glDepthMask(GL_TRUE);
    checkGlErrors(gl, "HairLowResTarget::composite");
}

} // namespace wisp
