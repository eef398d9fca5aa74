#include "widgets/Viewport.h"

#include "sim/geometry/Body.h"

#include "widgets/GuideGeometry.h"
#include "widgets/ViewportOverlay.h"
#include "widgets/ViewportWindow.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLDebugLogger>
#include <QOpenGLVersionFunctionsFactory>
#include <QPaintEvent>
#include <QPainter>
#include <QResizeEvent>
#include <QSurfaceFormat>
#include <QVBoxLayout>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>
#include <limits>

// The shaders are compiled into the static wisp_widgets library, whose resource initialiser the
// linker drops unless something refers to it; Q_INIT_RESOURCE must be called outside a namespace.
static void initialiseWidgetResources()
{
    Q_INIT_RESOURCE(resources);
}

namespace wisp {
namespace {

// How much of the key light a strand crossing a shadow-map texel takes, per unit of its width over
// the texel's: above 1, since a drawn strand stands for a lock whose hairs also scatter light away.
constexpr float kStrandShadowOpacity = 1.5f;
// While the hair moves, its shadows are rendered again every this many paints: the key light is
// fixed to the head, so between two renders only the hair's own motion, a frame or two of it, is
// missing from them; each render costs a software rasteriser about a fifth of a simulating paint.
constexpr std::uint64_t kShadowPaintInterval = 3;

// A plausible adult head with neck, for framing before any head is set (metres).
constexpr Aabb kFallbackHeadBounds{ { -0.09f, -0.23f, -0.11f }, { 0.09f, 0.14f, 0.12f } };

const glm::vec3 kBackgroundTop{ 0.235f, 0.247f, 0.275f }; // sRGB
const glm::vec3 kBackgroundBottom{ 0.105f, 0.110f, 0.125f };

// The brush ring's band, device pixels: thin enough not to hide what is painted, wide enough to
// see on a busy head.
constexpr float kBrushRingPixels = 2.5f;

glm::vec3 toVec(const QColor& c)
{
    return { float(c.redF()), float(c.greenF()), float(c.blueF()) };
}
QColor toColour(const glm::vec3& c)
{
    return QColor::fromRgbF(c.x, c.y, c.z);
}

bool finiteBounds(const Aabb& b)
{
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(b.min[i]) || !std::isfinite(b.max[i]) || b.min[i] > b.max[i])
            return false;
    return true;
}

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

// The context's and the window's: the window only receives finished frames, so it needs neither
// depth nor samples (the frame's own framebuffers have them, see GlCanvas).
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

// 4x MSAA. WISP_VIEWPORT_SAMPLES overrides it (0: none): on a software rasteriser 4x MSAA about
// doubles the cost of the hair and of resolving the frame.
int viewportSamples()
{
    bool overridden = false;
    const int samples = qEnvironmentVariableIntValue("WISP_VIEWPORT_SAMPLES", &overridden);
    return overridden ? std::clamp(samples, 0, 16) : 4;
}

} // namespace

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
    m_refineTimer.setSingleShot(true);
    m_refineTimer.setInterval(300);
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

// --- Camera -------------------------------------------------------------------------------------

float Viewport::aspect() const
{
    if (m_image)
        return static_cast<float>(m_image->pixels.width()) / static_cast<float>(m_image->pixels.height());
    return height() > 0 ? static_cast<float>(width()) / static_cast<float>(height()) : 1.0f;
}

glm::vec2 Viewport::project(const glm::vec3& worldMetres) const
{
    return m_camera.project(worldMetres, glm::vec2(width(), height()));
}

