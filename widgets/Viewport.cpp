#include "widgets/Viewport.h"

#include "sim/geometry/Body.h"

#include "widgets/ViewportOverlay.h"
#include "widgets/ViewportSupport.h"
#include "widgets/ViewportWindow.h"

#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QVBoxLayout>

#include <algorithm>

// The shaders are compiled into the static wisp_widgets library, whose resource initialiser the
// linker drops unless something refers to it; Q_INIT_RESOURCE must be called outside a namespace.
static void initialiseWidgetResources()
{
    Q_INIT_RESOURCE(resources);
}

namespace wisp {
namespace {

// A plausible adult head with neck, for framing before any head is set (metres).
constexpr Aabb kFallbackHeadBounds{ { -0.09f, -0.23f, -0.11f }, { 0.09f, 0.14f, 0.12f } };

glm::vec3 toVec(const QColor& c)
{
    return { float(c.redF()), float(c.greenF()), float(c.blueF()) };
}
QColor toColour(const glm::vec3& c)
{
    return QColor::fromRgbF(c.x, c.y, c.z);
}

// 4x MSAA. WISP_VIEWPORT_SAMPLES overrides it (0: none): on a software rasteriser 4x MSAA about
// doubles the cost of the hair and of resolving the frame.
int viewportSamples()
{
    bool overridden = false;
    const int samples = qEnvironmentVariableIntValue("WISP_VIEWPORT_SAMPLES", &overridden);
    return overridden ? std::clamp(samples, 0, 16) : 4;
}

} // namespace

QSurfaceFormat viewportFormat()
{
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGL);
    format.setVersion(3, 3);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(0);
    format.setStencilBufferSize(0);
    format.setSamples(0);
    format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
#ifndef NDEBUG
    format.setOption(QSurfaceFormat::DebugContext);
#endif
    return format;
}

Viewport::Viewport(QWidget* parent)
    : QWidget(parent)
    , m_headBounds(kFallbackHeadBounds)
    , m_requestedSamples(viewportSamples())
    , m_passTiming(qEnvironmentVariableIsSet("WISP_PASS_TIMES"))
{
    initialiseWidgetResources();
    setFocusPolicy(Qt::StrongFocus); // F must reach us after a click in the view
    setMinimumSize(160, 120);
    m_window = new ViewportWindow(this);
    m_window->setFormat(viewportFormat());
    m_container = QWidget::createWindowContainer(m_window, this);
    m_container->setFocusPolicy(Qt::NoFocus);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_container);
    connect(m_window, &ViewportWindow::exposed, this, &Viewport::presentFrame);
    connect(m_window, &ViewportWindow::surfaceAboutToBeDestroyed, this, [this] {
        // Off this surface before it goes; the next frame makes the context current again.
        if (m_canvas.context() && QOpenGLContext::currentContext() == m_canvas.context())
            m_canvas.doneCurrent();
    });
    m_frameTimer.setSingleShot(true);
    m_frameTimer.setInterval(0);
    connect(&m_frameTimer, &QTimer::timeout, this, &Viewport::presentFrame);
    m_camera.reset(m_headBounds, 4.0f / 3.0f);
    rebuildGuides();
    m_frameClock.invalidate();
    // After a reduced paint, once nothing has asked for another for a moment, draw everything.
    // WISP_FULL_RESOLUTION_HAIR: never half resolution, to compare with.
    if (qEnvironmentVariableIsSet("WISP_FULL_RESOLUTION_HAIR"))
        m_halfResolutionWhileMoving = false;
    // WISP_MULTISAMPLED_BACKDROP: the backdrop multisampled in every paint, to compare with.
    if (qEnvironmentVariableIsSet("WISP_MULTISAMPLED_BACKDROP"))
        m_singleSampledBackdropWhileMoving = false;
    // WISP_GL_HAIR: the half-resolution hair drawn by GL's lines, to compare with.
    m_glHairWanted = qEnvironmentVariableIsSet("WISP_GL_HAIR");
    m_refineTimer.setSingleShot(true);
    m_refineTimer.setInterval(kRefineDelayMs);
    connect(&m_refineTimer, &QTimer::timeout, this, [this] {
        m_refining = true;
        scheduleFrame();
    });
}

Viewport::~Viewport()
{
    // GL objects belong to the context (m_canvas's): free them while it is current. Then the
    // window goes, while the canvas its signals would reach still exists: no signals from it.
    releaseGl();
    disconnect(m_window, nullptr, this, nullptr);
    delete m_container;
}

void Viewport::releaseGl()
{
    if (!m_gl)
        return;
    if (makeCurrent()) {
        m_compositor.release();
        m_guides.release();
        m_hair.release();
        m_shadowMap.release();
        m_lowRes.release();
        m_head.release();
        m_body.release();
        m_background.release();
        m_canvas.releaseFramebuffers();
        m_canvas.doneCurrent();
    }
    m_gl = nullptr;
}

// --- Scene --------------------------------------------------------------------------------------

