#pragma once
// The editor's 3D viewport: the head, the newest simulation frame's hair, a ground grid, the wind
// arrow, an axis gizmo and a heads-up line, under an orbit camera driven as in DCC tools:
//   Alt + left drag, or middle drag     orbit
//   Shift + middle drag (or Alt+middle)  pan
//   wheel, Ctrl + middle drag, Alt + right drag   zoom toward the pivot
//   F                                    frame the head
// Left clicks without Alt are left to the editor's tools (the events are ignored here); a paint
// tool installs an event filter, picks with rayAt() and shows its brush with setBrushCursor().
// The head can be tinted by painted growth weights (setGrowthOverlay).
//
// It draws whatever FramePtr it was given last and never touches simulation state: frames are
// immutable and shared, so drawing holds no lock.
//
// OpenGL 3.3 core with 4x MSAA, asked of this widget only (the application's default format is
// left alone). Without such a context the viewport paints an explanation instead of crashing.
//
// It draws into a native child window (ViewportWindow, in a window container that fills this
// widget), not as a QOpenGLWidget: Qt composes a QOpenGLWidget's window with OpenGL for every frame,
// which on a software rasteriser cost as much as a third of each frame in the editor's window. The
// API is a widget's all the same: input reaching the child window is sent on to this widget (its
// event filters see it), update() and repaint() draw a frame, grabFramebuffer() reads one.
//
// Thread: GUI, every member function.

#include "sim/geometry/TriangleMesh.h"
#include "sim/solver/Frame.h"
#include "sim/solver/Solver.h"
#include "sim/util/ThreadPool.h"
#include "widgets/BackgroundRenderer.h"
#include "widgets/FrameCompositor.h"
#include "widgets/GlCanvas.h"
#include "widgets/GlSupport.h"
#include "widgets/GuideRenderer.h"
#include "widgets/HairChildren.h"
#include "widgets/HairDetail.h"
#include "widgets/HairLowResTarget.h"
#include "widgets/HairRenderer.h"
#include "widgets/HairShadowMap.h"
#include "widgets/HeadRenderer.h"
#include "widgets/OrbitCamera.h"
#include "widgets/PassTimes.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <QColor>
#include <QElapsedTimer>
#include <QImage>
#include <QPointF>
#include <QTimer>
#include <QWidget>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace wisp {

class ViewportWindow;

// A ray in world space, metres: from the camera's eye through a point of the view.
struct ViewRay {
    glm::vec3 origin{ 0.0f };
    glm::vec3 direction{ 0.0f, 0.0f, -1.0f }; // unit
};

class Viewport : public QWidget {
    Q_OBJECT
public:
    explicit Viewport(QWidget* parent = nullptr);
    ~Viewport() override; // makes the context current and frees the GL objects

    // Draws a frame of the current state (without showing it) and returns its pixels, device
    // pixels, opaque; null when there is no usable GL.
    QImage grabFramebuffer();

    // An image of the scene as this view draws it, `pixels` big (device pixels), at full detail
    // and without the heads-up line, the gizmo, the wind arrow or the brush: File ▸ Render Image,
    // the turntable, `wisp --render` and the presets' thumbnails all come through here. The camera
    // is this view's, framed for the image's aspect while the artist has not moved it, turned by
    // `turnRadians` about the vertical through its pivot (a turntable's frames). A transparent
    // background leaves the background and the grid out: alpha 0 there, the image premultiplied.
    // Null when there is no usable GL or no framebuffer of that size. The next frame of the view
    // is drawn as before.
    struct ImageOptions {
        bool transparentBackground = false;
        float turnRadians = 0.0f;
        std::optional<Aabb> frameBounds; // framed instead of the head (thumbnails frame the hair)
        // Below 1: the preview the view draws while things move (that fraction of the strands,
        // widened, coarse curves), for comparing it with full detail.
        float previewFraction = 1.0f;
        // The hair at half the width and height, laid over the full-resolution image, as the view
        // draws it while the camera or the hair moves (HairLowResTarget), for comparing the two.
        bool hairAtHalfResolution = false;
        // The backdrop single-sampled, as the view draws it while the camera moves.
        bool backdropSingleSampled = false;
    };
    QImage renderImage(QSize pixels, const ImageOptions& options);
    QImage renderImage(QSize pixels) { return renderImage(pixels, ImageOptions{}); }
    // The largest image side renderImage() is asked for (the editor's and the command line's limit;
    // software rasterisers allocate 4 samples per pixel).
    static constexpr int kMaxImageSide = 8192;