ViewRay Viewport::rayAt(QPointF logicalPixel) const
{
    // The same size and aspect that project() uses, so the two are exact inverses.
    const glm::vec2 size(static_cast<float>(width()), static_cast<float>(height()));
    const float rayAspect = size.y > 0.0f ? size.x / size.y : 1.0f;
    const glm::vec2 ndc = size.x > 0.0f && size.y > 0.0f
        ? glm::vec2(2.0f * static_cast<float>(logicalPixel.x()) / size.x - 1.0f,
            1.0f - 2.0f * static_cast<float>(logicalPixel.y()) / size.y)
        : glm::vec2(0.0f);
    // In view space the ray through NDC (x, y) runs along (x / P00, y / P11, -1) from the eye.
    const glm::mat4 projection = m_camera.projection(rayAspect);
    const glm::vec3 directionView{ ndc.x / projection[0][0], ndc.y / projection[1][1], -1.0f };
    const glm::mat4 viewToWorld = glm::inverse(m_camera.view());
    return { glm::vec3(viewToWorld[3]), glm::normalize(glm::mat3(viewToWorld) * directionView) };
}

void Viewport::frameHead()
{
    m_camera.frame(m_headBounds, aspect());
    scheduleFrame();
}

void Viewport::cameraMovedByUser()
{
    m_cameraTouched = true;
    scheduleFrame();
}

void Viewport::mousePressEvent(QMouseEvent* event)
{
    const Qt::KeyboardModifiers mods = event->modifiers();
    Drag drag = Drag::None;
    if (event->button() == Qt::MiddleButton) {
        // Blender: middle orbits, Shift pans, Ctrl zooms. Maya: Alt + middle pans.
        if (mods & Qt::ShiftModifier || mods & Qt::AltModifier)
            drag = Drag::Pan;
        else if (mods & Qt::ControlModifier)
            drag = Drag::Dolly;
        else
            drag = Drag::Orbit;
    } else if (event->button() == Qt::LeftButton && (mods & Qt::AltModifier)) {
        drag = Drag::Orbit; // Maya
    } else if (event->button() == Qt::RightButton && (mods & Qt::AltModifier)) {
        drag = Drag::Dolly; // Maya
    }
    if (drag == Drag::None) {
        event->ignore(); // for the editor's tools
        return;
    }
    m_drag = drag;
    m_dragButton = event->button();
    m_lastMouse = event->position();
    event->accept();
}

void Viewport::mouseMoveEvent(QMouseEvent* event)
{
    if (m_drag == Drag::None) {
        event->ignore();
        return;
    }
    const QPointF delta = event->position() - m_lastMouse;
    m_lastMouse = event->position();
    switch (m_drag) {
    case Drag::Orbit:
        m_camera.orbit(static_cast<float>(delta.x()), static_cast<float>(delta.y()));
        break;
    case Drag::Pan:
        m_camera.pan(static_cast<float>(delta.x()), static_cast<float>(delta.y()), static_cast<float>(height()));
        break;
    case Drag::Dolly:
        m_camera.dolly(static_cast<float>(delta.y()));
        break;
    case Drag::None:
        break;
    }
    cameraMovedByUser();
    event->accept();
}

void Viewport::mouseReleaseEvent(QMouseEvent* event)
{
    if (m_drag != Drag::None && event->button() == m_dragButton) {
        m_drag = Drag::None;
        m_dragButton = Qt::NoButton;
        event->accept();
        return;
    }
    event->ignore();
}

void Viewport::wheelEvent(QWheelEvent* event)
{
    // angleDelta is in eighths of a degree; a notch of a common mouse wheel is 15 degrees.
    const QPoint angle = event->angleDelta();
    const int eighths = angle.y() != 0 ? angle.y() : angle.x();
    if (eighths == 0) {
        event->ignore();
        return;
    }
    m_camera.zoom(static_cast<float>(eighths) / 120.0f);
    cameraMovedByUser();
    event->accept();
}

void Viewport::keyPressEvent(QKeyEvent* event)
{
    if (event->key() == Qt::Key_F && !(event->modifiers() & (Qt::ControlModifier | Qt::AltModifier))) {
        frameHead();
        event->accept();
        return;
    }
    QWidget::keyPressEvent(event);
}

