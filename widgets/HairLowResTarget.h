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
// (resources/shaders/lowres_depth.frag, lowres_hair.glsl). Laid over the frame by the pass that
// finishes it (FrameCompositor::draw with a LowResHairLayer, present_hair.frag), or by composite()
// where something is drawn over the hair afterwards (the brush rings).
//
// Thread: GUI, with the viewport's context current (every member function).

#include "widgets/GlSupport.h"
#include "widgets/HairSoftwareRaster.h"
#include "widgets/ScreenRect.h"

#include <glm/mat4x4.hpp>

#include <QOpenGLShaderProgram>
#include <QRect>
#include <QSize>
#include <QString>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace wisp {

// What a pass needs to lay the hair drawn this frame over the frame (lowres_hair.glsl's uniforms).
struct LowResHairLayer {
    GLuint colourTexture = 0; // the target's, GL_TEXTURE_2D
    GLuint depthTexture = 0;
    QSize pixels; // the target's
    GLuint frameDepthTexture = 0; // the frame's, GL_TEXTURE_2D: read, not written
    QSize framePixels;
    glm::mat4 projection{ 1.0f }; // the view's, to compare depths in metres
    ClipRect region = kWholeViewport; // where the hair can be (outside it the target is stale)
    // Where it is, when known (the CPU drew it: HairLowResTarget::inkedSpans): frame pixels, y up;
    // every frame pixel outside them has no hair. Unset: anywhere in `region`.
    std::optional<std::vector<QRect>> inkedSpans;
};

// Sets lowres_hair.glsl's uniforms on `program` (bound) and binds `layer`'s three textures to the
// units `firstUnit` .. `firstUnit` + 2; unbindLowResHair unbinds them and leaves unit 0 active.
void bindLowResHair(GlFunctions* gl, QOpenGLShaderProgram& program, const LowResHairLayer& layer, int firstUnit);
void unbindLowResHair(GlFunctions* gl, int firstUnit);

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
    // The hair drawn since begin(), to lay over the frame (`framePixels` big, whose depth is
    // `frameDepthTexture`) inside `region` (clip space: where the hair can be).
    LowResHairLayer layer(
        QSize framePixels, GLuint frameDepthTexture, const glm::mat4& projection, const ClipRect& region) const;
    // Lays `layer` over the bound framebuffer (the frame; its depth is read, not written),
    // premultiplied "over", inside its region (a full-screen pass costs a software rasteriser a
    // few milliseconds).
    // The software path (HairSoftwareRaster.h): the target's depth over `rect` (window depths, rows
    // bottom up) after begin(), and the hair's colour written straight into the target over `rect`
    // (premultiplied RGBA8, rows bottom up), in place of drawing it. The target stays bound.
    void readDepth(const PixelRect& rect, std::vector<float>& depth);
    void writeColour(const PixelRect& rect, std::span<const std::uint8_t> rgba);
    void composite(const LowResHairLayer& layer);
    // Where the hair in `rgba` (as writeColour takes it, over `rect` of a target sizeFor(framePixels)
    // big) reaches the frame through the composite's bilinear reads: for each band of kSpanRows frame
    // rows (from the bottom), one rectangle from the first to the last frame pixel that reads an
    // inked texel; bands with none are left out. Laying the hair costs a software rasteriser per
    // pixel it covers, and the hair fills a fraction of its box.
    static constexpr int kSpanRows = 16;
    static std::vector<QRect> inkedSpans(const PixelRect& rect, std::span<const std::uint8_t> rgba, QSize framePixels);
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
