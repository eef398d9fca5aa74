#pragma once
// Finishes a frame in the bound target (the window's back buffer, or GlCanvas's grab framebuffer):
// resolves the multisampled scene into it, then draws the overlay images over it (the heads-up
// line and the axis gizmo, painted by ViewportOverlay with QPainter's raster engine).
//
// Why not QPainter's OpenGL engine over the frame, as before: it tessellated and drew the text and
// the gizmo anew every frame (and left GL_MULTISAMPLE off behind it, so every frame after the
// first was drawn without anti-aliasing), and glBlitFramebuffer's resolve on a software rasteriser
// costs several times this one pass. The overlay images are uploaded only when they change.
//
// Thread: GUI, with the viewport's context current (every member function).

#include "widgets/GlSupport.h"
#include "widgets/HairLowResTarget.h"

#include <glm/vec3.hpp>

#include <QImage>
#include <QOpenGLShaderProgram>
#include <QPoint>
#include <QRect>
#include <QSize>
#include <QString>

#include <array>
#include <memory>
#include <optional>
#include <span>

namespace wisp {

class FrameCompositor {
public:
    enum class Slot { Hud, Gizmo };

    FrameCompositor() = default;
    ~FrameCompositor(); // GL objects must already be released
    FrameCompositor(const FrameCompositor&) = delete;
    FrameCompositor& operator=(const FrameCompositor&) = delete;

    // False (and why, in error()) when the shaders do not build; draw() then does nothing.
    bool initialize(GlFunctions* gl);
    void release();
    QString error() const { return m_error; }

    // What `slot` shows from now on: `image` (premultiplied alpha, device pixels) with its top-left
    // corner at `topLeftPixels` from the target's top-left. A null image hides the slot.
    void setOverlay(Slot slot, const QImage& image, QPoint topLeftPixels);
    // Resolves `frameTexture` (GL_TEXTURE_2D_MULTISAMPLE with `samples` samples, or GL_TEXTURE_2D
    // when `samples` is 0; `pixels` big) into the bound framebuffer, which must be as big, then
    // draws the overlays over it. A rendered image (Viewport::renderImage) has no overlays and may
    // keep the frame's alpha (premultiplied) for a transparent background. With `hair` (a
    // single-sampled frame only), the half-resolution hair is laid over the frame in the same pass
    // (present_hair.frag), in place of a blended pass of its own into the frame.
    enum class Finish { Screen, Image, ImageWithAlpha };
    void draw(GLuint frameTexture, int samples, QSize pixels, Finish finish = Finish::Screen,
        const LowResHairLayer* hair = nullptr);
    // Resolves a multisampled colour and depth pair (GlCanvas's backdrop, `samples` > 0) into the
    // bound single-sampled framebuffer, colour and depth (resources/shaders/resolve.frag). With a
    // gradient, the colour (premultiplied, transparent where nothing was drawn) is laid over it.
    struct Gradient {
        glm::vec3 topSrgb;
        glm::vec3 bottomSrgb;
    };
    void resolveWithDepth(GLuint colourTexture, GLuint depthTexture, int samples, QSize pixels,
        const std::optional<Gradient>& under = std::nullopt);

private:
    // A rectangle of the target (pixels, origin at the bottom left as GL counts them).
    void drawRect(QRect rect, QSize pixels, QOpenGLShaderProgram& program);
    // composite.frag's copy of the frame (multisampled with `samples` > 0) over `rects` of the target.
    void copyFrame(GLuint frameTexture, int samples, QSize pixels, int keepAlpha, std::span<const QRect> rects);

    struct Overlay {
        GLuint texture = 0;
        QSize size; // device pixels; empty: hidden
        QPoint topLeft;
    };

    GlFunctions* m_gl = nullptr;
    std::unique_ptr<QOpenGLShaderProgram> m_composite;
    std::unique_ptr<QOpenGLShaderProgram> m_compositeWithHair; // present_hair.frag
    std::unique_ptr<QOpenGLShaderProgram> m_overlay;
    std::unique_ptr<QOpenGLShaderProgram> m_resolve;
    GLuint m_vao = 0; // none of the passes reads vertex attributes, but core profile needs one bound
    std::array<Overlay, 2> m_overlays{};
    QString m_error;
};

} // namespace wisp