// --- Frames -------------------------------------------------------------------------------------

bool Viewport::event(QEvent* event)
{
    // The child window shows its own cursor: give it ours (the paint tool's cross).
    if (event->type() == QEvent::CursorChange && m_window)
        m_window->setCursor(cursor());
    return QWidget::event(event);
}

void Viewport::paintEvent(QPaintEvent*)
{
    if (m_glFailed) {
        paintUnavailable();
        return;
    }
    presentFrame();
}

void Viewport::resizeEvent(QResizeEvent* event)
{
    QWidget::resizeEvent(event);
    // Until the artist takes the camera, keep the head framed as the window takes its size.
    if (!m_cameraTouched)
        m_camera.reset(m_headBounds, aspect());
    scheduleFrame();
}

void Viewport::scheduleFrame()
{
    // A zero timer rather than QWindow::requestUpdate, which waits 5 ms on X11 before every frame.
    if (!m_glFailed && !m_frameTimer.isActive())
        m_frameTimer.start();
}

void Viewport::presentFrame()
{
    m_frameTimer.stop();
    // Hidden or covered: the window's next expose draws the frame.
    if (m_glFailed || !m_window->isExposed())
        return;
    if (!drawFrame())
        return;
    m_canvas.bindWindow();
    m_compositor.draw(m_canvas.frameColourTexture(), 0, m_canvas.size());
    m_passTimes.presentMs += m_passClock.lap();
    m_canvas.swap(m_window);
}

QImage Viewport::grabFramebuffer()
{
    m_grabbing = true;
    const bool drawn = drawFrame();
    m_grabbing = false;
    if (!drawn)
        return {};
    m_canvas.bindGrab();
    m_compositor.draw(m_canvas.frameColourTexture(), 0, m_canvas.size());
    QImage image = m_canvas.readGrab();
    image.setDevicePixelRatio(frameRatio());
    return image;
}

QImage Viewport::renderImage(QSize pixels, const ImageOptions& options)
{
    if (pixels.isEmpty() || pixels.width() > kMaxImageSide || pixels.height() > kMaxImageSide)
        return {};
    ImageRender render{ pixels, m_camera, options.transparentBackground, options.previewFraction };
    const float imageAspect = static_cast<float>(pixels.width()) / static_cast<float>(pixels.height());
    if (options.frameBounds && finiteBounds(*options.frameBounds))
        render.camera.reset(*options.frameBounds, imageAspect);
    else if (!m_cameraTouched)
        render.camera.reset(m_headBounds, imageAspect);
    render.camera.setOrientation(render.camera.yaw() + options.turnRadians, render.camera.pitch());
    m_image = render;
    QImage image;
    if (drawFrame()) {
        m_canvas.bindGrab();
        m_compositor.draw(m_canvas.frameColourTexture(), 0, m_canvas.size(),
            render.transparent ? FrameCompositor::Finish::ImageWithAlpha : FrameCompositor::Finish::Image);
        image = m_canvas.readGrab(render.transparent);
    }
    m_image.reset();
    scheduleFrame(); // the view's own framebuffers are made again at its size
    return image;
}

QSize Viewport::framePixels() const
{
    if (m_image)
        return m_image->pixels;
    // The window's size once it has one (the frame is copied into it unscaled), else this widget's.
    const QSize logical = m_window->handle() && !m_window->size().isEmpty() ? m_window->size() : size();
    return (QSizeF(logical) * frameRatio()).toSize().expandedTo(QSize(1, 1));
}

double Viewport::frameRatio() const
{
    return m_window->handle() ? m_window->devicePixelRatio() : devicePixelRatioF();
}

bool Viewport::makeCurrent()
{
    return m_canvas.makeCurrent(m_window);
}

