#pragma once
// The wisp panel: the current growth region's own parameters (the registry's Wisp group: density,
// wisp size, clumping, length, curl, stiffness scale) and its hair colour, root to tip.
//
// Every change goes to the Document as an undoable edit of that region; what the panel shows
// always comes back from the document (after an edit, undo, redo, another current region or a new
// head), shown without emitting edits again.
//
// Thread: GUI.

#include "sim/params/Parameters.h"

#include <QWidget>

#include <cstdint>

class QColor;
class QLabel;
class QPushButton;

namespace wisp {

class Document;
class ParameterPanel;

class WispPanel : public QWidget {
    Q_OBJECT
public:
    explicit WispPanel(Document* document, QWidget* parent = nullptr);

    ParameterPanel* parameterPanel() const { return m_parameters; }
    QPushButton* rootColourButton() const { return m_rootColour; }
    QPushButton* tipColourButton() const { return m_tipColour; }
    QLabel* titleLabel() const { return m_title; }

signals:
    // The document refused an edit (a value outside the parameter's range); for the status bar.
    void editRefused(const QString& message);

private:
    enum class HairEnd { Root, Tip };

    QWidget* createColourRow();
    void connectDocument();

    // Document → widgets.
    void refresh();
    void showValues();
    void showColours();
    int validCurrent() const; // the document's current region, or -1 while it has none

    // Widgets → document.
    void parameterEdited(Param id, double value, bool dragging);
    void pickColour(HairEnd end);
    void applyColour(std::uint32_t regionId, HairEnd end, const QColor& colour);

    Document* m_document;
    QLabel* m_title = nullptr;
    ParameterPanel* m_parameters = nullptr;
    QPushButton* m_rootColour = nullptr;
    QPushButton* m_tipColour = nullptr;
};

} // namespace wisp
