#include "app/editor/Document.h"

#include "app/editor/DocumentCommands.h"
#include "sim/geometry/DefaultHead.h"

#include <glm/common.hpp>

#include <algorithm>

namespace wisp {

namespace {

GrowthRegion firstRegion(std::vector<float> weights)
{
    GrowthRegion r;
    r.id = 0;
    r.name = "Scalp";
    r.weights = std::move(weights);
    return r;
}

} // namespace

Document::Document(QObject* parent)
    : QObject(parent)
{
    DefaultHead d = makeDefaultHead();
    m_head = std::make_shared<const HeadModel>(std::move(d.mesh));
    m_regions.push_back(firstRegion(std::move(d.growthWeights)));
    m_current = 0;
}

int Document::indexOfRegion(std::uint32_t id) const
{
    for (std::size_t i = 0; i < m_regions.size(); ++i)
        if (m_regions[i].id == id)
            return static_cast<int>(i);
    return -1;
}

void Document::setCurrentRegion(int index)
{
    if (m_regions.empty())
        index = -1;
    else
        index = std::clamp(index, 0, regionCount() - 1);
    if (index == m_current)
        return;
    m_current = index;
    emit currentRegionChanged(index);
}

std::uint32_t Document::nextRegionId() const
{
    std::uint32_t next = 0;
    for (const GrowthRegion& r : m_regions)
        next = std::max(next, r.id + 1);
    return next;
}

// --- Edits -----------------------------------------------------------------------------------

QString Document::editParameter(Param id, double value, bool dragging)
{
    ParameterValues check = m_parameters;
    if (std::string error = check.set(id, value); !error.empty())
        return QString::fromStdString(error);
    m_undoStack.push(new SetParameterCommand(this, id, m_parameters.get(id), check.get(id), dragging));
    return {};
}

QString Document::editRegionParameter(int index, Param id, double value, bool dragging)
{
    if (index < 0 || index >= regionCount())
        return tr("no region %1").arg(index + 1);
    if (parameterInfo(id).group != ParamGroup::Wisp)
        return tr("%1 is not a region's parameter").arg(QString::fromUtf8(parameterInfo(id).key.data()));
    const GrowthRegion& r = region(index);
    ParameterValues check = r.values;
    if (std::string error = check.set(id, value); !error.empty())
        return QString::fromStdString(error);
    m_undoStack.push(new SetRegionParameterCommand(
        this, r.id, QString::fromStdString(r.name), id, r.values.get(id), check.get(id), dragging));
    return {};
}

int Document::addRegion(const QString& name)
{
    std::vector<GrowthRegion> after = m_regions;
    GrowthRegion r;
    r.id = nextRegionId();
    r.name = name.toStdString();
    r.weights.assign(head().positions.size(), 0.0f);
    if (m_current >= 0) { // a new layer starts from the look being edited, as artists expect
        r.values = region(m_current).values;
        r.rootColour = region(m_current).rootColour;
        r.tipColour = region(m_current).tipColour;
    }
    after.push_back(std::move(r));
    m_undoStack.push(
        new SetRegionsCommand(this, m_regions, m_soloId, std::move(after), m_soloId, tr("Add region %1").arg(name)));
    setCurrentRegion(regionCount() - 1);
    return m_current;
}

void Document::removeRegion(int index)
{
    if (index < 0 || index >= regionCount())
        return;
    std::vector<GrowthRegion> after = m_regions;
    const std::uint32_t id = after[static_cast<std::size_t>(index)].id;
    after.erase(after.begin() + index);
    m_undoStack.push(new SetRegionsCommand(this, m_regions, m_soloId, std::move(after),
        m_soloId == id ? kNoSolo : m_soloId, tr("Remove region %1").arg(QString::fromStdString(region(index).name))));
}

void Document::renameRegion(int index, const QString& name)
{
    if (index < 0 || index >= regionCount() || name.trimmed().isEmpty() || name.toStdString() == region(index).name)
        return;
    std::vector<GrowthRegion> after = m_regions;
    after[static_cast<std::size_t>(index)].name = name.trimmed().toStdString();
    m_undoStack.push(new SetRegionsCommand(
        this, m_regions, m_soloId, std::move(after), m_soloId, tr("Rename region to %1").arg(name.trimmed())));
}

void Document::moveRegion(int from, int to)
{
    if (from < 0 || from >= regionCount() || to < 0 || to >= regionCount() || from == to)
        return;
    std::vector<GrowthRegion> after = m_regions;
    GrowthRegion moved = std::move(after[static_cast<std::size_t>(from)]);
    after.erase(after.begin() + from);
    after.insert(after.begin() + to, std::move(moved));
    const bool wasCurrent = m_current == from;
    m_undoStack.push(new SetRegionsCommand(this, m_regions, m_soloId, std::move(after), m_soloId,
        tr("Move region %1").arg(QString::fromStdString(region(from).name))));
    if (wasCurrent)
        setCurrentRegion(to);
}

void Document::setRegionVisible(int index, bool visible)
{
    if (index < 0 || index >= regionCount() || region(index).visible == visible)
        return;
    std::vector<GrowthRegion> after = m_regions;
    after[static_cast<std::size_t>(index)].visible = visible;
    const QString name = QString::fromStdString(region(index).name);
    m_undoStack.push(new SetRegionsCommand(this, m_regions, m_soloId, std::move(after), m_soloId,
        visible ? tr("Show region %1").arg(name) : tr("Hide region %1").arg(name)));
}

void Document::setSoloRegion(std::uint32_t id)
{
    if (id != kNoSolo && indexOfRegion(id) < 0)
        return;
    if (id == m_soloId)
        return;
    const QString text = id == kNoSolo
        ? tr("End solo")
        : tr("Solo region %1").arg(QString::fromStdString(region(indexOfRegion(id)).name));
    m_undoStack.push(new SetRegionsCommand(this, m_regions, m_soloId, m_regions, id, text));
}

void Document::setRegionColours(int index, const glm::vec3& root, const glm::vec3& tip)
{
    if (index < 0 || index >= regionCount())
        return;
    const glm::vec3 r = glm::clamp(root, glm::vec3(0.0f), glm::vec3(1.0f));
    const glm::vec3 t = glm::clamp(tip, glm::vec3(0.0f), glm::vec3(1.0f));
    if (region(index).rootColour == r && region(index).tipColour == t)
        return;
    std::vector<GrowthRegion> after = m_regions;
    after[static_cast<std::size_t>(index)].rootColour = r;
    after[static_cast<std::size_t>(index)].tipColour = t;
    m_undoStack.push(new SetRegionsCommand(this, m_regions, m_soloId, std::move(after), m_soloId,
        tr("Colour region %1").arg(QString::fromStdString(region(index).name))));
}

// --- Strokes ----------------------------------------------------------------------------------

void Document::beginStroke()
{
    if (m_current < 0)
        return;
    m_strokeRegion = m_current;
    m_strokeBefore = region(m_current).weights;
}

std::vector<float>& Document::strokeWeights()
{
    static std::vector<float> none;
    if (m_strokeRegion < 0)
        return none;
    return m_regions[static_cast<std::size_t>(m_strokeRegion)].weights.forWrite();
}

void Document::strokeUpdated()
{
    if (m_strokeRegion >= 0)
        emit regionWeightsChanged(m_regions[static_cast<std::size_t>(m_strokeRegion)].id);
}

void Document::endStroke(const QString& text)
{
    if (m_strokeRegion < 0)
        return;
    const GrowthRegion& r = m_regions[static_cast<std::size_t>(m_strokeRegion)];
    std::vector<std::uint32_t> vertices;
    std::vector<float> before, after;
    for (std::size_t i = 0; i < r.weights.size(); ++i)
        if (r.weights[i] != m_strokeBefore[i]) {
            vertices.push_back(static_cast<std::uint32_t>(i));
            before.push_back(m_strokeBefore[i]);
            after.push_back(r.weights[i]);
        }
    const std::uint32_t id = r.id;
    m_strokeRegion = -1;
    m_strokeBefore = {};
    if (!vertices.empty())
        m_undoStack.push(
            new PaintStrokeCommand(this, id, std::move(vertices), std::move(before), std::move(after), text));
}

void Document::replaceHead(TriangleMesh head, std::vector<float> growthWeights, const QString& name,
    const QString& source, const io::HeadPlacement& placement)
{
    std::vector<GrowthRegion> regions{ firstRegion(std::move(growthWeights)) };
    auto* command = new ReplaceHeadCommand(
        this, m_head, m_regions, std::make_shared<const HeadModel>(std::move(head)), std::move(regions), name);
    command->setOrigins({ m_headSource, m_headPlacement }, { source, placement });
    if (m_style->empty()) {
        m_undoStack.push(command);
        return;
    }
    // The salon edits name strands of this head's groom: a new head starts without them (and undo
    // brings them back with the old head).
    m_undoStack.beginMacro(command->text());
    StyleChanges before, after;
    for (const auto& [id, style] : *m_style) {
        before[id] = style;
        after[id] = std::nullopt;
    }
    m_undoStack.push(new StyleStrokeCommand(this, std::move(before), std::move(after), command->text(), false));
    m_undoStack.push(command);
    m_undoStack.endMacro();
}

void Document::applyPreset(const io::Preset& preset)
{
    std::vector<GrowthRegion> after = m_regions;
    for (std::size_t i = 0; i < after.size() && !preset.regions.empty(); ++i) {
        const io::RegionLook& look = preset.regions[std::min(i, preset.regions.size() - 1)];
        for (const ParameterInfo& p : allParameters())
            if (p.group == ParamGroup::Wisp)
                after[i].values.set(p.id, look.wisp.get(p.id));
        after[i].rootColour = look.rootColour;
        after[i].tipColour = look.tipColour;
    }
    ParameterValues parameters = m_parameters;
    for (const ParameterInfo& p : allParameters())
        if (p.group != ParamGroup::Wisp)
            parameters.set(p.id, preset.parameters.get(p.id));
    const QString text = tr("Apply preset %1").arg(QString::fromStdString(preset.name));
    HeadMotion motion = m_motion; // the preset's procedural motion, if it has one; keys stay
    motion.setProcedural(preset.motion);
    const bool withMotion
        = preset.motion.kind != MotionKind::None && motion.validate().empty() && !(motion == m_motion);
    if (withMotion)
        m_undoStack.beginMacro(text); // one undo step for the look and the motion
    m_undoStack.push(new ApplyLookCommand(this, m_parameters, m_regions, parameters, std::move(after), text));
    if (withMotion) {
        setHeadMotion(std::move(motion), text);
        m_undoStack.endMacro();
    }
}

io::Preset Document::toPreset(const QString& name) const
{
    io::Preset preset;
    preset.name = name.toStdString();
    preset.parameters = m_parameters;
    preset.motion = m_motion.procedural(); // none: the preset leaves the head's motion alone
    for (const GrowthRegion& r : m_regions)
        preset.regions.push_back({ r.name, r.values, r.rootColour, r.tipColour });
    return preset;
}

int Document::addImportedHair(std::shared_ptr<const HairCurves> strands, const QString& name)
{
    std::vector<GrowthRegion> after = m_regions;
    GrowthRegion r;
    r.id = nextRegionId();
    r.name = name.toStdString();
    r.weights.assign(head().positions.size(), 0.0f);
    r.importedStrands = std::move(strands);
    after.push_back(std::move(r));
    m_undoStack.push(
        new SetRegionsCommand(this, m_regions, m_soloId, std::move(after), m_soloId, tr("Import hair %1").arg(name)));
    setCurrentRegion(regionCount() - 1);
    return m_current;
}

io::Project Document::toProject() const
{
    io::Project p;
    p.head = head();
    p.headSource = m_headSource.toStdString();
    p.headEmbedded = true; // a project opens even when the head file has moved
    p.headImportScale = m_headPlacement.scale;
    p.headImportOffset = m_headPlacement.offset;
    p.headImportUp = m_headPlacement.up;
    p.headImportFront = m_headPlacement.front;
    p.parameters = m_parameters;
    p.regions = m_regions;
    p.soloRegion = m_soloId;
    p.style = *m_style;
    p.motion = m_motion;
    p.timeline = m_timeline;
    return p;
}

void Document::loadProject(io::Project project)
{
    m_undoStack.clear();
    m_headSource = QString::fromStdString(project.headSource);
    m_headPlacement = {};
    m_headPlacement.scale = project.headImportScale;
    m_headPlacement.offset = project.headImportOffset;
    m_headPlacement.up = project.headImportUp;
    m_headPlacement.front = project.headImportFront;
    m_parameters = project.parameters;
    m_soloId = kNoSolo;
    m_styleStroke.reset();
    m_styleBefore.reset();
    m_style = std::make_shared<const StyleEdits>(std::move(project.style));
    m_motion = std::move(project.motion);
    m_timeline = project.timeline;
    applyHead(std::make_shared<const HeadModel>(std::move(project.head)), std::move(project.regions));
    if (project.soloRegion != kNoSolo && indexOfRegion(project.soloRegion) >= 0)
        m_soloId = project.soloRegion;
    emit parametersReplaced();
    emit regionsChanged();
    emit styleChanged();
    emit headMotionChanged();
    emit timelineChanged();
    m_undoStack.setClean();
}

void Document::reset()
{
    io::Project fresh;
    DefaultHead d = makeDefaultHead();
    fresh.head = std::move(d.mesh);
    fresh.regions.push_back(firstRegion(std::move(d.growthWeights)));
    loadProject(std::move(fresh));
}

// --- Head motion and timeline --------------------------------------------------------------------

QString Document::setHeadMotion(HeadMotion motion, const QString& text)
{
    if (const std::string error = motion.validate(); !error.empty())
        return QString::fromStdString(error);
    if (motion == m_motion)
        return {};
    m_undoStack.push(new SetHeadMotionCommand(this, m_motion, std::move(motion), text));
    return {};
}

QString Document::setTimeline(const BakeRange& range, const QString& text)
{
    if (const std::string error = validateBakeRange(range); !error.empty())
        return QString::fromStdString(error);
    if (range == m_timeline)
        return {};
    m_undoStack.push(new SetTimelineCommand(this, m_timeline, range, text));
    return {};
}

void Document::applyHeadMotion(const HeadMotion& motion)
{
    m_motion = motion;
    emit headMotionChanged();
}

void Document::applyTimeline(const BakeRange& range)
{
    m_timeline = range;
    emit timelineChanged();
}

// --- Salon edits ---------------------------------------------------------------------------------

void Document::beginStyleStroke()
{
    if (m_styleStroke)
        endStyleStroke(tr("Style"));
    m_styleBefore = m_style;
    m_styleStroke = *m_style;
}

StyleEdits& Document::strokeStyle()
{
    if (!m_styleStroke)
        beginStyleStroke();
    return *m_styleStroke;
}

void Document::styleStrokeUpdated()
{
    if (!m_styleStroke)
        return;
    m_style = std::make_shared<const StyleEdits>(*m_styleStroke);
    emit styleChanged();
}

int Document::endStyleStroke(const QString& text)
{
    if (!m_styleStroke)
        return 0;
    // Edits that change nothing are dropped, so "no edit" has one form; an edit the project file
    // would refuse (a tool's bug) is not kept, so the work can always be saved.
    std::erase_if(*m_styleStroke, [](const auto& entry) { return entry.second.isDefault(); });
    for (auto it = m_styleStroke->begin(); it != m_styleStroke->end();) {
        if (validateStrandStyle(it->first, it->second).empty()) {
            ++it;
            continue;
        }
        const auto before = m_styleBefore->find(it->first);
        if (before != m_styleBefore->end())
            (it++)->second = before->second;
        else
            it = m_styleStroke->erase(it);
    }
    m_style = std::make_shared<const StyleEdits>(std::move(*m_styleStroke));
    m_styleStroke.reset();
    const StyleEdits& before = *m_styleBefore;
    const StyleEdits& after = *m_style;
    StyleChanges undo, redo;
    auto note = [&](std::uint64_t id) {
        const auto b = before.find(id);
        const auto a = after.find(id);
        const std::optional<StrandStyle> was = b == before.end() ? std::nullopt : std::optional(b->second);
        const std::optional<StrandStyle> now = a == after.end() ? std::nullopt : std::optional(a->second);
        if (was != now) {
            undo[id] = was;
            redo[id] = now;
        }
    };
    for (const auto& entry : before)
        note(entry.first);
    for (const auto& entry : after)
        if (!before.count(entry.first))
            note(entry.first);
    m_styleBefore.reset();
    emit styleChanged();
    const int changed = static_cast<int>(undo.size());
    if (!undo.empty())
        m_undoStack.push(new StyleStrokeCommand(this, std::move(undo), std::move(redo), text, true));
    return changed;
}

// --- For commands -----------------------------------------------------------------------------

void Document::applyStyleChanges(const StyleChanges& changes)
{
    StyleEdits edits = *m_style;
    for (const auto& [id, style] : changes) {
        if (style && !style->isDefault())
            edits[id] = *style;
        else
            edits.erase(id);
    }
    m_style = std::make_shared<const StyleEdits>(std::move(edits));
    emit styleChanged();
}

void Document::applyParameter(Param id, double value)
{
    if (m_parameters.get(id) == value)
        return;
    m_parameters.set(id, value);
    emit parameterChanged(id);
}

void Document::applyRegionParameter(std::uint32_t regionId, Param id, double value)
{
    const int index = indexOfRegion(regionId);
    if (index < 0 || region(index).values.get(id) == value)
        return;
    m_regions[static_cast<std::size_t>(index)].values.set(id, value);
    emit regionParameterChanged(index, id);
}

void Document::applyRegions(std::vector<GrowthRegion> regions, std::uint32_t soloId)
{
    const std::uint32_t currentId = m_current >= 0 ? region(m_current).id : kNoSolo;
    m_regions = std::move(regions);
    m_soloId = soloId;
    // The current index is valid before anyone hears of the change; its own signal follows.
    const int stillThere = indexOfRegion(currentId);
    const int current = m_regions.empty() ? -1
        : stillThere >= 0                 ? stillThere
                                          : std::min(std::max(m_current, 0), regionCount() - 1);
    const bool currentMoved = current != m_current;
    m_current = current;
    emit regionsChanged();
    if (currentMoved)
        emit currentRegionChanged(m_current);
}

void Document::applyRegionWeights(
    std::uint32_t regionId, const std::vector<std::uint32_t>& vertices, const std::vector<float>& values)
{
    const int index = indexOfRegion(regionId);
    if (index < 0)
        return;
    std::vector<float>& weights = m_regions[static_cast<std::size_t>(index)].weights.forWrite();
    for (std::size_t i = 0; i < vertices.size(); ++i)
        if (vertices[i] < weights.size())
            weights[vertices[i]] = values[i];
    emit regionWeightsChanged(regionId);
}

void Document::applyHeadOrigin(const QString& source, const io::HeadPlacement& placement)
{
    m_headSource = source;
    m_headPlacement = placement;
}

void Document::applyLook(const ParameterValues& parameters, std::vector<GrowthRegion> regions)
{
    m_parameters = parameters;
    emit parametersReplaced();
    applyRegions(std::move(regions), m_soloId);
}

void Document::applyHead(HeadModelPtr head, std::vector<GrowthRegion> regions)
{
    m_head = std::move(head);
    m_regions = std::move(regions);
    m_soloId = kNoSolo;
    m_current = m_regions.empty() ? -1 : 0;
    emit headChanged();
    emit regionsChanged();
    emit currentRegionChanged(m_current);
}

} // namespace wisp
