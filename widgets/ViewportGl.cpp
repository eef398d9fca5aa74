// Viewport's OpenGL: setting up the renderers, and painting the backdrop, shadows, hair and
// overlays of one frame.
#include "widgets/Viewport.h"

#include "widgets/GuideGeometry.h"
#include "widgets/ViewportOverlay.h"
#include "widgets/ViewportSupport.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <QOpenGLContext>
#include <QOpenGLDebugLogger>
#include <QOpenGLVersionFunctionsFactory>
#include <QPainter>
#include <QSurfaceFormat>

#include <algorithm>
#include <cmath>
#include <limits>

namespace wisp {
namespace {

// How much of the key light a strand crossing a shadow-map texel takes, per unit of its width over
// the texel's: above 1, since a drawn strand stands for a lock whose hairs also scatter light away.
constexpr float kStrandShadowOpacity = 1.5f;
// While the hair moves, its shadows are rendered again every this many paints: the key light is
// fixed to the head, so between two renders only the hair's own motion, a frame or two of it, is
// missing from them; each render costs a software rasteriser about a fifth of a simulating paint.
constexpr std::uint64_t kShadowPaintInterval = 3;

// The brush ring's band, device pixels: thin enough not to hide what is painted, wide enough to
// see on a busy head.
constexpr float kBrushRingPixels = 2.5f;

// The box around `b` placed by the rigid `modelToWorld` (its eight corners'): where a moved head is.
Aabb placedBounds(const Aabb& b, const glm::mat4& modelToWorld)
{
    Aabb out{ glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest()) };
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p{ corner & 1 ? b.max.x : b.min.x, corner & 2 ? b.max.y : b.min.y,
            corner & 4 ? b.max.z : b.min.z };
        const glm::vec3 placed = glm::vec3(modelToWorld * glm::vec4(p, 1.0f));
        out.min = glm::min(out.min, placed);
        out.max = glm::max(out.max, placed);
    }
    return out;
}

} // namespace

void Viewport::initializeGL()
{
    m_gl = nullptr;
    m_frameDirty = true;

    QOpenGLContext* context = m_canvas.context();
    const QSurfaceFormat actual = context->format();
    const bool versionOk = actual.version() >= qMakePair(3, 3) && !context->isOpenGLES();
    auto* functions = versionOk ? QOpenGLVersionFunctionsFactory::get<GlFunctions>(context) : nullptr;
    if (!functions || !functions->initializeOpenGLFunctions()) {
        m_glStatus = tr("The 3D view needs OpenGL 3.3 core; this system offers %1.%2.")
                         .arg(actual.majorVersion())
                         .arg(actual.minorVersion());
        return;
    }
    m_gl = functions;
    const QByteArray renderer = reinterpret_cast<const char*>(m_gl->glGetString(GL_RENDERER));
    m_glDescription = QString::fromUtf8(renderer) + QStringLiteral(", ")
        + QString::fromUtf8(reinterpret_cast<const char*>(m_gl->glGetString(GL_VERSION)));
    m_softwareGl = renderer.contains("llvmpipe") || renderer.contains("softpipe") || renderer.contains("SwiftShader")
        || renderer.contains("Software");

#ifndef NDEBUG
    if (actual.testOption(QSurfaceFormat::DebugContext)) {
        auto* logger = new QOpenGLDebugLogger(this);
        if (logger->initialize()) {
            connect(logger, &QOpenGLDebugLogger::messageLogged, this, [](const QOpenGLDebugMessage& message) {
                if (message.severity() & (QOpenGLDebugMessage::HighSeverity | QOpenGLDebugMessage::MediumSeverity))
                    qWarning("GL: %s", qPrintable(message.message()));
            });
            logger->startLogging();
        }
    }
#endif

    QStringList errors;
    if (!m_background.initialize(m_gl))
        errors << m_background.error();
    if (!m_head.initialize(m_gl))
        errors << m_head.error();
    if (!m_body.initialize(m_gl))
        errors << m_body.error();
    m_body.setColour({ 0.80f, 0.61f, 0.52f }); // the skin a little darker, so the head stands out
    if (!m_hair.initialize(m_gl))
        errors << m_hair.error();
    // Without shadows (a driver without float framebuffers) the hair is still drawn, lit.
    if (!m_shadowMap.initialize(m_gl))
        qWarning("Viewport: %s", qPrintable(m_shadowMap.error()));
    // On a software rasteriser the shadow map's hair passes too are ours (HairShadowRaster.h).
    const bool softwareHair = m_softwareGl && !m_glHairWanted;
    m_shadowMap.setSoftwareHair(softwareHair, softwareHair ? rasterPool() : nullptr); // no threads on a card
    // Without it (a shader that does not build) the hair is always drawn at full resolution.
    if (!m_lowRes.initialize(m_gl))
        qWarning("Viewport: %s", qPrintable(m_lowRes.error()));
    if (!m_guides.initialize(m_gl))
        errors << m_guides.error();
    if (!m_compositor.initialize(m_gl))
        errors << m_compositor.error();
    m_glStatus = errors.join(QLatin1Char('\n'));
    if (!m_glStatus.isEmpty())
        qWarning("Viewport: %s", qPrintable(m_glStatus));
    // Nothing drawn or uploaded with an earlier context is left.
    ++m_backdropRevision;
    m_hudShown.clear();
    m_gizmoShown.reset();
    // A renderer whose shader failed draws nothing; the others still work.
    checkGlErrors(m_gl, "Viewport::initializeGL");
}

