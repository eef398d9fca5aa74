#include "app/editor/StyleTool.h"

#include "app/editor/Document.h"
#include "app/editor/PaintTool.h"
#include "app/editor/SimulationHost.h"
#include "sim/HairDryer.h"
#include "sim/MeshBvh.h"
#include "sim/StrandPicking.h"
#include "widgets/Viewport.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {

constexpr float kFar = 1.0e4f;             // metres: a ray that meets no head
constexpr double kDabSpacingPixels = 6.0;  // the dab brushes (length, curl, wet, spray) dab this often

// The newest frame, if its groom names its strands (a frame from before the first groom does not).
FramePtr styledFrame(const SimulationHost& host)
{
    FramePtr frame = host.latestFrame();
    if (!frame || !frame->groomShape || frame->groomShape->identities.size() != frame->strands.strandCount())
        return nullptr;
    return frame;
}

}  // namespace

QString styleBrushName(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb: return StyleTool::tr("Comb");
    case StyleBrush::Cut: return StyleTool::tr("Cut");
    case StyleBrush::Length: return StyleTool::tr("Grow / Shrink");
    case StyleBrush::Curl: return StyleTool::tr("Curl (Perm)");
    case StyleBrush::Wet: return StyleTool::tr("Wet");
    case StyleBrush::Hairspray: return StyleTool::tr("Hairspray");
    case StyleBrush::BlowDry: return StyleTool::tr("Blow-dry");
    }
    return {};
}

QString styleBrushHelp(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb:
        return StyleTool::tr("Drag through the hair: it follows the comb and rests where you leave it");
    case StyleBrush::Cut:
        return StyleTool::tr("Drag across the hanging hair: every strand the stroke crosses is cut there");
    case StyleBrush::Length:
        return StyleTool::tr("Drag over the hair to grow it; hold Ctrl to shrink it");
    case StyleBrush::Curl:
        return StyleTool::tr("Drag over the hair to perm the touched wisps with the curl below; Ctrl takes the perm out");
    case StyleBrush::Wet:
        return StyleTool::tr("Drag over the hair to wet it (heavier, clumped, curls relaxed); it dries over the "
                              "drying time; Ctrl towel-dries");
    case StyleBrush::Hairspray:
        return StyleTool::tr("Drag over the hair to fix its current shape against gravity and wind; Ctrl washes "
                              "the spray out");
    case StyleBrush::BlowDry:
        return StyleTool::tr("Hold the button: air from the cursor along the view pushes and dries the hair");
    }
    return {};
}

StyleTool::StyleTool(Document* document, Viewport* viewport, SimulationHost* simulation, PaintTool* brushSettings,
                     QObject* parent)
    : ViewportBrush(viewport, parent), m_document(document), m_simulation(simulation), m_brushSettings(brushSettings)
{
    connect(m_document, &Document::headChanged, this, &StyleTool::cancel);
}

