#pragma once
// The growth brush's settings: on/off, mode, radius (cm), strength, falloff (slider-and-spin-box
// rows, as in the parameter panels), X-mirror, and whether
// the painted weights are shown on the head. It edits the PaintTool and follows it ([ and ] change
// the radius from the viewport).
//
// Thread: GUI.

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QPushButton;

namespace wisp {

class PaintTool;
class SliderRow;

class BrushPanel : public QWidget {
    Q_OBJECT
public:
    explicit BrushPanel(PaintTool* tool, QWidget* parent = nullptr);

    QPushButton* paintButton() const { return m_paint; }
    QComboBox* modeBox() const { return m_mode; }
    QDoubleSpinBox* radiusBox() const;
    QDoubleSpinBox* strengthBox() const;
    QDoubleSpinBox* falloffBox() const;
    SliderRow* radiusRow() const { return m_radius; }
    SliderRow* strengthRow() const { return m_strength; }
    SliderRow* falloffRow() const { return m_falloff; }
    QCheckBox* mirrorBox() const { return m_mirror; }
    QCheckBox* overlayBox() const { return m_overlay; }

signals:
    void showOverlayToggled(bool show);

private:
    void showSettings();

    PaintTool* m_tool;
    QPushButton* m_paint = nullptr;
    QComboBox* m_mode = nullptr;
    SliderRow* m_radius = nullptr;
    SliderRow* m_strength = nullptr;
    SliderRow* m_falloff = nullptr;
    QCheckBox* m_mirror = nullptr;
    QCheckBox* m_overlay = nullptr;
    bool m_updating = false;
};

} // namespace wisp