RenderView Viewport::renderView() const
{
    RenderView view;
    const QSize pixels = m_canvas.size().expandedTo(QSize(1, 1));
    view.viewportPixels = glm::vec2(static_cast<float>(pixels.width()), static_cast<float>(pixels.height()));
    const OrbitCamera& camera = m_image ? m_image->camera : m_camera;
    view.view = camera.view();
    view.projection = camera.projection(aspect());
    view.viewProjection = view.projection * view.view;
    // Key from the upper left and in front, fill low from the right: the classic portrait setup. The
    // fill follows the camera; the key stays with the head unless asked to follow (keyLightWorld).
    view.keyLightView = glm::normalize(glm::mat3(view.view) * keyLightWorld());
    view.fillLightView = glm::normalize(glm::vec3(0.70f, -0.15f, 0.45f));
    if (m_shadowsEnabled && m_shadowMap.valid())
        view.shadow = m_shadowMap.lookup();
    // The cranium's centre, not the box's (which the neck pulls down): hair wraps around it.
    const glm::vec3 cranium{ m_headBounds.center().x, m_headBounds.max.y - 0.3f * m_headBounds.size().y,
        m_headBounds.center().z };
    view.headCentreView = glm::vec3(view.view * m_headToWorld * glm::vec4(cranium, 1.0f));
    view.headRadiusMetres = 0.5f * std::max(m_headBounds.size().x, m_headBounds.size().z);
    view.samples = m_samples;
    return view;
}

glm::vec3 Viewport::keyLightWorld() const
{
    // Where the portrait key (upper left, in front) is seen from the start-up view, or from the
    // camera now when the light follows it.
    const glm::vec3 keyView = glm::normalize(glm::vec3(-0.45f, 0.65f, 0.60f));
    OrbitCamera startUp;
    const glm::mat3 turn(m_lightFollowsCamera ? m_camera.view() : startUp.view());
    return glm::normalize(glm::transpose(turn) * keyView);
}

