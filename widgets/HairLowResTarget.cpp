#include "widgets/HairLowResTarget.h"

#include <QOpenGLContext>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace wisp {

void bindLowResHair(GlFunctions* gl, QOpenGLShaderProgram& program, const LowResHairLayer& layer, int firstUnit)
{
    program.setUniformValue("u_hair", firstUnit);
    program.setUniformValue("u_hairDepth", firstUnit + 1);
    program.setUniformValue("u_frameDepth", firstUnit + 2);
    program.setUniformValue("u_hairRegion", layer.region.x, layer.region.y, layer.region.z, layer.region.w);
    program.setUniformValue(
        "u_framePixels", static_cast<float>(layer.framePixels.width()), static_cast<float>(layer.framePixels.height()));
    program.setUniformValue(
        "u_hairPixels", static_cast<float>(layer.pixels.width()), static_cast<float>(layer.pixels.height()));
    program.setUniformValue("u_p22", layer.projection[2][2]);
    program.setUniformValue("u_p32", layer.projection[3][2]);
    const GLuint textures[3] = { layer.colourTexture, layer.depthTexture, layer.frameDepthTexture };
    for (int i = 0; i < 3; ++i) {
        gl->glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + firstUnit + i));
        gl->glBindTexture(GL_TEXTURE_2D, textures[i]);
    }
    gl->glActiveTexture(GL_TEXTURE0);
}

void unbindLowResHair(GlFunctions* gl, int firstUnit)
{
    for (int i = 0; i < 3; ++i) {
        gl->glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + firstUnit + i));
        gl->glBindTexture(GL_TEXTURE_2D, 0);
    }
    gl->glActiveTexture(GL_TEXTURE0);
}

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

std::vector<QRect> HairLowResTarget::inkedSpans(
    const PixelRect& rect, std::span<const std::uint8_t> rgba, QSize framePixels)
{
    const int w = rect.width();
    const int h = rect.height();
    if (w == 0 || h == 0 || framePixels.isEmpty()
        || rgba.size() != 4 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h))
        return {};
    // Each texel row's first and last inked column (target texels), or none.
    std::vector<int> first(static_cast<std::size_t>(h), -1);
    std::vector<int> last(static_cast<std::size_t>(h), -1);
    for (int y = 0; y < h; ++y) {
        const std::uint8_t* row = rgba.data() + 4 * static_cast<std::size_t>(y) * static_cast<std::size_t>(w);
        const auto inked = [row](int x) {
            std::uint32_t texel;
            std::memcpy(&texel, row + 4 * x, 4);
            return texel != 0;
        };
        int x0 = 0;
        while (x0 < w && !inked(x0))
            ++x0;
        if (x0 == w)
            continue;
        int x1 = w - 1;
        while (!inked(x1))
            --x1;
        first[static_cast<std::size_t>(y)] = rect.x0 + x0;
        last[static_cast<std::size_t>(y)] = rect.x0 + x1;
    }
    // lowres_hair.glsl: frame pixel p reads texels floor(a) and floor(a) + 1, a = (p + 0.5) r - 0.5,
    // r = target / frame pixels (a little over 1/2 for an odd frame size). Texel t is read by the
    // pixels with a in [t - 1, t + 1); a pixel of margin each way covers rounding.
    const QSize target = sizeFor(framePixels);
    const double rx = static_cast<double>(target.width()) / framePixels.width();
    const double ry = static_cast<double>(target.height()) / framePixels.height();
    const auto texelOf = [](int pixel, double r) { return static_cast<int>(std::floor((pixel + 0.5) * r - 0.5)); };
    std::vector<QRect> spans;
    for (int band = 0; band < framePixels.height(); band += kSpanRows) {
        const int bandEnd = std::min(band + kSpanRows, framePixels.height());
        // The texel rows the band's pixels read, less a row of margin at each end.
        const int t0 = std::max(texelOf(band, ry) - 1, rect.y0);
        const int t1 = std::min(texelOf(bandEnd - 1, ry) + 2, rect.y1 - 1);
        int lo = std::numeric_limits<int>::max();
        int hi = -1;
        for (int t = t0; t <= t1; ++t) {
            const std::size_t row = static_cast<std::size_t>(t - rect.y0);
            if (first[row] < 0)
                continue;
            lo = std::min(lo, first[row]);
            hi = std::max(hi, last[row]);
        }
        if (hi < 0)
            continue;
        // Pixels with a in [lo - 1, hi + 1): p in [(lo - 0.5) / r - 0.5, (hi + 1.5) / r - 0.5).
        const int p0 = std::max(static_cast<int>(std::floor((lo - 0.5) / rx - 0.5)) - 1, 0);
        const int p1 = std::min(static_cast<int>(std::ceil((hi + 1.5) / rx - 0.5)) + 1, framePixels.width());
        if (p0 < p1)
            spans.emplace_back(p0, band, p1 - p0, bandEnd - band);
    }
    return spans;
}

LowResHairLayer HairLowResTarget::layer(
    QSize framePixels, GLuint frameDepthTexture, const glm::mat4& projection, const ClipRect& region) const
{
    return LowResHairLayer{ m_colour, m_depth, m_size, frameDepthTexture, framePixels, projection, region, {} };
}

void HairLowResTarget::composite(const LowResHairLayer& layer)
{
    if (!m_gl || !m_compositeProgram || !m_framebuffer || clipRectEmpty(layer.region))
        return;
    GlFunctions* gl = m_gl;
    gl->glViewport(0, 0, layer.framePixels.width(), layer.framePixels.height());
    // The frame's depth is read here while it is attached: nothing may write it.
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glEnable(GL_BLEND);
    gl->glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->glBindVertexArray(m_vao);
    m_compositeProgram->bind();
    const ClipRect& region = layer.region;
    m_compositeProgram->setUniformValue("u_rect", region.x, region.y, region.z, region.w);
    bindLowResHair(gl, *m_compositeProgram, layer, 0);
    gl->glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    unbindLowResHair(gl, 0);
    m_compositeProgram->release();
    gl->glBindVertexArray(0);
    gl->glDisable(GL_BLEND);
    gl->glDepthMask(GL_TRUE);
    checkGlErrors(gl, "HairLowResTarget::composite");
}

} // namespace wisp
