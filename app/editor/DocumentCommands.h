#pragma once
// One small QUndoCommand per kind of edit (as Tiled does), merged while a slider or stroke is dragged.

#include "sim/Parameters.h"
#include "sim/TriangleMesh.h"

#include <QUndoCommand>

#include <vector>

namespace wisp {

class Document;

class SetParameterCommand : public QUndoCommand {
public:
    SetParameterCommand(Document* document, Param id, double oldValue, double newValue, bool open);
    void undo() override;
    void redo() override;
    int id() const override { return kMergeIdBase + static_cast<int>(m_param); }
    bool mergeWith(const QUndoCommand* other) override;

    static constexpr int kMergeIdBase = 1000;

private:
    Document* m_document;
    Param m_param;
    double m_old;
    double m_new;
    bool m_open;  // the gesture is still going on: the next edit of this parameter merges here
};

class ReplaceHeadCommand : public QUndoCommand {
public:
    ReplaceHeadCommand(Document* document, TriangleMesh oldHead, std::vector<float> oldWeights, TriangleMesh newHead,
                       std::vector<float> newWeights, const QString& name);
    void undo() override;
    void redo() override;

private:
    Document* m_document;
    TriangleMesh m_oldHead, m_newHead;
    std::vector<float> m_oldWeights, m_newWeights;
};

}  // namespace wisp
