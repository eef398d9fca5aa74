#pragma once
// The salon brushes' panel: one button per styling tool (the same actions as the Tools menu and
// the Styling toolbar, with their shortcuts), the perm's curl, and a line on how the chosen tool
// is used. Radius, strength, falloff and mirror are the Brush panel's, shared with painting.
//
// Thread: GUI.

#include "app/editor/StyleTool.h"

#include <QWidget>

#include <map>

class QAction;
class QActionGroup;
class QDoubleSpinBox;
class QLabel;

namespace wisp {

class SliderRow;

class StylePanel : public QWidget {
    Q_OBJECT
public:
    explicit StylePanel(StyleTool* tool, QWidget* parent = nullptr);

    // Checkable, one per brush, in StyleBrush order; checking one selects it, unchecking it ends styling.
    const std::map<StyleBrush, QAction*>& brushActions() const { return m_actions; }
    QAction* actionFor(StyleBrush brush) const { return m_actions.at(brush); }
    QDoubleSpinBox* curlRadiusBox() const;
    QDoubleSpinBox* curlTurnsBox() const;

private:
    void showBrush(std::optional<StyleBrush> brush);

    StyleTool* m_tool;
    std::map<StyleBrush, QAction*> m_actions;
    SliderRow* m_curlRadius = nullptr;
    SliderRow* m_curlTurns = nullptr;
    QLabel* m_hint = nullptr;
};

} // namespace wisp
