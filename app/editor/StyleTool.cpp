#include "app/editor/StyleTool.h"

#include "app/editor/Document.h"
#include "app/editor/PaintTool.h"
#include "app/editor/SimulationHost.h"
#include "sim/solver/FrameSpace.h"
#include "sim/style/CombOperation.h"
#include "sim/style/StrandPicking.h"
#include "widgets/Viewport.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {
constexpr double kDabSpacingPixels = 6.0; // the dab brushes (length, curl, wet, spray) dab this often
} // namespace

StyleTool::StyleTool(
    Document* document, Viewport* viewport, SimulationHost* simulation, PaintTool* brushSettings, QObject* parent)
    : ViewportBrush(viewport, parent)
    , m_document(document)
    , m_simulation(simulation)
    , m_brushSettings(brushSettings)
{
    connect(m_document, &Document::headChanged, this, &StyleTool::cancel);
}

StyleTool::~StyleTool() = default;

void StyleTool::setBrush(std::optional<StyleBrush> brush)
{
    if (brush == m_brush)
        return;
    if (isStroking()) { // put down mid-stroke: the stroke ends here
        stopStroking();
        end();
    }
    m_brush = brush;
    if (!brush)
        viewport()->setBrushCursor(std::nullopt);
    viewport()->setCursor(brush ? Qt::CrossCursor : Qt::ArrowCursor);
    emit brushChanged(brush);
}

void StyleTool::setCurlRadiusMetres(double metres)
{
    if (!std::isfinite(metres))
        return;
    m_curlRadius = static_cast<float>(clampToToolSetting(ToolSetting::PermRadius, metres));
    emit curlChanged();
}

void StyleTool::setCurlTurnsPerMetre(double turns)
{
    if (!std::isfinite(turns))
        return;
    m_curlTurns = static_cast<float>(clampToToolSetting(ToolSetting::PermTurns, turns));
    emit curlChanged();
}

// What the operations read now: the newest frame, the head, the brush settings and the perm's curl.
BrushContext StyleTool::context() const
{
    BrushContext c;
    c.frame = m_simulation->latestFrame();
    c.head = m_document->headModel();
    c.brush = m_brushSettings->settings();
    c.everyStrandSimulated = m_document->parameters().get(Param::SimulateAllStrands) != 0.0;
    c.curlRadiusMetres = m_curlRadius;
    c.curlTurnsPerMetre = m_curlTurns;
    return c;
}

// The view ray through the cursor; past the head, the dryer aims at the camera pivot's depth.
BrushSample StyleTool::sampleAt(QPointF widgetPosition, Qt::KeyboardModifiers modifiers) const
{
    const ViewRay ray = viewport()->rayAt(widgetPosition);
    BrushSample s;
    s.eye_ws = ray.origin;
    s.direction_ws = ray.direction;
    s.aimDepthMetres = glm::dot(viewport()->camera().pivot() - ray.origin, ray.direction);
    s.inverted = (modifiers & Qt::ControlModifier) != 0;
    return s;
}

void StyleTool::showCursor(QPointF widgetPosition, Qt::KeyboardModifiers modifiers)
{
    const BrushSettings& s = m_brushSettings->settings();
    BrushCursor cursor;
    cursor.radiusMetres = s.radiusMetres;
    cursor.erase = (modifiers & Qt::ControlModifier) != 0;
    cursor.mirrored = s.mirrorX;
    const auto* comb = dynamic_cast<const CombOperation*>(m_operation.get());
    if (const auto hit = m_brushSettings->hitAt(widgetPosition)) {
        m_brushSettings->placeCursor(cursor, hit->point, hit->normal);
    } else if (comb && comb->catchDepthMetres()) { // the comb off the head: at the hair
        const ViewRay ray = viewport()->rayAt(widgetPosition);
        const glm::mat4 toHead = worldToHeadOf(viewport()->frame());
        m_brushSettings->placeCursor(cursor,
            glm::vec3(toHead * glm::vec4(ray.origin + ray.direction * *comb->catchDepthMetres(), 1.0f)),
            glm::mat3(toHead) * -ray.direction);
    } else {
        viewport()->setBrushCursor(std::nullopt);
        return;
    }
    if (m_brush == StyleBrush::BlowDry) { // the cone of air, from the nozzle to where it aims
        const HairDryer dryer = dryersFor(context(), sampleAt(widgetPosition, modifiers)).front();
        cursor.dryer = true;
        cursor.dryerNozzle = dryer.nozzle;
        cursor.dryerHalfAngleRadians = dryer.halfAngleRadians;
        cursor.radiusMetres = kDryerDistanceMetres * std::tan(dryer.halfAngleRadians);
        cursor.erase = false;
    }
    viewport()->setBrushCursor(cursor);
}