void Viewport::updateShadows()
{
    const bool wanted = m_shadowsEnabled && m_frame && m_hair.strandCount() > 0;
    if (!wanted) {
        if (m_shadowMap.valid()) {
            m_shadowMap.invalidate();
            ++m_backdropRevision; // the head loses the hair's shadow
        }
        return;
    }
    const glm::vec3 light = keyLightWorld();
    if (m_shadowMap.valid() && !m_hairMoved && light == m_shadowLight)
        return;
    // While the hair moves, every third paint: a shadow two frames late does not show, and the passes
    // (and the head drawn again under the new shadow) cost a software rasteriser much of a frame.
    // Once frames stop coming, the refinement paint catches up, so a still scene's shadows are its
    // own. Not a paint of its own at once: while frames stream, it came before the next frame, a
    // paint with nothing moving, so drawn in full (measured in the editor: every third paint,
    // 75-90 ms, holding it at 21-24 fps). Grabbed frames (tests, rendered images) always have their own.
    if (!m_grabbing && !m_refining && m_shadowMap.valid() && light == m_shadowLight
        && m_paintCount < m_shadowPaint + kShadowPaintInterval) {
        m_refineTimer.start();
        return;
    }
    m_shadowPaint = m_paintCount;
    m_hairMoved = false;
    m_shadowLight = light;
    // Everything that can cast or take a shadow: the hair and the head where the frame has it (with
    // a little margin).
    Aabb box = placedBounds(m_headBounds, m_headToWorld);
    const Aabb& hair = m_hair.bounds();
    box.min = glm::min(box.min, hair.min);
    box.max = glm::max(box.max, hair.max);
    const float radius = 0.5f * glm::length(box.size()) + 0.01f;
    // What one strand takes of the light crossing a texel: its width over the texel's (capped), the
    // shadow's own phone-wire antialiasing (a one-texel line with the true width as opacity). The
    // width drawn in the view: children above 1x density are thinner there, and so here.
    const float texelMetres = 2.0f * radius / static_cast<float>(HairShadowMap::kPixels);
    const float opacity = std::clamp(kStrandShadowOpacity * drawnStyle().rootWidthMetres() / texelMetres, 0.02f, 1.0f);
    const std::uint64_t before = m_shadowMap.passCount();
    m_shadowMap.render(m_hair, m_head, m_body, m_headToWorld, light, box.center(), radius, opacity);
    if (m_shadowMap.passCount() != before)
        ++m_backdropRevision; // the head shows the new shadow (none drawn: no GL for it, nothing new)
}

void Viewport::measureFrameRate()
{
    ++m_paintCount;
    if (m_frameClock.isValid()) {
        const double seconds = static_cast<double>(m_frameClock.nsecsElapsed()) * 1e-9;
        if (seconds > 0.0 && seconds < 0.5) {
            const double rate = 1.0 / seconds;
            // Exponential smoothing over ~10 paints: steady to read, still follows a real change.
            m_fps = m_fps > 0.0 ? m_fps + 0.1 * (rate - m_fps) : rate;
        }
    }
    m_frameClock.start();
    if (!m_emitClock.isValid() || m_emitClock.elapsed() >= 250) {
        m_emitClock.start();
        emit fpsChanged(m_fps);
    }
}

void Viewport::paintUnavailable()
{
    QPainter painter(this);
    painter.fillRect(rect(), backgroundColour(0.5));
    painter.setPen(QColor(230, 230, 230));
    painter.drawText(rect().adjusted(20, 20, -20, -20), Qt::AlignCenter | Qt::TextWordWrap, m_glStatus);
}

float Viewport::metresPerPixelAt(const RenderView& view, const glm::vec3& worldMetres) const
{
    // projection[1][1] = 1 / tan(fovY / 2): the view is 2 depth / P11 metres tall at that depth.
    const float depth = std::max(-(view.view * glm::vec4(worldMetres, 1.0f)).z, m_camera.nearPlane());
    return 2.0f * depth / (view.projection[1][1] * view.viewportPixels.y);
}

void Viewport::updateBrushRings(const RenderView& view)
{
    if (!m_brushCursor) {
        if (m_brushDirty)
            m_guides.setBrushRings({});
        m_brushDirty = false;
        return;
    }
    // A constant width on screen: rebuilt when the cursor moves or the zoom changes the width.
    const BrushCursor& cursor = *m_brushCursor;
    const float band = kBrushRingPixels * metresPerPixelAt(view, cursor.centre);
    const float mirrorBand = kBrushRingPixels * metresPerPixelAt(view, cursor.mirrorCentre);
    const auto changed = [](float was, float now) { return !(std::abs(now - was) <= 0.02f * was); };
    if (!m_brushDirty && !changed(m_brushBandMetres, band) && !changed(m_mirrorBandMetres, mirrorBand))
        return;
    m_brushDirty = false;
    m_brushBandMetres = band;
    m_mirrorBandMetres = mirrorBand;
    m_guides.setBrushRings(buildBrushRings(cursor, band, mirrorBand));
}