void Viewport::setHead(const TriangleMesh& head)
{
    m_head.setMesh(head);
    ++m_backdropRevision;
    m_shadowMap.invalidate();
    const bool usable = validateMesh(head).empty();
    const Aabb bounds = usable ? boundsOf(head) : kFallbackHeadBounds;
    m_hasHead = usable;
    m_headBounds = finiteBounds(bounds) ? bounds : kFallbackHeadBounds;
    if (!m_cameraTouched)
        m_camera.reset(m_headBounds, aspect());
    rebuildGuides();
    scheduleFrame();
}

void Viewport::setBody(const std::vector<Capsule>& capsules)
{
    const bool same = capsules.size() == m_bodyCapsules.size()
        && std::equal(capsules.begin(), capsules.end(), m_bodyCapsules.begin(), [](const Capsule& x, const Capsule& y) {
               return x.a == y.a && x.b == y.b && x.radiusMetres == y.radiusMetres;
           });
    if (same)
        return;
    m_bodyCapsules = capsules;
    m_body.setMesh(capsuleMesh(m_bodyCapsules));
    ++m_backdropRevision;
    m_shadowMap.invalidate();
    scheduleFrame();
}

void Viewport::setFrame(FramePtr frame)
{
    m_frame = std::move(frame);
    m_frameDirty = true;
    if (m_frame && m_frame->wind != m_wind) {
        m_wind = m_frame->wind; // shown beside the axis gizmo (updateOverlays)
    }
    if (m_frame && m_frame->headToWorld != m_headToWorld) {
        m_headToWorld = m_frame->headToWorld; // the head is drawn where the solver has it
        ++m_backdropRevision;
        m_shadowMap.invalidate();
    }
    scheduleFrame();
}

void Viewport::setWind(const glm::vec3& windMetresPerSecond)
{
    if (windMetresPerSecond == m_wind)
        return;
    m_wind = windMetresPerSecond; // shown beside the axis gizmo (updateOverlays)
    scheduleFrame();
}

void Viewport::setBrushCursor(std::optional<BrushCursor> cursor)
{
    if (cursor == m_brushCursor)
        return;
    m_brushCursor = std::move(cursor);
    m_brushDirty = true;
    scheduleFrame();
}

void Viewport::setGrowthOverlay(std::vector<float> weights)
{
    m_head.setGrowthWeights(std::move(weights));
    ++m_backdropRevision;
    scheduleFrame();
}

void Viewport::setShowGrowthOverlay(bool show)
{
    if (show == m_showGrowthOverlay)
        return;
    m_showGrowthOverlay = show;
    ++m_backdropRevision;
    scheduleFrame();
}

void Viewport::rebuildGuides()
{
    m_guides.setGrid(buildGroundGrid(m_headBounds));
    m_guides.setWindArrow(buildWindArrow(m_headBounds, m_wind));
    ++m_backdropRevision;
}

void Viewport::setScalpCoverage(std::vector<glm::vec4> coverage)
{
    m_head.setScalpCoverage(std::move(coverage));
    ++m_backdropRevision;
    scheduleFrame();
}

void Viewport::setPaused(bool paused)
{
    if (paused == m_paused)
        return;
    m_paused = paused;
    scheduleFrame(); // the HUD says so
}

void Viewport::setShadowsEnabled(bool enabled)
{
    if (enabled == m_shadowsEnabled)
        return;
    m_shadowsEnabled = enabled;
    m_shadowMap.invalidate();
    ++m_backdropRevision; // the head shows the hair's shadow
    scheduleFrame();
}

void Viewport::setLightFollowsCamera(bool follows)
{
    if (follows == m_lightFollowsCamera)
        return;
    m_lightFollowsCamera = follows;
    m_shadowMap.invalidate();
    ++m_backdropRevision;
    scheduleFrame();
}

void Viewport::setShowGrid(bool show)
{
    if (show == m_showGrid)
        return;
    m_showGrid = show;
    ++m_backdropRevision;
    scheduleFrame();
}

void Viewport::setHairColours(const QColor& root, const QColor& tip)
{
    m_hairStyle.rootColour = toVec(root);
    m_hairStyle.tipColour = toVec(tip);
    scheduleFrame();
}

QColor Viewport::hairRootColour() const
{
    return toColour(m_hairStyle.rootColour);
}
QColor Viewport::hairTipColour() const
{
    return toColour(m_hairStyle.tipColour);
}

void Viewport::setHairStyle(const HairStyle& style)
{
    m_hairStyle = style;
    scheduleFrame();
}

QColor Viewport::backgroundColour(double heightFraction)
{
    const float t = static_cast<float>(std::clamp(heightFraction, 0.0, 1.0));
    return toColour(kBackgroundTop + (kBackgroundBottom - kBackgroundTop) * t);
}

QString Viewport::hudText() const
{
    return composeHudText(m_frame.get(), m_fps, m_lastPreview ? m_lastFraction : 1.0, m_lastPreview, m_paused);
}

void Viewport::setLevelOfDetail(bool enabled)
{
    m_levelOfDetail = enabled;
    m_detail.reset();
    scheduleFrame();
}

void Viewport::setHalfResolutionWhileMoving(bool enabled)
{
    m_halfResolutionWhileMoving = enabled;
    scheduleFrame();
}

void Viewport::setSingleSampledBackdropWhileMoving(bool enabled)
{
    m_singleSampledBackdropWhileMoving = enabled;
    scheduleFrame();
}

} // namespace wisp
