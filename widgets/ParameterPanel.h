#pragma once
// A panel of parameter rows, each a slider with a spin box (SliderRow: the registry's slider scale,
// Shift + drag fine, Ctrl + drag snaps), its unit and a tooltip, all taken from the parameter
// registry (sim/params/Parameters.h): panels state no range, default, scale or help of their own.
//
// Thread: GUI.

#include "sim/params/Parameters.h"

#include <QWidget>

#include <vector>

class QDoubleSpinBox;
class QSlider;
class QCheckBox;

namespace wisp {

class SliderRow;

class ParameterPanel : public QWidget {
    Q_OBJECT
public:
    ParameterPanel(std::vector<Param> parameters, QWidget* parent = nullptr);

    // Shows these values without emitting anything (for undo, presets, other panels).
    void setValues(const ParameterValues& values);
    double value(Param id) const;

    QSlider* sliderFor(Param id) const; // for tests and keyboard focus
    QDoubleSpinBox* spinBoxFor(Param id) const; // null for toggles; in the shown unit (displayUnit)
    QCheckBox* checkBoxFor(Param id) const; // null for numbers
    SliderRow* rowFor(Param id) const; // null for toggles

signals:
    // The artist changed a value. `dragging` is true while a slider is held, so that one drag can
    // become one undo step; the last call of a gesture has dragging == false.
    void valueEdited(wisp::Param id, double value, bool dragging);

private:
    struct Row {
        Param id;
        SliderRow* numbers = nullptr;
        QCheckBox* check = nullptr;
        double scale = 1.0; // the row shows the value times this (ParameterInfo::displayScale)
    };
    const Row* find(Param id) const;

    std::vector<Row> m_rows;
    bool m_updating = false;
};

} // namespace wisp