void Viewport::drawBackdrop(const RenderView& view, bool gradientInResolve)
{
    GlFunctions* gl = m_gl;
    const bool transparent = m_image && m_image->transparent;
    gl->glViewport(0, 0, static_cast<GLsizei>(view.viewportPixels.x), static_cast<GLsizei>(view.viewportPixels.y));
    gl->glDisable(GL_SCISSOR_TEST);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glDepthMask(GL_TRUE);
    gl->glDepthFunc(GL_LESS);
    if (transparent || gradientInResolve)
        gl->glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    else
        gl->glClearColor(kBackgroundBottom.x, kBackgroundBottom.y, kBackgroundBottom.z, 1.0f);
    gl->glClearDepth(1.0);
    gl->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!transparent && !gradientInResolve)
        m_background.draw(kBackgroundTop, kBackgroundBottom);
    m_head.draw(withModel(view, m_headToWorld), m_showGrowthOverlay);
    m_body.draw(withModel(view, m_headToWorld)); // the solver collides with the body in head space too
    if (m_showGrid && !transparent)
        m_guides.drawGrid(view); // translucent and writing no depth: the hair is drawn over it
}

void Viewport::drawResolvedBackdrop(const RenderView& view, bool intoCache, bool multisample)
{
    // Multisampled (the head's silhouette is smooth), then resolved into the single-sampled target
    // the hair is drawn over (see GlCanvas).
    const bool multisampled = multisample && m_canvas.samples() > 0;
    const auto bindTarget = [&] {
        if (intoCache)
            m_canvas.bindBackdropCache();
        else
            m_canvas.bindFrame();
    };
    // The gradient goes under the head in the resolve, a colour a pixel, rather than four samples
    // a pixel here (on llvmpipe a full-screen multisampled pass is a good part of the backdrop).
    const bool transparent = m_image && m_image->transparent;
    const bool gradientInResolve = multisampled && !transparent;
    if (multisampled)
        m_canvas.bindBackdrop();
    else
        bindTarget();
    drawBackdrop(view, gradientInResolve);
    if (multisampled) {
        bindTarget();
        std::optional<FrameCompositor::Gradient> gradient;
        if (gradientInResolve)
            gradient = FrameCompositor::Gradient{ kBackgroundTop, kBackgroundBottom };
        m_compositor.resolveWithDepth(m_canvas.backdropColourTexture(), m_canvas.backdropDepthTexture(),
            m_canvas.samples(), m_canvas.size(), gradient);
    }
}

