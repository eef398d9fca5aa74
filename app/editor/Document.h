#pragma once
// What the artist is editing: the head, its growth map and every parameter. It changes only through
// undoable commands on its QUndoStack, so every edit can be undone and one gesture is one step.
//
// Thread: GUI.

#include "sim/Parameters.h"
#include "sim/TriangleMesh.h"

#include <QObject>
#include <QUndoStack>

#include <vector>

namespace wisp {

class Document : public QObject {
    Q_OBJECT
public:
    explicit Document(QObject* parent = nullptr);  // starts on the built-in head and its growth map

    const TriangleMesh& head() const { return m_head; }
    const std::vector<float>& growthWeights() const { return m_growthWeights; }
    const ParameterValues& parameters() const { return m_parameters; }
    QUndoStack* undoStack() { return &m_undoStack; }

    // The artist's edit of one parameter, as an undo step. While `dragging`, successive edits of
    // the same parameter merge into one step; the edit with dragging == false closes it.
    // Returns the refusal message for an invalid value (nothing is pushed then).
    QString editParameter(Param id, double value, bool dragging);

    // Replaces the head (and its growth map) as one undo step.
    void replaceHead(TriangleMesh head, std::vector<float> growthWeights, const QString& name);

    // For commands only: applies without touching the undo stack.
    void applyParameter(Param id, double value);
    void applyHead(TriangleMesh head, std::vector<float> growthWeights);

signals:
    void parameterChanged(wisp::Param id);
    void headChanged();

private:
    TriangleMesh m_head;
    std::vector<float> m_growthWeights;
    ParameterValues m_parameters;
    QUndoStack m_undoStack;
};

}  // namespace wisp
