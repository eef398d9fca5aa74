#include "app/editor/DocumentCommands.h"

#include "app/editor/Document.h"

namespace wisp {

namespace {

QString labelOf(Param id)
{
    const ParameterInfo& p = parameterInfo(id);
    return QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size()));
}

} // namespace

SetParameterCommand::SetParameterCommand(Document* document, Param id, double oldValue, double newValue, bool open)
    : m_document(document)
    , m_param(id)
    , m_old(oldValue)
    , m_new(newValue)
    , m_open(open)
{
    setText(QStringLiteral("Set %1 to %2").arg(labelOf(id)).arg(newValue));
}

void SetParameterCommand::undo()
{
    m_document->applyParameter(m_param, m_old);
}
void SetParameterCommand::redo()
{
    m_document->applyParameter(m_param, m_new);
    setObsolete(m_new == m_old); // a gesture that ends where it began leaves no undo step
}

bool SetParameterCommand::mergeWith(const QUndoCommand* other)
{
    const auto* next = static_cast<const SetParameterCommand*>(other); // same id() means same class and parameter
    if (!m_open || next->m_param != m_param)
        return false;
    m_new = next->m_new;
    m_open = next->m_open;
    setObsolete(m_new == m_old);
    setText(QStringLiteral("Set %1 to %2").arg(labelOf(m_param)).arg(m_new));
    return true;
}

SetRegionParameterCommand::SetRegionParameterCommand(Document* document, std::uint32_t regionId,
    const QString& regionName, Param id, double oldValue, double newValue, bool open)
    : m_document(document)
    , m_region(regionId)
    , m_regionName(regionName)
    , m_param(id)
    , m_old(oldValue)
    , m_new(newValue)
    , m_open(open)
{
    updateText();
}

void SetRegionParameterCommand::updateText()
{
    setText(QStringLiteral("Set %1 of %2 to %3").arg(labelOf(m_param), m_regionName).arg(m_new));
}

void SetRegionParameterCommand::undo()
{
    m_document->applyRegionParameter(m_region, m_param, m_old);
}
void SetRegionParameterCommand::redo()
{
    m_document->applyRegionParameter(m_region, m_param, m_new);
    setObsolete(m_new == m_old);
}

bool SetRegionParameterCommand::mergeWith(const QUndoCommand* other)
{
    const auto* next = static_cast<const SetRegionParameterCommand*>(other);
    if (!m_open || next->m_param != m_param || next->m_region != m_region)
        return false;
    m_new = next->m_new;
    m_open = next->m_open;
    setObsolete(m_new == m_old);
    updateText();
    return true;
}

SetRegionsCommand::SetRegionsCommand(Document* document, std::vector<GrowthRegion> before, std::uint32_t soloBefore,
    std::vector<GrowthRegion> after, std::uint32_t soloAfter, const QString& text)
    : m_document(document)
    , m_before(std::move(before))
    , m_after(std::move(after))
    , m_soloBefore(soloBefore)
    , m_soloAfter(soloAfter)
{
    setText(text);
}

void SetRegionsCommand::undo()
{
    m_document->applyRegions(m_before, m_soloBefore);
}
void SetRegionsCommand::redo()
{
    m_document->applyRegions(m_after, m_soloAfter);
}

PaintStrokeCommand::PaintStrokeCommand(Document* document, std::uint32_t regionId, std::vector<std::uint32_t> vertices,
    std::vector<float> before, std::vector<float> after, const QString& text)
    : m_document(document)
    , m_region(regionId)
    , m_vertices(std::move(vertices))
    , m_before(std::move(before))
    , m_after(std::move(after))
{
    setText(text);
}

void PaintStrokeCommand::undo()
{
    m_document->applyRegionWeights(m_region, m_vertices, m_before);
    m_applied = false;
}

void PaintStrokeCommand::redo()
{
    if (m_applied) // pushed after the stroke was painted live: nothing to do the first time
        return;
    m_document->applyRegionWeights(m_region, m_vertices, m_after);
    m_applied = true;
}

StyleStrokeCommand::StyleStrokeCommand(Document* document, std::map<std::uint64_t, std::optional<StrandStyle>> before,
    std::map<std::uint64_t, std::optional<StrandStyle>> after, const QString& text, bool applied)
    : m_document(document)
    , m_before(std::move(before))
    , m_after(std::move(after))
    , m_applied(applied)
{
    setText(text);
}

void StyleStrokeCommand::undo()
{
    m_document->applyStyleChanges(m_before);
    m_applied = false;
}

void StyleStrokeCommand::redo()
{
    if (m_applied)
        return;
    m_document->applyStyleChanges(m_after);
    m_applied = true;
}

ReplaceHeadCommand::ReplaceHeadCommand(Document* document, HeadModelPtr oldHead, std::vector<GrowthRegion> oldRegions,
    HeadModelPtr newHead, std::vector<GrowthRegion> newRegions, const QString& name)
    : m_document(document)
    , m_oldHead(std::move(oldHead))
    , m_newHead(std::move(newHead))
    , m_oldRegions(std::move(oldRegions))
    , m_newRegions(std::move(newRegions))
{
    setText(QStringLiteral("Load head %1").arg(name));
}

void ReplaceHeadCommand::setOrigins(Origin before, Origin after)
{
    m_oldOrigin = std::move(before);
    m_newOrigin = std::move(after);
}

void ReplaceHeadCommand::undo()
{
    m_document->applyHeadOrigin(m_oldOrigin.source, m_oldOrigin.placement);
    m_document->applyHead(m_oldHead, m_oldRegions);
}

void ReplaceHeadCommand::redo()
{
    m_document->applyHeadOrigin(m_newOrigin.source, m_newOrigin.placement);
    m_document->applyHead(m_newHead, m_newRegions);
}

ApplyLookCommand::ApplyLookCommand(Document* document, ParameterValues parametersBefore,
    std::vector<GrowthRegion> regionsBefore, ParameterValues parametersAfter, std::vector<GrowthRegion> regionsAfter,
    const QString& text)
    : m_document(document)
    , m_parametersBefore(std::move(parametersBefore))
    , m_parametersAfter(std::move(parametersAfter))
    , m_regionsBefore(std::move(regionsBefore))
    , m_regionsAfter(std::move(regionsAfter))
{
    setText(text);
}

void ApplyLookCommand::undo()
{
    m_document->applyLook(m_parametersBefore, m_regionsBefore);
}
void ApplyLookCommand::redo()
{
    m_document->applyLook(m_parametersAfter, m_regionsAfter);
}

SetHeadMotionCommand::SetHeadMotionCommand(Document* document, HeadMotion before, HeadMotion after, const QString& text)
    : m_document(document)
    , m_before(std::move(before))
    , m_after(std::move(after))
{
    setText(text);
}

void SetHeadMotionCommand::undo()
{
    m_document->applyHeadMotion(m_before);
}

void SetHeadMotionCommand::redo()
{
    m_document->applyHeadMotion(m_after);
}

SetTimelineCommand::SetTimelineCommand(Document* document, BakeRange before, BakeRange after, const QString& text)
    : m_document(document)
    , m_before(before)
    , m_after(after)
{
    setText(text);
}

void SetTimelineCommand::undo()
{
    m_document->applyTimeline(m_before);
}

void SetTimelineCommand::redo()
{
    m_document->applyTimeline(m_after);
}

} // namespace wisp