void Viewport::paintGL(bool framebuffersRemade)
{
    if (m_image) {
        // An image always has its own, up-to-date shadows (drawn before the frame is bound: the
        // map has framebuffers of its own).
        uploadFrameIfChanged();
        const bool grabbing = m_grabbing;
        m_grabbing = true;
        if (m_shadowMap.valid() || m_shadowsEnabled)
            updateShadows();
        m_grabbing = grabbing;
        paintImage(renderView());
        return;
    }
    measureFrameRate();
    GlFunctions* gl = m_gl;
    m_paintClock.start();
    m_passTimes = PassTimes{};
    m_passClock.start(gl, m_passTiming);
    const bool hairIsNew = m_frameDirty; // a frame arrived: the hair moves
    uploadFrameIfChanged();
    m_passTimes.uploadMs = m_passClock.lap();

    if (m_shadowMap.valid() || m_shadowsEnabled)
        updateShadows();
    m_passTimes.shadowMs = m_passClock.lap();
    m_samples = m_canvas.samples() > 1 ? m_canvas.samples() : 0;
    const RenderView view = renderView();

    // The background, the head, the wind arrow and the grid change only with the camera, the head
    // and its overlay, the wind and the grid's switch, but cost a good part of a software
    // rasteriser's frame: they are drawn into the backdrop once, and every frame starts from a copy
    // of it (colour and depth). While they change every frame (the camera orbits, a brush paints
    // the overlay), they are drawn straight into the frame; the backdrop is made once they hold.
    const BackdropKey key{ view.view, view.projection, m_canvas.size(), m_backdropRevision };
    if (framebuffersRemade)
        m_backdropKey.reset();
    // Settled: as the last paint had it. While frames stream under a still camera, a new revision
    // (the head's new shadow every few paints) is settled too: the camera holds, so what is drawn
    // now is what the next paints show (drawn into the cache once, not into the frame and again).
    const bool sameCamera = m_lastBackdropKey && m_lastBackdropKey->view == key.view
        && m_lastBackdropKey->projection == key.projection && m_lastBackdropKey->pixels == key.pixels;
    const bool settled = m_lastBackdropKey == key || (hairIsNew && sameCamera);
    m_lastBackdropKey = key;
    // While it changes every paint, single-sampled (setSingleSampledBackdropWhileMoving); while frames
    // stream in too, where the head takes a new shadow every few paints and a multisampled backdrop
    // would be made for a paint or two (measured between docks: 29 ms against 12 every third paint).
    // A single-sampled backdrop kept in the cache is made again multisampled once things hold.
    const bool singleSampled = (!settled || hairIsNew) && singleSampledBackdropWhileMoving() && !m_grabbing
        && !m_refining && m_canvas.samples() > 0;
    if (m_backdropKey != key || (m_backdropCacheSingleSampled && !singleSampled)) {
        m_backdropKey.reset();
        drawResolvedBackdrop(view, settled, !singleSampled);
        if (settled) {
            m_backdropKey = key;
            m_backdropCacheSingleSampled = singleSampled;
        }
    }
    m_lastBackdropSingleSampled = singleSampled;
    if (m_backdropKey)
        m_canvas.copyBackdropCacheToFrame();
    m_canvas.bindFrame();
    gl->glViewport(0, 0, static_cast<GLsizei>(view.viewportPixels.x), static_cast<GLsizei>(view.viewportPixels.y));
    m_passTimes.backdropMs = m_passClock.lap();

    const bool refining = m_refining;
    m_refining = false;
    const bool preview = m_levelOfDetail && !refining && m_detail.previewing();
    const float fraction = preview ? m_detail.fraction(m_hair.strandCount()) : 1.0f;
    // Below a density of 1 only that share of the strands is drawn, widened (see setDisplayDensity).
    // While the camera or the hair moves (this paint's backdrop or hair differs from the last's), the
    // hair at half resolution; the refinement paint after the motion draws it whole.
    const bool moving = !settled || hairIsNew;
    const bool halfResolution = halfResolutionWhileMoving() && moving && !refining && !m_grabbing;
    // The brush rings are drawn over the hair: it is then laid over the frame before them.
    drawHair(view, std::min(m_displayDensity, 1.0f) * fraction, preview, halfResolution, m_brushCursor.has_value());
    // Last: its hidden parts are drawn over everything.
    updateBrushRings(view);
    if (m_brushCursor)
        m_guides.drawBrushRings(view);
    gl->glDisable(GL_DEPTH_TEST);
    checkGlErrors(gl, "Viewport::paintGL");

    m_passTimes.hairMs = m_passClock.lap();
    const std::size_t strands = m_hair.strandCount();
    m_lastFraction = strands > 0 ? static_cast<float>(m_hair.lastDrawnStrands()) / static_cast<float>(strands) : 1.0f;
    m_lastPreview = preview;
    // Reported to the level of detail once the frame is finished (finishFrame): the hair may be
    // laid over it there, and that is part of what this paint's detail costs.
    m_detailReport.reset();
    if (m_levelOfDetail && !refining)
        m_detailReport = DetailReport{ preview, fraction, strands };
    if (preview || m_lastHairAtHalfResolution || m_lastBackdropSingleSampled)
        m_refineTimer.start();

    updateOverlays(view);
}

void Viewport::uploadFrameIfChanged()
{
    if (!m_frameDirty)
        return;
    m_frameDirty = false;
    if (m_frame && m_children.prepare(m_frame->strands, m_frame->lookOfStrand, m_displayDensity) > 0) {
        m_children.interpolate(
            m_frame->strands, m_frame->lookOfStrand, m_frame->wetness, m_drawnStrands, m_drawnLooks, m_drawnWetness);
        m_hair.setLooks(m_frame->looks);
        m_hair.upload(m_drawnStrands, m_drawnLooks, m_drawnWetness);
        m_hairMoved = true;
    } else if (m_frame) {
        m_hair.setLooks(m_frame->looks);
        m_hair.upload(m_frame->strands, m_frame->lookOfStrand, m_frame->wetness);
        m_hairMoved = true;
    } else {
        m_hair.clear();
    }
}

void Viewport::setDisplayDensity(float density)
{
    density = std::clamp(std::isfinite(density) ? density : 1.0f, HairChildren::kMinDensity, HairChildren::kMaxDensity);
    if (density == m_displayDensity)
        return;
    m_displayDensity = density;
    m_frameDirty = true;
    m_detail.reset();
    scheduleFrame();
}

