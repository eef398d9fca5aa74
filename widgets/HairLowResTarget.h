#pragma once
// The hair drawn at half the frame's width and height while the camera or the hair moves, then laid
// over the full-resolution frame (issue 14's frame rates on a software rasteriser).
//
// Why: on Mesa's llvmpipe most of a paused orbit's hair pass is rasterising the strands (measured
// with the rasteriser discarding: 26 of 164-177 ms), and a thin line costs per 4x4 block it crosses,
// so half the length in pixels is about half that work. The look keeps its coverage and colour: the
// target starts transparent and the hair is blended into it as into the frame (premultiplied, the
// same "over"), each strand's analytic coverage computed for the target's pixels, so a strand half
// as wide in them is drawn half as opaque; the composite then lays it over the frame with bilinear
// weights, so its coverage summed across is the same. A still view draws the hair at full
// resolution (Viewport's refinement paint), as do images and grabs.
//
// Depth-aware: the target's depth is the farthest of each 2x2 block of the frame's (hair behind the
// head in all four pixels is rejected there); the hair tests it but does not write it (a texel is
// four pixels: a partly covering strand would hide its neighbours). The composite keeps, of the four
// texels around a frame pixel, only those whose block reaches no more than 1 % behind that pixel's
// backdrop, renormalised, so hair behind the head's silhouette does not bleed over its edge
// (resources/shaders/lowres_depth.frag, lowres_composite.frag).
//
// Thread: GUI, with the viewport's context current (every member function).

#include "widgets/GlSupport.h"
#include "widgets/HairSoftwareRaster.h"
#include "widgets/ScreenRect.h"

#include <glm/mat4x4.hpp>

#include <QOpenGLShaderProgram>
#include <QSize>
#include <QString>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace wisp {

class HairLowResTarget {
public:
    HairLowResTarget() = default;
    ~HairLowResTarget(); // GL objects must already be released
    HairLowResTarget(const HairLowResTarget&) = delete;
    HairLowResTarget& operator=(const HairLowResTarget&) = delete;

    // False (and why, in error()) when the shaders do not build; begin() then refuses.
    bool initialize(GlFunctions* gl);
    void release();
    QString error() const { return m_error; }

    // The target's size for a frame `framePixels` big: half of it, rounded up.
    static QSize sizeFor(QSize framePixels);
    // Binds the target (made or remade at sizeFor(framePixels)), its colour cleared transparent and
    // its depth the farthest of each 2x2 block of `frameDepthTexture` (GL_TEXTURE_2D, the frame's)
    // inside `region` (clip space; at least composite()'s region widened by two target texels),
    // with the viewport set to it. False (nothing bound) when it cannot be made.
    bool begin(QSize framePixels, GLuint frameDepthTexture, const ClipRect& region = kWholeViewport);
    // Lays the hair drawn since begin() over the bound framebuffer (the frame, `framePixels` big,
    // whose depth is `frameDepthTexture`; read, not written), premultiplied "over", inside `region`
    // (clip space: where the hair can be; a full-screen pass costs a software rasteriser a few
    // milliseconds). `projection`: the view's, to compare depths in metres.
    // The software path (HairSoftwareRaster.h): the target's depth over `rect` (window depths, rows
    // bottom up) after begin(), and the hair's colour written straight into the target over `rect`
    // (premultiplied RGBA8, rows bottom up), in place of drawing it. The target stays bound.
    void readDepth(const PixelRect& rect, std::vector<float>& depth);
    void writeColour(const PixelRect& rect, std::span<const std::uint8_t> rgba);
    void composite(QSize framePixels, GLuint frameDepthTexture, const glm::mat4& projection,
        const ClipRect& region = kWholeViewport);
    QSize size() const { return m_size; }

private:
    void freeTarget();

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_depthProgram;
    std::unique_ptr<QOpenGLShaderProgram> m_compositeProgram;
    GLuint m_vao = 0; // the passes read no attributes, but core profile needs one bound
    GLuint m_framebuffer = 0;
    GLuint m_colour = 0;
    GLuint m_depth = 0;
    QSize m_size;
    QString m_error;
};

} // namespace wisp