    // Copies the head; uploads it on the next paint. Until the artist moves the camera, the view
    // follows the head (start-up 3/4 view, framed).
    void setHead(const TriangleMesh& head);
    // The neck and shoulders under the head (sim/geometry/Body.h, head space), drawn as shaded capsules a
    // little darker than the skin; none hides them.
    void setBody(const std::vector<Capsule>& capsules);
    // The newest simulation frame (null: no hair). Keeps the shared_ptr (no copy of the points)
    // and schedules a repaint; the points are streamed to the GPU in that paint.
    void setFrame(FramePtr frame);
    FramePtr frame() const { return m_frame; }
    // For the wind indicator beside the axis gizmo (bottom left, never over the model). Frames
    // carry their wind too; whichever arrived last is shown.
    void setWind(const glm::vec3& windMetresPerSecond);
    glm::vec3 wind() const { return m_wind; }

    OrbitCamera& camera() { return m_camera; }
    const OrbitCamera& camera() const { return m_camera; }
    Aabb headBounds() const { return m_headBounds; }
    // Where a world point lands in this widget, logical pixels from the top-left corner.
    glm::vec2 project(const glm::vec3& worldMetres) const;
    // The inverse of project(): the ray from the eye through a widget position (logical pixels
    // from the top-left corner), for picking the head under the mouse.
    ViewRay rayAt(QPointF logicalPixel) const;

    // The paint brush's ring on the head (BrushCursor, in GuideGeometry.h); nullopt hides it.
    // Repaints when it changes.
    void setBrushCursor(std::optional<BrushCursor> cursor);
    const std::optional<BrushCursor>& brushCursor() const { return m_brushCursor; }

    // Painted growth weights, one per head vertex, 0..1, shown as a tint of the skin. Weights of
    // another count than the head's vertices are not shown (kept, in case the matching head
    // follows). Cheap enough to call for every step of a brush stroke: only the weights are sent
    // to the GPU in the next paint.
    void setGrowthOverlay(std::vector<float> weights);
    void setShowGrowthOverlay(bool show);
    // The scalp under the hair, per head vertex (scalpCoverage in sim/groom/GrowthRegion.h): the skin is
    // tinted toward the hair's root colour there.
    void setScalpCoverage(std::vector<glm::vec4> coverage);
    bool showGrowthOverlay() const { return m_showGrowthOverlay; }

    // Hair shadows (deep opacity map from the key light, see ShadowMap): hair shades hair, hair
    // shadows the head and the head shadows the hair. On by default.
    void setShadowsEnabled(bool enabled);
    bool shadowsEnabled() const { return m_shadowsEnabled; }
    // The key light is fixed to the head by default (orbiting a paused scene reuses the shadows);
    // following the camera keeps the head lit from the artist's side, at a shadow pass per orbit step.
    void setLightFollowsCamera(bool follows);
    bool lightFollowsCamera() const { return m_lightFollowsCamera; }

    bool showGrid() const { return m_showGrid; }
    void setHairColours(const QColor& root, const QColor& tip);
    QColor hairRootColour() const;
    QColor hairTipColour() const;
    void setHairStyle(const HairStyle& style); // widths, taper, subdivision; colours included
    const HairStyle& hairStyle() const { return m_hairStyle; }