HairStyle Viewport::drawnStyle() const
{
    HairStyle style = m_hairStyle;
    // Children stand for hairs of the lock their parent draws, so they are thinner; by the square
    // root of the density, not the density: thinner still and their coverage would round away in
    // 8-bit colour (measured: 88 % of 1x's coverage at 4x), while this makes more strands look
    // fuller, as children do in Blender and XGen.
    if (m_displayDensity > 1.0f) {
        const float thinner = std::sqrt(m_displayDensity);
        style.lockWidthScale /= thinner; // every look's width is its thickness times this
    }
    return style;
}

void Viewport::paintImage(const RenderView& view)
{
    // Straight into the frame (the backdrop cache is the view's), every strand, no overlays; the
    // frame rate, the level of detail and the refinement timer are the view's and stay untouched.
    uploadFrameIfChanged();
    m_samples = m_canvas.samples() > 1 ? m_canvas.samples() : 0;
    RenderView imageView = view;
    imageView.samples = m_samples;
    drawResolvedBackdrop(imageView, false, !m_image->backdropSingleSampled);
    m_canvas.bindFrame();
    m_gl->glViewport(
        0, 0, static_cast<GLsizei>(imageView.viewportPixels.x), static_cast<GLsizei>(imageView.viewportPixels.y));
    const float preview = std::clamp(m_image->previewFraction, 0.0f, 1.0f);
    drawHair(
        imageView, std::min(m_displayDensity, 1.0f) * preview, preview < 1.0f, m_image->hairAtHalfResolution, false);
    m_gl->glDisable(GL_DEPTH_TEST);
    checkGlErrors(m_gl, "Viewport::paintImage");
}

void Viewport::drawHair(const RenderView& view, float fraction, bool preview, bool halfResolution, bool drawnOver)
{
    m_hairLayer.reset();
    const QSize pixels = m_canvas.size();
    const HairStyle style = drawnStyle();
    // Only where the hair can be: the half-resolution target's passes cover the whole frame
    // otherwise (measured: a fifth of a paused orbit's hair pass). Its strands reach half a width
    // beyond their points (drawnBounds), lines and the antialiasing skirt a pixel or two more, and
    // the target's texels are two pixels: four pixels of margin, two more where begin() clears.
    const ClipRect hairRegion = halfResolution ? clipRectOfBox(m_hair.drawnBounds(style, fraction), view.viewProjection,
                                    view.viewportPixels, std::max(style.minWidthPixels, 1.0f) + 4.0f)
                                               : kWholeViewport;
    const ClipRect lowResRegion = widenClipRect(hairRegion, view.viewportPixels, 4.0f);
    m_lastHairOnCpu = false;
    m_lastHairAtHalfResolution = halfResolution && m_lowRes.begin(pixels, m_canvas.frameDepthTexture(), lowResRegion);
    if (!m_lastHairAtHalfResolution) {
        m_hair.draw(view, style, fraction, preview);
        return;
    }
    // The same view over half the pixels: each strand's width in them, its coverage, and how finely
    // its curve is sampled follow (HairRenderer::draw reads viewportPixels).
    RenderView half = view;
    half.viewportPixels
        = glm::vec2(static_cast<float>(m_lowRes.size().width()), static_cast<float>(m_lowRes.size().height()));
    std::vector<QRect> inkedSpans;
    m_lastHairOnCpu
        = softwareHairWhileMoving() && drawHairOnCpu(half, style, fraction, preview, lowResRegion, inkedSpans);
    if (!m_lastHairOnCpu) {
        // No depth writes: its texels are four pixels, and a partly covering strand would hide the
        // strands beside it (measured on the default groom: 11 % of the hair's ink lost with them).
        m_hair.setDepthWrites(false);
        m_hair.draw(half, style, fraction, preview);
        m_hair.setDepthWrites(true);
    }
    m_canvas.bindFrame();
    // Laid over the frame as it is copied into the window (finishFrame): a blended pass of its own
    // over the frame cost llvmpipe 12-14 ms between the editor's docks, whatever its shader.
    LowResHairLayer layer = m_lowRes.layer(pixels, m_canvas.frameDepthTexture(), view.projection, hairRegion);
    if (m_lastHairOnCpu)
        layer.inkedSpans = std::move(inkedSpans);
    if (drawnOver || !m_halfResolutionHairInPresent)
        m_lowRes.composite(layer);
    else
        m_hairLayer = std::move(layer);
    m_gl->glEnable(GL_DEPTH_TEST); // as HairRenderer::draw leaves it
}

