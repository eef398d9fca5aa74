#pragma once
// The OpenGL context the viewport draws with, and the framebuffers it draws into:
//   backdrop        multisampled colour and depth: what changes only with the camera (background,
//                   head, grid), drawn when that changes;
//   backdrop cache  single-sampled colour and depth: the backdrop resolved (FrameCompositor::
//                   resolveWithDepth), copied into the frame at the start of every frame it holds;
//   frame           single-sampled colour and depth: each frame's scene. The hair is drawn here,
//                   single-sampled: it carries its own analytic coverage (hair.vert/frag), and 4x
//                   MSAA about doubled its cost on a software rasteriser (issue 14);
//   grab            single-sampled colour, for reading a finished frame back (grabFramebuffer, tests).
// Without multisampling (samples 0) there is no separate backdrop: it is drawn straight into the
// cache or the frame. A finished frame is copied into the window's back buffer (or the grab
// framebuffer) by FrameCompositor, then swapped. Framebuffers of our own keep anti-aliasing
// independent of the visuals the window system offers, and let frames be drawn and read before the
// window is shown.
//
// Thread: GUI. Every function but create() and makeCurrent() needs the context current.

#include "widgets/GlSupport.h"

#include <QImage>
#include <QSize>
#include <QSurfaceFormat>

#include <memory>

class QOffscreenSurface;
class QOpenGLContext;
class QWindow;

namespace wisp {

class GlCanvas {
public:
    GlCanvas();
    ~GlCanvas(); // frees the framebuffers with the context current, then the context
    GlCanvas(const GlCanvas&) = delete;
    GlCanvas& operator=(const GlCanvas&) = delete;

    // Makes the context, once: false when the system cannot make one of `format`.
    bool create(const QSurfaceFormat& format);
    QOpenGLContext* context() const { return m_context.get(); }
    // Current on `window` while it has a native surface, else on a small offscreen surface.
    bool makeCurrent(QWindow* window);
    void doneCurrent();

    // Framebuffers `pixels` big with `samples` samples per pixel (0: no multisampling), made anew
    // when either changes (the driver may give another count). False when they cannot be made.
    // True `remade`: the backdrop has lost its contents.
    bool prepare(GlFunctions* gl, QSize pixels, int samples, bool* remade = nullptr);
    QSize size() const { return m_size; }
    int samples() const { return m_samples; } // the backdrop's, as made; 0: not multisampled
    // GL_TEXTURE_2D: the frame is single-sampled.
    GLuint frameColourTexture() const { return m_frame.colour; }
    GLuint frameDepthTexture() const { return m_frame.depth; } // GL_TEXTURE_2D, DEPTH_COMPONENT24
    // GL_TEXTURE_2D_MULTISAMPLE, while samples() > 0.
    GLuint backdropColourTexture() const { return m_backdrop.colour; }
    GLuint backdropDepthTexture() const { return m_backdrop.depth; }

    void bindFrame();
    void bindBackdrop(); // the multisampled one; while samples() is 0, the frame
    void bindBackdropCache();
    void copyBackdropCacheToFrame(); // colour and depth; leaves the frame bound
    // The window's back buffer, the target of the composite pass.
    void bindWindow();
    void swap(QWindow* window);
    // The grab framebuffer, as a target; readGrab() then returns its pixels, top row first, opaque
    // (or with their alpha, premultiplied, when `keepAlpha`).
    void bindGrab();
    QImage readGrab(bool keepAlpha = false);
    void releaseFramebuffers();

private:
    struct Target {
        GLuint framebuffer = 0;
        GLuint colour = 0; // texture
        GLuint depth = 0; // texture
        bool multisampled = false;
    };
    bool makeTarget(Target& target, int samples);
    void makeColourTarget(Target& target); // single-sampled colour, no depth
    void freeTarget(Target& target);

    std::unique_ptr<QOpenGLContext> m_context;
    std::unique_ptr<QOffscreenSurface> m_offscreen;
    GlFunctions* m_gl = nullptr;
    Target m_frame;
    Target m_backdrop; // made only with samples
    Target m_backdropCache;
    Target m_grab; // single-sampled colour, made when first needed
    QSize m_size;
    int m_requestedSamples = -1;
    int m_samples = 0;
};

} // namespace wisp