    // Level of detail while things move (see HairDetail): on by default; off draws every strand
    // in every paint. It only ever engages where painting a frame takes longer than its budget.
    void setLevelOfDetail(bool enabled);
    bool levelOfDetail() const { return m_levelOfDetail; }
    float lastDrawnFraction() const { return m_lastFraction; } // of the strands, in the last paint
    bool lastPaintWasPreview() const { return m_lastPreview; }
    // While the camera or the hair moves, the hair is drawn at half the width and height and laid
    // over the frame (HairLowResTarget); a full-resolution paint follows once they stop (as the
    // level of detail's refinement). On by default where GL is a software rasteriser (where
    // rasterising the strands is most of a paint), off on a graphics card; grabs and images always
    // draw it at full resolution.
    void setHalfResolutionWhileMoving(bool enabled);
    bool halfResolutionWhileMoving() const { return m_halfResolutionWhileMoving.value_or(m_softwareGl); }
    bool lastPaintHairAtHalfResolution() const { return m_lastHairAtHalfResolution; }
    // How long after a reduced paint (half resolution, a preview, shadows left for later) with no
    // paint after it the refinement paint comes: kRefineDelayMs by default, about the pause between
    // two drags that still reads as one motion. Tests that pace frames themselves set it beyond
    // their run, so that a slow paint on a loaded machine does not let one in between.
    static constexpr int kRefineDelayMs = 300;
    void setRefineDelayMs(int ms) { m_refineTimer.setInterval(std::max(0, ms)); }
    // The half-resolution hair drawn by our own rasteriser on the CPU (HairSoftwareRaster), the
    // strands' shaded samples captured from GL: on llvmpipe a thin line costs a triangle's setup and
    // a 4x4 block's shading per few pixels, and our code pays only for the pixels. On by default
    // where GL is a software rasteriser; WISP_GL_HAIR=1 in the environment keeps GL's lines there.
    void setSoftwareHairWhileMoving(bool enabled) { m_softwareHairWhileMoving = enabled; }
    bool softwareHairWhileMoving() const { return m_softwareHairWhileMoving.value_or(m_softwareGl && !m_glHairWanted); }
    bool lastPaintHairOnCpu() const { return m_lastHairOnCpu; }
    // The half-resolution hair laid over the frame by the pass that copies the frame into the window
    // (FrameCompositor::draw with a LowResHairLayer), only over where the CPU inked it, rather than
    // by a blended pass of its own over the frame (measured in the editor while simulating: 27.7 ->
    // 34 fps). On by default; off, to compare. The brush rings, drawn over the hair, still take
    // the pass of its own.
    void setHalfResolutionHairInPresent(bool enabled) { m_halfResolutionHairInPresent = enabled; }
    bool lastPaintHairLaidInPresent() const { return m_hairLayer.has_value(); }
    // The shadow map's hair passes drawn on the CPU (HairShadowRaster.h), the head's pass still by GL.
    // On by default where GL is a software rasteriser (unless WISP_GL_HAIR); needs the GL context
    // (call after the first paint), and the next paint makes the map again.
    void setSoftwareShadowHair(bool enabled);
    bool softwareShadowHair() const { return m_shadowMap.softwareHair(); }
    // The hair's samples for the current view at half resolution as a moving view draws them,
    // shaded by GL's vertex shader or by the software path's CPU (HairShading.h): the two must agree
    // (HairLowResTest). Empty without a context or hair. Paint first: it reads what the last paint
    // uploaded.
    std::vector<HairRasterSample> shadedHairSamples(bool onCpu);
    // GL passes that captured the hair's samples for the software path (HairRenderer::prepareSoftware):
    // one per frame, shadow map or level of detail, none per orbiting paint.
    std::uint64_t hairWorldCaptures() const { return m_hair.worldCaptures(); }
    // While the backdrop (background, head, body, grid) changes from paint to paint (the camera
    // moves, or the hair's shadow on the head moves with the hair), it is drawn single-sampled
    // straight into the frame rather than multisampled and resolved: on llvmpipe the 4x pass and its
    // resolve were two fifths of a paused orbit's paint (README "The hair's look"). The paint once
    // it holds draws it multisampled into the backdrop cache, as before. On by default where GL is a
    // software rasteriser; grabs and images always multisample.
    void setSingleSampledBackdropWhileMoving(bool enabled);
    bool singleSampledBackdropWhileMoving() const { return m_singleSampledBackdropWhileMoving.value_or(m_softwareGl); }
    bool lastPaintBackdropSingleSampled() const { return m_lastBackdropSingleSampled; }
    std::size_t lastDrawnStrands() const { return m_hair.lastDrawnStrands(); } // parents and children
    std::size_t lastDrawnLineSegments() const { return m_hair.lastDrawnLineSegments(); } // 0: ribbons

