#include "app/editor/PaintTool.h"

#include "app/editor/Document.h"
#include "sim/params/Parameters.h"
#include "sim/solver/FrameSpace.h"
#include "widgets/Viewport.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <QKeyEvent>
#include <QMouseEvent>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {

// Dabs along a stroke this far apart, as a share of the radius: close enough that a fast stroke
// leaves an even band, far enough that a slow one does not pile up dabs on one spot.
constexpr float kDabSpacing = 0.25f;
constexpr float kRadiusStep = 1.15f; // [ and ] scale the radius by this

} // namespace

PaintTool::PaintTool(Document* document, Viewport* viewport, QObject* parent)
    : ViewportBrush(viewport, parent)
    , m_document(document)
{
    connect(m_document, &Document::headChanged, this, &PaintTool::endStroke);
}

PaintTool::~PaintTool() = default;

float PaintTool::mirrorPlaneX() const
{
    return m_document->headModel()->mirrorPlaneX();
}

void PaintTool::setActive(bool active)
{
    if (active == m_active)
        return;
    if (!active)
        endStroke();
    m_active = active;
    if (!active)
        viewport()->setBrushCursor(std::nullopt);
    viewport()->setCursor(active ? Qt::CrossCursor : Qt::ArrowCursor);
    emit activeChanged(active);
}

void PaintTool::setRadius(double metres)
{
    const float r = static_cast<float>(clampToToolSetting(ToolSetting::BrushRadius, metres));
    if (!std::isfinite(metres) || r == m_settings.radiusMetres)
        return;
    m_settings.radiusMetres = r;
    if (m_active && hasCursor())
        showCursor(lastCursor(), Qt::NoModifier);
    emit settingsChanged();
}

void PaintTool::setStrength(double strength)
{
    if (!std::isfinite(strength))
        return;
    m_settings.strength = static_cast<float>(clampToToolSetting(ToolSetting::BrushStrength, strength));
    emit settingsChanged();
}

void PaintTool::setFalloff(double falloff)
{
    if (!std::isfinite(falloff))
        return;
    m_settings.falloff = static_cast<float>(clampToToolSetting(ToolSetting::BrushFalloff, falloff));
    emit settingsChanged();
}

void PaintTool::setMode(BrushMode mode)
{
    m_settings.mode = mode;
    emit settingsChanged();
}

void PaintTool::setMirror(bool mirror)
{
    m_settings.mirrorX = mirror;
    if (m_active && hasCursor())
        showCursor(lastCursor(), Qt::NoModifier);
    emit settingsChanged();
}

std::optional<PaintTool::Hit> PaintTool::hitAt(QPointF widgetPosition) const
{
    const ViewRay ray_ws = viewport()->rayAt(widgetPosition);
    const glm::mat4 toHead = worldToHeadOf(viewport()->frame()); // the head as drawn
    const auto hit = m_document->headModel()->hitAlong(
        glm::vec3(toHead * glm::vec4(ray_ws.origin, 1.0f)), glm::mat3(toHead) * ray_ws.direction);
    if (!hit)
        return std::nullopt;
    return Hit{ hit->point, hit->normal };
}

void PaintTool::placeCursor(BrushCursor& cursor, const glm::vec3& point_hs, const glm::vec3& normal_hs) const
{
    const glm::mat4 toWorld = headToWorldOf(viewport()->frame());
    const float plane = mirrorPlaneX();
    cursor.centre = glm::vec3(toWorld * glm::vec4(point_hs, 1.0f));
    cursor.normal = glm::mat3(toWorld) * normal_hs;
    cursor.mirrorCentre = glm::vec3(toWorld * glm::vec4(2.0f * plane - point_hs.x, point_hs.y, point_hs.z, 1.0f));
    cursor.mirrorNormal = glm::mat3(toWorld) * glm::vec3(-normal_hs.x, normal_hs.y, normal_hs.z);
}

// Held modifiers change the mode for as long as they are held: Ctrl erases, Shift smooths.
BrushMode PaintTool::modeFor(Qt::KeyboardModifiers modifiers) const
{
    if (modifiers & Qt::ControlModifier)
        return m_settings.mode == BrushMode::Erase ? BrushMode::Add : BrushMode::Erase;
    if (modifiers & Qt::ShiftModifier)
        return BrushMode::Smooth;
    return m_settings.mode;
}

void PaintTool::showCursor(QPointF widgetPosition, Qt::KeyboardModifiers modifiers)
{
    const std::optional<Hit> hit = hitAt(widgetPosition);
    if (!hit) {
        viewport()->setBrushCursor(std::nullopt);
        return;
    }
    BrushCursor cursor;
    placeCursor(cursor, hit->point, hit->normal);
    cursor.radiusMetres = m_settings.radiusMetres;
    cursor.erase = modeFor(modifiers) == BrushMode::Erase;
    cursor.mirrored = m_settings.mirrorX;
    viewport()->setBrushCursor(cursor);
}

// Dabs from the stroke's last dab to `to`, kDabSpacing radii apart, then lets the hair follow.
void PaintTool::dabAlong(const Hit& to, Qt::KeyboardModifiers modifiers)
{
    BrushSettings s = m_settings;
    s.mode = modeFor(modifiers);
    const ScalpBrush& brush = m_document->headModel()->scalp();
    std::vector<float>& weights = m_document->strokeWeights();
    if (weights.size() != brush.vertexCount())
        return;
    const float spacing = kDabSpacing * s.radiusMetres;
    bool changed = false;
    if (!m_lastDab) {
        changed = !brush.dab(to.point, s, weights).empty();
        m_lastDab = to.point;
    } else {
        const glm::vec3 from = *m_lastDab;
        const float length = glm::distance(from, to.point);
        const int steps = static_cast<int>(length / spacing);
        for (int i = 1; i <= steps; ++i) {
            const glm::vec3 p = glm::mix(from, to.point, static_cast<float>(i) * spacing / length);
            changed = !brush.dab(p, s, weights).empty() || changed;
            m_lastDab = p;
        }
    }
    if (changed)
        m_document->strokeUpdated();
}

bool PaintTool::resizeByKey(const QKeyEvent* e)
{
    if (e->type() != QEvent::KeyPress || (e->key() != Qt::Key_BracketLeft && e->key() != Qt::Key_BracketRight))
        return false;
    setRadius(e->key() == Qt::Key_BracketLeft ? m_settings.radiusMetres / kRadiusStep
                                              : m_settings.radiusMetres * kRadiusStep);
    return true;
}

// A stroke ended without the mouse (the tool put down, a new head).
void PaintTool::endStroke()
{
    if (!isStroking())
        return;
    stopStroking();
    finishStroke({}, Qt::NoModifier);
}

bool PaintTool::beginStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    if (m_document->currentRegion() < 0)
        return false;
    const std::optional<Hit> hit = hitAt(position);
    if (!hit)
        return false; // off the head: nothing to paint, and nothing else wants a left click
    m_document->beginStroke();
    dabAlong(*hit, modifiers);
    return true;
}

void PaintTool::continueStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    if (const std::optional<Hit> hit = hitAt(position))
        dabAlong(*hit, modifiers);
}

void PaintTool::finishStroke(QPointF, Qt::KeyboardModifiers)
{
    m_lastDab.reset();
    m_document->endStroke(tr("Paint stroke"));
}

} // namespace wisp
