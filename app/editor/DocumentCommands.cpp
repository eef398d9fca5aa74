#include "app/editor/DocumentCommands.h"

#include "app/editor/Document.h"

namespace wisp {

SetParameterCommand::SetParameterCommand(Document* document, Param id, double oldValue, double newValue, bool open)
    : m_document(document), m_param(id), m_old(oldValue), m_new(newValue), m_open(open)
{
    const ParameterInfo& p = parameterInfo(id);
    setText(QStringLiteral("Set %1 to %2").arg(QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size()))).arg(newValue));
}

void SetParameterCommand::undo() { m_document->applyParameter(m_param, m_old); }
void SetParameterCommand::redo()
{
    m_document->applyParameter(m_param, m_new);
    setObsolete(m_new == m_old);  // a gesture that ends where it began leaves no undo step
}

bool SetParameterCommand::mergeWith(const QUndoCommand* other)
{
    const auto* next = static_cast<const SetParameterCommand*>(other);  // same id() means same class and parameter
    if (!m_open || next->m_param != m_param)
        return false;
    m_new = next->m_new;
    m_open = next->m_open;
    setObsolete(m_new == m_old);
    const ParameterInfo& p = parameterInfo(m_param);
    setText(QStringLiteral("Set %1 to %2").arg(QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size()))).arg(m_new));
    return true;
}

ReplaceHeadCommand::ReplaceHeadCommand(Document* document, TriangleMesh oldHead, std::vector<float> oldWeights,
                                       TriangleMesh newHead, std::vector<float> newWeights, const QString& name)
    : m_document(document), m_oldHead(std::move(oldHead)), m_newHead(std::move(newHead)),
      m_oldWeights(std::move(oldWeights)), m_newWeights(std::move(newWeights))
{
    setText(QStringLiteral("Load head %1").arg(name));
}

void ReplaceHeadCommand::undo() { m_document->applyHead(m_oldHead, m_oldWeights); }
void ReplaceHeadCommand::redo() { m_document->applyHead(m_newHead, m_newWeights); }

}  // namespace wisp