bool StyleTool::beginStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    const BrushContext c = context();
    if (!hasStyledHair(c)) {
        emit message(tr("The hair is still being groomed; try again in a moment"));
        return false;
    }
    m_lastPosition = position;
    emit message(QString()); // the last stroke's news (or warning) is old now
    m_document->beginStyleStroke();
    m_operation = makeStyleOperation(*m_brush);
    passOn(m_operation->begin(c, sampleAt(position, modifiers), m_document->strokeStyle()));
    return true;
}

void StyleTool::drag(QPointF position, Qt::KeyboardModifiers modifiers)
{
    if (!m_operation)
        return;
    const QPointF moved = position - m_lastPosition;
    if (m_operation->dabs() && std::hypot(moved.x(), moved.y()) < kDabSpacingPixels)
        return;
    passOn(m_operation->step(context(), sampleAt(position, modifiers), m_document->strokeStyle()));
    m_lastPosition = position;
}

// The stroke's end: the button released, or (through setBrush) the tool put down mid-stroke. The
// edits go into the undo step before the simulation lets go of the comb's strands.
void StyleTool::end()
{
    if (!m_operation)
        return;
    StyleEffects effects = m_operation->end(context(), m_document->strokeStyle());
    if (effects.editsChanged)
        m_document->styleStrokeUpdated();
    effects.editsChanged = false;
    report(m_operation->changedStrands(m_document->endStyleStroke(brushName())));
    passOn(effects);
    m_operation.reset();
}

// The live effects of a call: the edits (the hair follows), then held strands, wet wisps, dryers.
void StyleTool::passOn(const StyleEffects& effects)
{
    if (effects.editsChanged)
        m_document->styleStrokeUpdated();
    if (effects.held) {
        std::vector<SimulationHost::HeldStrand> held;
        for (const HeldStrand& h : *effects.held)
            held.push_back({ h.identity, h.positions_ws });
        m_simulation->holdStrands(std::move(held));
    }
    if (!effects.wettedKeys.empty())
        m_simulation->wetStrands(effects.wettedKeys, effects.wetness);
    if (effects.dryers) {
        m_dryers = *effects.dryers;
        m_simulation->setDryers(*effects.dryers);
    }
}

// What a stroke did, on the status bar: an artist sees at once when a stroke caught nothing.
void StyleTool::report(int changedStrands)
{
    if (changedStrands == 0)
        emit message(tr("%1: no strand under the brush changed").arg(brushName()));
    else
        emit message(changedStrands == 1 ? tr("%1: 1 strand changed").arg(brushName())
                                         : tr("%1: %2 strands changed").arg(brushName()).arg(changedStrands));
}

// A stroke cut short (the head replaced under it): the comb and the dryer let go, and what the
// stroke changed so far is kept as its undo step (the new head then clears the edits, undoably).
void StyleTool::cancel()
{
    if (!isStroking())
        return;
    stopStroking();
    m_operation.reset();
    m_simulation->holdStrands({});
    m_dryers.clear();
    m_simulation->setDryers({});
    if (m_document->inStyleStroke())
        m_document->endStyleStroke(brushName());
}

void StyleTool::continueStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    drag(position, modifiers);
}

void StyleTool::finishStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    drag(position, modifiers);
    end();
}

bool StyleTool::keyPressed(const QKeyEvent* event)
{
    return m_brushSettings->resizeByKey(event);
}

} // namespace wisp