void Viewport::finishFrame(FrameCompositor::Finish finish)
{
    m_compositor.draw(m_canvas.frameColourTexture(), 0, m_canvas.size(), finish, m_hairLayer ? &*m_hairLayer : nullptr);
    // A software rasteriser works when flushed: finish here so the time is the paint's real cost
    // (the swap would wait for it anyway). On a graphics card this would only stall the pipeline,
    // and there the detail never needs to drop.
    if (m_softwareGl)
        m_gl->glFinish();
    if (m_image)
        return; // an image's paint is not the view's: its time and detail are left alone
    m_lastPaintMs = static_cast<double>(m_paintClock.nsecsElapsed()) * 1e-6;
    if (m_detailReport)
        m_detail.paintTook(m_lastPaintMs, m_detailReport->preview, m_detailReport->fraction, m_detailReport->strands);
    m_detailReport.reset();
}

bool Viewport::drawHairOnCpu(const RenderView& half, const HairStyle& style, float fraction, bool preview,
    const ClipRect& lowResRegion, std::vector<QRect>& inkedSpans)
{
    // The samples first: llvmpipe runs their vertex shader on this thread, while its own threads
    // rasterise the backdrop and the target's depth, flushed to them here.
    m_gl->glFlush();
    if (!m_hair.prepareSoftware(half, style, fraction, preview))
        return false;
    const PixelRect rect = pixelRectOfClipRect(lowResRegion, m_lowRes.size().width(), m_lowRes.size().height());
    m_lowRes.readDepth(rect, m_lowResDepth);
    const std::span<const std::uint8_t> rgba = m_hair.drawSoftware(rect, m_lowResDepth, rasterPool());
    if (rgba.empty())
        return rect.width() == 0 || rect.height() == 0; // the samples could not be read: GL draws them
    m_lowRes.writeColour(rect, rgba);
    inkedSpans = HairLowResTarget::inkedSpans(rect, rgba, m_canvas.size());
    return true;
}

void Viewport::setSoftwareShadowHair(bool enabled)
{
    m_shadowMap.setSoftwareHair(enabled, rasterPool());
    m_shadowMap.invalidate();
    ++m_backdropRevision;
    scheduleFrame();
}

ThreadPool* Viewport::rasterPool()
{
    if (!m_rasterPool)
        m_rasterPool = std::make_unique<ThreadPool>(0);
    return m_rasterPool.get();
}

std::vector<HairRasterSample> Viewport::shadedHairSamples(bool onCpu)
{
    if (!m_gl || !makeCurrent())
        return {};
    RenderView half = renderView();
    const QSize lowRes = HairLowResTarget::sizeFor(m_canvas.size());
    half.viewportPixels = glm::vec2(static_cast<float>(lowRes.width()), static_cast<float>(lowRes.height()));
    return m_hair.shadedSamples(half, drawnStyle(), std::min(m_displayDensity, 1.0f), false, onCpu);
}

void Viewport::updateOverlays(const RenderView& view)
{
    // Painted again only when what they show changes: the text, the camera's turn, the size.
    const QSize pixels = m_canvas.size();
    const double ratio = frameRatio();
    const QString hud = hudText();
    if (hud != m_hudShown || ratio != m_overlayRatio) {
        m_hudShown = hud;
        m_compositor.setOverlay(FrameCompositor::Slot::Hud, paintHudImage(hud, ratio), QPoint(0, 0));
    }
    const glm::mat3 turn(view.view);
    if (!m_gizmoShown || *m_gizmoShown != turn || ratio != m_overlayRatio || pixels.height() != m_gizmoTargetHeight
        || m_gizmoWind != m_wind) {
        m_gizmoShown = turn;
        m_gizmoWind = m_wind;
        m_gizmoTargetHeight = pixels.height();
        const QImage gizmo = paintGizmoImage(view.view, ratio, m_wind);
        m_compositor.setOverlay(FrameCompositor::Slot::Gizmo, gizmo, QPoint(0, pixels.height() - gizmo.height()));
    }
    m_overlayRatio = ratio;
}

} // namespace wisp