void StyleTool::setBrush(std::optional<StyleBrush> brush)
{
    if (brush == m_brush)
        return;
    if (isStroking()) {  // put down mid-stroke: the stroke ends here
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
    m_curlRadius = std::clamp(static_cast<float>(metres), 0.0f, kStyleMaxCurlRadiusMetres);
    emit curlChanged();
}

void StyleTool::setCurlTurnsPerMetre(double turns)
{
    if (!std::isfinite(turns))
        return;
    m_curlTurns = std::clamp(static_cast<float>(turns), 0.0f, kStyleMaxCurlTurnsPerMetre);
    emit curlChanged();
}

std::vector<StyleTool::Ray> StyleTool::raysAt(QPointF widgetPosition) const
{
    const ViewRay view = viewport()->rayAt(widgetPosition);
    const float radius = m_brushSettings->settings().radiusMetres;
    float maxDepth = kFar;
    if (const auto hit = m_brushSettings->hitAt(widgetPosition))
        maxDepth = glm::dot(hit->point - view.origin, view.direction) + radius;
    std::vector<Ray> rays{{view.origin, view.direction, maxDepth}};
    if (m_brushSettings->settings().mirrorX) {
        const float plane = m_brushSettings->mirrorPlaneX();
        rays.push_back({mirroredPoint(view.origin, plane), mirroredDirection(view.direction), maxDepth});
    }
    return rays;
}

void StyleTool::showCursor(QPointF widgetPosition, Qt::KeyboardModifiers modifiers)
{
    const BrushSettings& s = m_brushSettings->settings();
    BrushCursor cursor;
    cursor.radiusMetres = s.radiusMetres;
    cursor.erase = (modifiers & Qt::ControlModifier) != 0;
    cursor.mirrored = s.mirrorX;
    if (const auto hit = m_brushSettings->hitAt(widgetPosition)) {
        cursor.centre = hit->point;
        cursor.normal = hit->normal;
    } else if (m_brush == StyleBrush::Comb && !m_grabbed.empty()) {  // the comb off the head: at the hair
        const ViewRay ray = viewport()->rayAt(widgetPosition);
        cursor.centre = ray.origin + ray.direction * m_grabbed.front().depth;
        cursor.normal = -ray.direction;
    } else {
        viewport()->setBrushCursor(std::nullopt);
        return;
    }
    const float plane = m_brushSettings->mirrorPlaneX();
    cursor.mirrorCentre = mirroredPoint(cursor.centre, plane);
    cursor.mirrorNormal = mirroredDirection(cursor.normal);
    if (m_brush == StyleBrush::BlowDry) {  // the cone of air, from the nozzle to where it aims
        const HairDryer dryer = dryerAt(widgetPosition);
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
    if (!styledFrame(*m_simulation)) {
        emit message(tr("The hair is still being groomed; try again in a moment"));
        return false;
    }
    m_lastPosition = position;
    m_touched.clear();
    emit message(QString());  // the last stroke's news (or warning) is old now
    switch (*m_brush) {
    case StyleBrush::Comb:
        m_document->beginStyleStroke();
        grabForComb(position);
        break;
    case StyleBrush::Cut:
        m_document->beginStyleStroke();
        break;
    case StyleBrush::BlowDry:
        m_wetBefore.clear();
        for (const auto& [id, style] : *m_document->style())
            if (style.wetness > 0.0f)
                m_wetBefore[id] = style.wetness;
        placeDryer(position);
        break;
    default:
        m_document->beginStyleStroke();
        dab(position, modifiers);
        break;
    }
    return true;
}

void StyleTool::drag(QPointF position, Qt::KeyboardModifiers modifiers)
{
    switch (*m_brush) {
    case StyleBrush::Comb:
        combTo(position);
        m_lastPosition = position;
        break;
    case StyleBrush::Cut:
        cutBetween(m_lastPosition, position);
        m_lastPosition = position;
        break;
    case StyleBrush::BlowDry:
        placeDryer(position);
        m_lastPosition = position;
        break;
    default: {
        const QPointF moved = position - m_lastPosition;
        if (std::hypot(moved.x(), moved.y()) >= kDabSpacingPixels) {
            dab(position, modifiers);
            m_lastPosition = position;
        }
        break;
    }
    }
}

// The stroke's end: the button released, or (through setBrush) the tool put down mid-stroke.
void StyleTool::end()
{
    if (m_brush == StyleBrush::Comb) {
        // The combed shape becomes where the strands rest; the host solves the rest shape that sags
        // onto it, then lets go of them.
        StyleEdits& edits = m_document->strokeStyle();
        for (const Grabbed& g : m_grabbed)
            edits[g.identity].shape = g.positions;
        m_document->styleStrokeUpdated();
        // The drawn strands it moved (a key hair's wisp follows it), not only the key hairs.
        report(m_document->endStyleStroke(brushName()) > 0 ? m_combedStrands : 0);
        m_simulation->holdStrands({});
        m_grabbed.clear();
        return;
    }
    if (m_brush == StyleBrush::BlowDry) {
        m_dryers.clear();
        m_simulation->setDryers({});
        keepDriedWetness();
        return;
    }
    report(m_document->endStyleStroke(brushName()));
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
    m_grabbed.clear();
    m_simulation->holdStrands({});
    m_dryers.clear();
    m_simulation->setDryers({});
    if (m_document->inStyleStroke())
        m_document->endStyleStroke(brushName());
}

// The comb catches every strand its ring covers. Members are not simulated (only their wisp's key
// hair is, unless every strand is): a wisp is caught when any of its strands is under the ring, by
// its key hair, as firmly as its strand nearest the ring's centre.
void StyleTool::grabForComb(QPointF position)
{
    m_grabbed.clear();
    m_combedStrands = 0;
    const FramePtr frame = styledFrame(*m_simulation);
    if (!frame)
        return;
    const GroomShape& shape = *frame->groomShape;
    const bool everyStrandSimulated = m_document->parameters().get(Param::SimulateAllStrands) != 0.0;
    const BrushSettings& s = m_brushSettings->settings();
    const std::vector<Ray> rays = raysAt(position);
    std::map<std::uint32_t, std::size_t> grabbedOf;  // simulated strand -> its entry in m_grabbed
    for (std::size_t r = 0; r < rays.size(); ++r) {
        const Ray& ray = rays[r];
        for (const StrandPick& pick :
             strandsNearRay(frame->strands, {}, ray.origin, ray.direction, s.radiusMetres, s.falloff, ray.maxDepth)) {
            const std::uint32_t held = everyStrandSimulated || pick.strand >= shape.wispOf.size()
                                           ? pick.strand
                                           : shape.keyOfWisp[shape.wispOf[pick.strand]];
            const float weight = pick.weight * (0.5f + 0.5f * s.strength);
            if (const auto found = grabbedOf.find(held); found != grabbedOf.end()) {
                Grabbed& g = m_grabbed[found->second];
                if (g.mirrored == (r == 1) && weight > g.weight) {  // under both rings: the first one's
                    g.weight = weight;
                    g.depth = pick.depth;
                }
                continue;
            }
            Grabbed g;
            g.identity = shape.identities[held];
            g.weight = weight;
            g.depth = pick.depth;
            g.mirrored = r == 1;
            const auto points = frame->strands.strand(held);
            g.positions.assign(points.begin(), points.end());
            for (std::size_t j = 1; j < points.size(); ++j)
                g.segmentLengths.push_back(glm::distance(points[j], points[j - 1]));
            grabbedOf.emplace(held, m_grabbed.size());
            m_grabbed.push_back(std::move(g));
        }
    }
    // What the stroke moves: the caught strands and, through their key hairs, their wisps.
    for (std::uint32_t i = 0; i < shape.identities.size(); ++i) {
        const std::uint32_t held =
            everyStrandSimulated || i >= shape.wispOf.size() ? i : shape.keyOfWisp[shape.wispOf[i]];
        m_combedStrands += grabbedOf.count(held) ? 1 : 0;
    }
    if (m_grabbed.empty())
        return;
    std::vector<SimulationHost::HeldStrand> held;
    for (const Grabbed& g : m_grabbed)
        held.push_back({g.identity, g.positions});
    m_simulation->holdStrands(std::move(held));
}

void StyleTool::combTo(QPointF position)
{
    if (m_grabbed.empty())
        return;
    const std::vector<Ray> before = raysAt(m_lastPosition);
    const std::vector<Ray> after = raysAt(position);
    std::vector<SimulationHost::HeldStrand> held;
    for (Grabbed& g : m_grabbed) {
        const std::size_t r = g.mirrored && before.size() > 1 ? 1 : 0;
        // The point of the strand under the comb follows the cursor at the depth it was caught.
        const glm::vec3 delta = (after[r].origin + after[r].direction * g.depth) -
                                (before[r].origin + before[r].direction * g.depth);
        combStrand(g.positions, g.segmentLengths, delta, g.weight);
        held.push_back({g.identity, g.positions});
    }
    m_simulation->holdStrands(std::move(held));
}

void StyleTool::cutBetween(QPointF from, QPointF to)
{
    const FramePtr frame = styledFrame(*m_simulation);
    if (!frame)
        return;
    const std::vector<Ray> a = raysAt(from);
    const std::vector<Ray> b = raysAt(to);
    const MeshBvh& head = m_brushSettings->headBvh();
    StyleEdits& edits = m_document->strokeStyle();
    bool changed = false;
    for (std::size_t r = 0; r < a.size() && r < b.size(); ++r) {
        const glm::vec3 eye = a[r].origin;
        // The artist cuts what they see: a crossing behind the head (from this eye) is not cut.
        // Hair lying on the skin may sit a little inside the mesh (the collider is a sampled
        // field): a surface within kSkinTolerance before the crossing does not hide it.
        constexpr float kSkinTolerance = 0.01f;
        const auto visible = [&](const glm::vec3& x) {
            const glm::vec3 toX = x - eye;
            const float distance = glm::length(toX);
            return !head.raycast(eye, toX / distance, distance - kSkinTolerance).has_value();
        };
        const GroomShape& shape = *frame->groomShape;
        std::map<std::uint32_t, float> keyLength;  // wisp -> its cut key hair's new length
        std::set<std::uint32_t> cutNow;
        const auto cutTo = [&](std::uint32_t strand, float length) {
            const std::uint64_t id = shape.identities[strand];
            length = std::max(length, kStyleMinLengthMetres);
            if (length >= lengthOf(id, strand) - 1e-4f)
                return;
            StrandStyle& e = edits[id];
            e.lengthMetres = length;
            if (!e.shape.empty())
                e.shape = shapeWithLength(e.shape, length);
            changed = true;
        };
        for (const StrandCut& cut : strandsCutBy(frame->strands, eye, a[r].direction, b[r].direction, visible)) {
            // The cut's share of the strand as drawn, of its groomed length (a member's drawn length
            // differs a little from it).
            const float drawn = strandLength(frame->strands.strand(cut.strand));
            const float share = drawn > 0.0f ? cut.lengthMetres / drawn : 1.0f;
            // (Of the length in the frame's groom: both blades of a mirrored stroke may cross it.)
            const float length = share * shape.lengths[cut.strand];
            cutTo(cut.strand, length);
            cutNow.insert(cut.strand);
            const std::uint32_t wisp = shape.wispOf[cut.strand];
            if (shape.keyOfWisp[wisp] == cut.strand)
                keyLength[wisp] = std::max(std::min(length, keyLength.count(wisp) ? keyLength[wisp] : length),
                                           kStyleMinLengthMetres);
        }
        // A wisp's members ride beside its key hair, point for point along its length: where the
        // key is cut, members the blade missed are cut too, or they would stick out past its tip.
        if (!keyLength.empty())
            for (std::uint32_t i = 0; i < shape.wispOf.size(); ++i)
                if (const auto found = keyLength.find(shape.wispOf[i]); found != keyLength.end() && !cutNow.count(i))
                    cutTo(i, found->second);
    }
    if (changed)
        m_document->styleStrokeUpdated();
}

// The strand's length now: what an edit set, else its groomed length.
float StyleTool::lengthOf(std::uint64_t identity, std::uint32_t strand) const
{
    const StyleEdits& edits = m_document->inStyleStroke() ? m_document->strokeStyle() : *m_document->style();
    if (const auto found = edits.find(identity); found != edits.end()) {
        if (!found->second.shape.empty())
            return strandLength(found->second.shape);
        if (found->second.lengthMetres > 0.0f)
            return found->second.lengthMetres;
    }
    const FramePtr frame = styledFrame(*m_simulation);
    return frame && strand < frame->groomShape->lengths.size() ? frame->groomShape->lengths[strand] : 0.0f;
}

// One dab of the length, curl, wet or hairspray brush at the cursor (and its mirror).
void StyleTool::dab(QPointF position, Qt::KeyboardModifiers modifiers)
{
    const FramePtr frame = styledFrame(*m_simulation);
    if (!frame)
        return;
    const GroomShape& shape = *frame->groomShape;
    const BrushSettings& s = m_brushSettings->settings();
    const bool inverted = (modifiers & Qt::ControlModifier) != 0;
    StyleEdits& edits = m_document->strokeStyle();
    std::vector<std::uint64_t> wetted;
    bool changed = false;
    for (const Ray& ray : raysAt(position)) {
        const std::vector<StrandPick> picks =
            strandsNearRay(frame->strands, {}, ray.origin, ray.direction, s.radiusMetres, s.falloff, ray.maxDepth);
        for (const StrandPick& pick : picks) {
            if (m_brush == StyleBrush::Length) {  // every touched strand, a step per dab
                const std::uint64_t id = shape.identities[pick.strand];
                const float now = lengthOf(id, pick.strand);
                const float step = kLengthStepShare * s.strength * pick.weight;
                const float length =
                    std::clamp(now * (inverted ? 1.0f - step : 1.0f + step), kStyleMinLengthMetres, kStyleMaxLengthMetres);
                if (std::abs(length - now) < 1e-5f)
                    continue;
                StrandStyle& e = edits[id];
                e.lengthMetres = length;
                if (!e.shape.empty())
                    e.shape = shapeWithLength(e.shape, length);
                changed = true;
                continue;
            }
            // Curl, wet and hairspray act on wisps: on their key hair, once per stroke.
            if (pick.strand >= shape.wispOf.size())
                continue;
            const std::uint32_t key = shape.keyOfWisp[shape.wispOf[pick.strand]];
            const std::uint64_t id = shape.identities[key];
            if (!m_touched.insert(id).second)
                continue;
            StrandStyle& e = edits[id];
            switch (*m_brush) {
            case StyleBrush::Curl:
                e.curlRadiusMetres = inverted ? -1.0f : m_curlRadius;
                e.curlTurnsPerMetre = inverted ? -1.0f : m_curlTurns;
                e.shape.clear();  // a perm re-forms the hair: a combed shape gives way to the curl
                break;
            case StyleBrush::Wet:
                e.wetness = inverted ? 0.0f : std::max(e.wetness, s.strength);
                if (!inverted)
                    wetted.push_back(id);
                break;
            case StyleBrush::Hairspray:
                if (inverted) {
                    e.stiffnessScale = 1.0f;
                    e.shape.clear();
                } else {
                    // A spray covers its cone about evenly: the falloff softens only the rim.
                    const float cover = std::max(pick.weight, 0.5f);
                    e.stiffnessScale = std::clamp(e.stiffnessScale * (1.0f + kSprayStiffening * s.strength * cover),
                                                  1.0f, kStyleMaxStiffnessScale);
                    const auto points = frame->strands.strand(key);  // the shape it has now is the one to hold
                    e.shape.assign(points.begin(), points.end());
                }
                break;
            default:
                break;
            }
            changed = true;
        }
    }
    if (!wetted.empty())
        m_simulation->wetStrands(std::move(wetted), s.strength);  // at once, even where the edit was as wet
    if (changed)
        m_document->styleStrokeUpdated();
}

// The dryer held at the cursor: aimed from the eye through the cursor at the head's surface under
// it (or, past the head, at the depth of the camera's pivot), its nozzle kDryerDistanceMetres in
// front of that point, so its air blows from the artist toward the surface they point at.
HairDryer StyleTool::dryerAt(QPointF position) const
{
    const ViewRay ray = viewport()->rayAt(position);
    glm::vec3 aim;
    if (const auto hit = m_brushSettings->hitAt(position))
        aim = hit->point;
    else
        aim = ray.origin + ray.direction * glm::dot(viewport()->camera().pivot() - ray.origin, ray.direction);
    HairDryer dryer;
    dryer.direction = glm::normalize(aim - ray.origin);
    dryer.nozzle = aim - dryer.direction * kDryerDistanceMetres;
    return dryer;
}

void StyleTool::placeDryer(QPointF position)
{
    HairDryer dryer = dryerAt(position);
    std::vector<HairDryer> dryers{dryer};
    if (m_brushSettings->settings().mirrorX) {  // symmetry: a second dryer, mirrored
        const float plane = m_brushSettings->mirrorPlaneX();
        dryer.nozzle = mirroredPoint(dryer.nozzle, plane);
        dryer.direction = mirroredDirection(dryer.direction);
        dryers.push_back(dryer);
    }
    m_dryers = dryers;
    m_simulation->setDryers(std::move(dryers));
}

// After blow-drying: the document keeps how wet the dried wisps are now, as one undo step.
void StyleTool::keepDriedWetness()
{
    const FramePtr frame = styledFrame(*m_simulation);
    if (!frame || m_wetBefore.empty())
        return;
    const GroomShape& shape = *frame->groomShape;
    std::map<std::uint64_t, std::uint32_t> keyOf;
    for (std::uint32_t key : shape.keyOfWisp)
        keyOf.emplace(shape.identities[key], key);
    m_document->beginStyleStroke();
    StyleEdits& edits = m_document->strokeStyle();
    bool changed = false;
    for (const auto& [id, applied] : m_wetBefore) {
        const auto key = keyOf.find(id);
        if (key == keyOf.end())
            continue;
        const float now = frame->wetness.empty() ? 0.0f : frame->wetness[key->second];
        if (now < applied - 0.005f) {
            edits[id].wetness = std::round(now * 1000.0f) / 1000.0f;
            changed = true;
        }
    }
    if (changed)
        m_document->styleStrokeUpdated();
    report(m_document->endStyleStroke(brushName()));
}

void StyleTool::continueStroke(QPointF position, Qt::KeyboardModifiers modifiers) { drag(position, modifiers); }

void StyleTool::finishStroke(QPointF position, Qt::KeyboardModifiers modifiers)
{
    drag(position, modifiers);
    end();
}

bool StyleTool::keyPressed(const QKeyEvent* event) { return m_brushSettings->resizeByKey(event); }

}  // namespace wisp