bool Viewport::drawFrame()
{
    if (m_glFailed)
        return false;
    if (!m_canvas.context()) {
        if (!m_canvas.create(viewportFormat())) {
            glUnavailable(tr("The 3D view needs OpenGL 3.3 core; this system has no OpenGL."));
            return false;
        }
    }
    if (!makeCurrent()) {
        qWarning("Viewport: cannot make the OpenGL context current");
        return false;
    }
    if (!m_gl) {
        initializeGL();
        if (!m_gl) {
            glUnavailable(m_glStatus);
            return false;
        }
    }
    bool remade = false;
    if (!m_canvas.prepare(m_gl, framePixels(), m_requestedSamples, &remade)) {
        qWarning("Viewport: cannot make a %dx%d framebuffer", framePixels().width(), framePixels().height());
        return false;
    }
    paintGL(remade);
    return true;
}

void Viewport::glUnavailable(const QString& why)
{
    // Drawn by this widget (paintUnavailable), where the child window was.
    m_glFailed = true;
    m_glStatus = why;
    m_frameTimer.stop();
    m_container->hide();
    update();
}

// --- GL -----------------------------------------------------------------------------------------

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
    // The paint after the last skipped one catches up, so a still scene's shadows are its own.
    // Grabbed frames (tests, rendered images) always have their own.
    if (!m_grabbing && m_shadowMap.valid() && light == m_shadowLight
        && m_paintCount < m_shadowPaint + kShadowPaintInterval) {
        scheduleFrame();
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

void Viewport::drawResolvedBackdrop(const RenderView& view, bool intoCache)
{
    // Multisampled (the head's silhouette is smooth), then resolved into the single-sampled target
    // the hair is drawn over (see GlCanvas).
    const bool multisampled = m_canvas.samples() > 0;
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
    QElapsedTimer paintClock;
    paintClock.start();
    m_passTimes = PassTimes{};
    m_passClock.start(gl, m_passTiming);
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
    const bool settled = m_lastBackdropKey == key;
    m_lastBackdropKey = key;
    if (m_backdropKey != key) {
        m_backdropKey.reset();
        drawResolvedBackdrop(view, settled);
        if (settled)
            m_backdropKey = key;
    }
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
    m_hair.draw(view, drawnStyle(), std::min(m_displayDensity, 1.0f) * fraction, preview);
    // Last: its hidden parts are drawn over everything.
    updateBrushRings(view);
    if (m_brushCursor)
        m_guides.drawBrushRings(view);
    gl->glDisable(GL_DEPTH_TEST);
    checkGlErrors(gl, "Viewport::paintGL");

    // A software rasteriser works when flushed: finish here so the time is the paint's real cost
    // (presenting would wait for it anyway). On a graphics card this would only stall the
    // pipeline, and there the detail never needs to drop.
    if (m_softwareGl)
        gl->glFinish();
    m_passTimes.hairMs = m_passClock.lap();
    m_lastPaintMs = static_cast<double>(paintClock.nsecsElapsed()) * 1e-6;
    const std::size_t strands = m_hair.strandCount();
    m_lastFraction = strands > 0 ? static_cast<float>(m_hair.lastDrawnStrands()) / static_cast<float>(strands) : 1.0f;
    m_lastPreview = preview;
    if (m_levelOfDetail && !refining)
        m_detail.paintTook(m_lastPaintMs, preview, fraction, strands);
    if (preview)
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
    drawResolvedBackdrop(imageView, false);
    m_canvas.bindFrame();
    m_gl->glViewport(
        0, 0, static_cast<GLsizei>(imageView.viewportPixels.x), static_cast<GLsizei>(imageView.viewportPixels.y));
    const float preview = std::clamp(m_image->previewFraction, 0.0f, 1.0f);
    m_hair.draw(imageView, drawnStyle(), std::min(m_displayDensity, 1.0f) * preview, preview < 1.0f);
    m_gl->glDisable(GL_DEPTH_TEST);
    checkGlErrors(m_gl, "Viewport::paintImage");
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
