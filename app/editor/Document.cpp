#include "app/editor/Document.h"

#include "app/editor/DocumentCommands.h"
#include "sim/DefaultHead.h"

namespace wisp {

Document::Document(QObject* parent) : QObject(parent)
{
    DefaultHead d = makeDefaultHead();
    m_head = std::move(d.mesh);
    m_growthWeights = std::move(d.growthWeights);
}

QString Document::editParameter(Param id, double value, bool dragging)
{
    ParameterValues check = m_parameters;
    if (std::string error = check.set(id, value); !error.empty())
        return QString::fromStdString(error);
    const double rounded = check.get(id);
    const double old = m_parameters.get(id);
    m_undoStack.push(new SetParameterCommand(this, id, old, rounded, dragging));
    return {};
}

void Document::replaceHead(TriangleMesh head, std::vector<float> growthWeights, const QString& name)
{
    m_undoStack.push(new ReplaceHeadCommand(this, m_head, m_growthWeights, std::move(head), std::move(growthWeights), name));
}

void Document::applyParameter(Param id, double value)
{
    if (m_parameters.get(id) == value)
        return;
    m_parameters.set(id, value);
    emit parameterChanged(id);
}

void Document::applyHead(TriangleMesh head, std::vector<float> growthWeights)
{
    m_head = std::move(head);
    m_growthWeights = std::move(growthWeights);
    emit headChanged();
}

}  // namespace wisp