    // Drawn density (HairChildren): `density` times the frame's strands are drawn, 0.25..4. Above 1
    // render-time children are interpolated between neighbouring strands, each drawn thinner by the
    // square root of the density, so the hair looks finer and fuller; below 1 an even sample is
    // drawn, widened to keep the coverage. The preview while things move draws a fraction of these, widened to keep the
    // coverage.
    void setDisplayDensity(float density);
    float displayDensity() const { return m_displayDensity; }
    // GL work of the last paint, the frame copied out (with the hair laid in) included.
    double lastPaintMilliseconds() const { return m_lastPaintMs; }
    // Per pass, for the last paint (all zero unless timing is on; see PassTimes.h). The
    // WISP_PASS_TIMES environment variable turns it on from the start.
    void setPassTiming(bool on) { m_passTiming = on; }
    const PassTimes& lastPassTimes() const { return m_passTimes; }
    bool softwareRenderer() const { return m_softwareGl; }

    // The heads-up line as it is drawn (composed from the current frame and frame rate).
    QString hudText() const;
    // The simulation is paused: the HUD says so instead of a frame rate and solver time that
    // would be the last measured before the pause.
    void setPaused(bool paused);
    bool paused() const { return m_paused; }
    // Paints per second, smoothed; pauses of more than half a second (nothing to draw) are not
    // counted as slow drawing.
    double framesPerSecond() const { return m_fps; }
    std::uint64_t paintCount() const { return m_paintCount; } // paintGL calls so far
    std::uint64_t shadowPassCount() const { return m_shadowMap.passCount(); } // shadow maps rendered so far
    // Times the head's shadow and ambient per vertex were looked up so far: once per shadow map and
    // placement of the head, not once per paint (HeadRenderer).
    std::uint64_t headLightLookups() const { return m_head.lightUpdates(); }
    // The background at a height of the view: 0 is the top edge, 1 the bottom.
    static QColor backgroundColour(double heightFraction);
    // Empty when GL is ready; otherwise why nothing 3D is drawn (no 3.3 context, a shader error).
    QString glStatus() const { return m_glStatus; }
    // The OpenGL the view draws with, as the driver names it ("llvmpipe (LLVM 15.0.6, 256 bits), 4.5
    // (Core Profile) Mesa 22.3.6"); empty until the view's first paint has made its context.
    QString glDescription() const { return m_glDescription; }
    int samples() const { return m_samples; } // MSAA samples of the backdrop (the hair: none), known after a paint

public slots:
    void frameHead(); // F: fit the camera to the head's bounds, keeping its direction
    void setShowGrid(bool show);

signals:
    void fpsChanged(double framesPerSecond);

protected:
    bool event(QEvent* event) override;
    void paintEvent(QPaintEvent* event) override; // update(), repaint(): a frame, drawn now
    void resizeEvent(QResizeEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    enum class Drag { None, Orbit, Pan, Dolly };
    // What the backdrop (background, head, wind arrow and grid; see paintGL) was drawn for.
    struct BackdropKey {
        glm::mat4 view{ 1.0f };
        glm::mat4 projection{ 1.0f };
        QSize pixels;
        std::uint64_t revision = 0; // m_backdropRevision
        bool operator==(const BackdropKey&) const = default;
    };

    // Frames: scheduleFrame() asks for one at the next turn of the event loop (many asks, one
    // frame); presentFrame() draws one and shows it in the window; drawFrame() only draws it.
    void scheduleFrame();
    void presentFrame();
    bool drawFrame();
    bool makeCurrent();
    QSize framePixels() const;
    double frameRatio() const; // device pixels per logical pixel, of the frame
    void initializeGL();
    void paintGL(bool framebuffersRemade);
    // `gradientInResolve`: cleared transparent, the background's gradient left to the resolve.
    void drawBackdrop(const RenderView& view, bool gradientInResolve);
    // drawBackdrop, multisampled (unless `multisample` is false or the canvas has no samples),
    // resolved into the backdrop cache or the frame (GlCanvas).
    void drawResolvedBackdrop(const RenderView& view, bool intoCache, bool multisample = true);
    void paintImage(const RenderView& view); // paintGL's work for renderImage()
    // The half-resolution hair by HairSoftwareRaster into m_lowRes (begun over lowResRegion); false
    // (nothing drawn) where the samples cannot be captured.
    // `inkedSpans`: where it inked the frame (HairLowResTarget::inkedSpans).
    bool drawHairOnCpu(const RenderView& half, const HairStyle& style, float fraction, bool preview,
        const ClipRect& lowResRegion, std::vector<QRect>& inkedSpans);
    ThreadPool* rasterPool(); // m_rasterPool, made on first use
    // The hair into the bound frame, at full resolution or through m_lowRes (laid over the frame
    // by finishFrame, or here where `drawnOver`: something is drawn over the hair after it).
    void drawHair(const RenderView& view, float fraction, bool preview, bool halfResolution, bool drawnOver);
    // The finished frame into the bound target (window, grab framebuffer) with the overlays, and the
    // half-resolution hair of this paint laid in where drawHair left it (m_hairLayer).
    void finishFrame(FrameCompositor::Finish finish);
    void uploadFrameIfChanged(); // streams m_frame's strands to the hair renderer once per frame
    void updateOverlays(const RenderView& view);
    void glUnavailable(const QString& why);
    void releaseGl();
    RenderView renderView() const;
    float aspect() const;
    void measureFrameRate();
    void rebuildGuides();
    void cameraMovedByUser();
    void paintUnavailable();
    void updateBrushRings(const RenderView& view);
    float metresPerPixelAt(const RenderView& view, const glm::vec3& worldMetres) const;
    glm::vec3 keyLightWorld() const; // unit, toward the key light
    void updateShadows(); // renders the shadow map again if the hair, head or light moved

    // While renderImage() draws: its size, camera and background.
    struct ImageRender {
        QSize pixels;
        OrbitCamera camera;
        bool transparent = false;
        float previewFraction = 1.0f;
        bool hairAtHalfResolution = false;
        bool backdropSingleSampled = false;
    };
    std::optional<ImageRender> m_image;

    OrbitCamera m_camera;
    bool m_cameraTouched = false; // the artist moved it: stop following head and window changes
    Aabb m_headBounds;
    bool m_hasHead = false;

    FramePtr m_frame;
    bool m_frameDirty = false; // m_frame not yet streamed to the GPU
    glm::vec3 m_wind{ 0.0f };
    bool m_showGrid = true;
    HairStyle m_hairStyle;
    std::optional<BrushCursor> m_brushCursor;
    bool m_brushDirty = false; // rings not rebuilt since the cursor changed
    float m_brushBandMetres = 0.0f; // of the rings last built (they keep a constant width on screen)
    float m_mirrorBandMetres = 0.0f;
    bool m_showGrowthOverlay = false;
    bool m_shadowsEnabled = true;
    bool m_paused = false;
    bool m_lightFollowsCamera = false;

    ViewportWindow* m_window = nullptr; // owned by m_container
    QWidget* m_container = nullptr;
    GlCanvas m_canvas;
    FrameCompositor m_compositor;
    // Counts changes of the head, its overlay, the wind, the grid's switch and the context.
    std::uint64_t m_backdropRevision = 0;
    std::optional<BackdropKey> m_backdropKey; // what the backdrop holds; none: nothing usable
    std::optional<BackdropKey> m_lastBackdropKey; // what the last frame's backdrop was to show
    QString m_hudShown; // what the compositor's overlays show
    std::optional<glm::mat3> m_gizmoShown;
    glm::vec3 m_gizmoWind{ 0.0f }; // the wind the gizmo's image shows
    int m_gizmoTargetHeight = 0;
    double m_overlayRatio = 0.0;
    QTimer m_frameTimer; // a frame at the next turn of the event loop
    int m_requestedSamples = 4;
    GlFunctions* m_gl = nullptr;
    bool m_glFailed = false; // no usable context: the widget paints m_glStatus instead
    QString m_glStatus;
    QString m_glDescription; // GL_RENDERER, GL_VERSION (glDescription)
    int m_samples = 0;
    BackgroundRenderer m_background;
    HeadRenderer m_head;
    glm::mat4 m_headToWorld{ 1.0f }; // the newest frame's: the head moves with the simulation
    HeadRenderer m_body; // the body's capsules as one mesh
    std::vector<Capsule> m_bodyCapsules;
    HairRenderer m_hair;
    HairShadowMap m_shadowMap;
    HairLowResTarget m_lowRes;
    std::optional<bool> m_halfResolutionWhileMoving; // unset: m_softwareGl
    bool m_lastHairAtHalfResolution = false;
    std::optional<LowResHairLayer> m_hairLayer; // this paint's half-resolution hair, for finishFrame
    bool m_halfResolutionHairInPresent = true;
    std::optional<bool> m_softwareHairWhileMoving; // unset: m_softwareGl unless WISP_GL_HAIR
    bool m_glHairWanted = false; // WISP_GL_HAIR was set at construction
    bool m_lastHairOnCpu = false;
    std::unique_ptr<ThreadPool> m_rasterPool; // HairSoftwareRaster's threads, made on first use
    std::vector<float> m_lowResDepth; // the half-resolution target's depth, read for the CPU's hair
    std::optional<bool> m_singleSampledBackdropWhileMoving; // unset: m_softwareGl
    bool m_lastBackdropSingleSampled = false;
    bool m_backdropCacheSingleSampled = false; // the cache was made single-sampled (frames streaming)
    bool m_hairMoved = false; // points uploaded since the shadow map was rendered
    glm::vec3 m_shadowLight{ 0.0f }; // the light the shadow map was rendered for
    std::uint64_t m_shadowPaint = 0; // m_paintCount when it was rendered
    bool m_grabbing = false; // drawing for grabFramebuffer: shadows never a paint late
    GuideRenderer m_guides;

    Drag m_drag = Drag::None;
    Qt::MouseButton m_dragButton = Qt::NoButton;
    QPointF m_lastMouse;

    HairChildren m_children;
    float m_displayDensity = 1.0f;
    HairCurves m_drawnStrands; // the frame's strands and their children (when the density is above 1)
    std::vector<std::uint16_t> m_drawnLooks;
    std::vector<float> m_drawnWetness;
    HairStyle drawnStyle() const; // m_hairStyle, thinner by the density above 1

    HairDetail m_detail;
    bool m_levelOfDetail = true;
    bool m_refining = false; // this paint draws every strand: things stopped moving
    QTimer m_refineTimer; // fires when no paint followed a reduced one for a while
    float m_lastFraction = 1.0f;
    bool m_lastPreview = false;
    double m_lastPaintMs = 0.0;
    QElapsedTimer m_paintClock; // since this paint began
    // What the last paint drew, for the level of detail once its frame is finished (finishFrame).
    struct DetailReport {
        bool preview = false;
        float fraction = 1.0f;
        std::size_t strands = 0;
    };
    std::optional<DetailReport> m_detailReport;
    bool m_passTiming = false;
    PassTimes m_passTimes;
    PassClock m_passClock;
    bool m_softwareGl = false; // Mesa llvmpipe and friends: paints are timed with glFinish

    QElapsedTimer m_frameClock; // time between paints
    QElapsedTimer m_emitClock; // time since fpsChanged was last emitted
    double m_fps = 0.0;
    std::uint64_t m_paintCount = 0;
};

} // namespace wisp
