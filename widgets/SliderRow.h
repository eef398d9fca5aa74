#pragma once
// One row of a settings panel: a slider and a spin box showing the same value. The slider spreads
// its range as the registry says (SliderRange in sim/params/Parameters.h: linear, log or centred); the spin
// box gives the exact value. Every panel's numbers use it: the parameter panels and the Brush panel.
//
// Dragging the slider is relative, as in Blender's number fields: pressing does not jump, and a
// pixel of mouse travel moves the slider by 1 / max(its width, kMinTravelPixels) of its travel, so
// a narrow dock does not make a slider coarse. Shift + drag moves kFineFactor as far (fine), Ctrl +
// drag snaps to round values (snappedSliderValue). The arrow keys and the wheel step as QSlider does.
//
// Thread: GUI.

#include "sim/params/Parameters.h"

#include <QSlider>
#include <QString>
#include <QWidget>

class QDoubleSpinBox;

namespace wisp {

// The slider of a SliderRow: reports relative drags by fraction of travel (0..1).
class DragSlider : public QSlider {
    Q_OBJECT
public:
    explicit DragSlider(QWidget* parent = nullptr);

    static constexpr int kSteps = 1000; // slider positions over the travel
    static constexpr double kMinTravelPixels = 600.0; // the whole range takes at least this much drag
    static constexpr double kFineFactor = 0.1; // Shift + drag

    // Fraction of travel per pixel of mouse movement now (without Shift).
    double fractionPerPixel() const;

signals:
    void dragged(double fraction, Qt::KeyboardModifiers modifiers); // while the button is held
    void dragFinished(Qt::KeyboardModifiers modifiers);

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;

private:
    bool m_dragging = false;
    double m_lastX = 0.0;
    double m_fraction = 0.0;
};

struct SliderRowSpec {
    SliderRange range;
    int decimals = 2;
    double singleStep = 0.01; // the spin box's arrows
    QString suffix; // " m/s²": the unit, after a space
    QString tooltip;
    QString objectName; // the slider's (the parameter's key)
};

class SliderRow : public QWidget {
    Q_OBJECT
public:
    explicit SliderRow(SliderRowSpec spec, QWidget* parent = nullptr);

    // Shows `value` without emitting anything.
    void setValue(double value);
    double value() const;
    const SliderRange& range() const { return m_spec.range; }

    DragSlider* slider() const { return m_slider; }
    QDoubleSpinBox* spinBox() const { return m_spin; }

signals:
    // The artist changed the value; `dragging` is true while the slider is held (one drag can be
    // one undo step); the last call of a gesture has dragging == false.
    void valueEdited(double value, bool dragging);

private:
    void showOnSlider(double value);
    double shown(double value) const; // as the spin box holds it (its decimals)

    SliderRowSpec m_spec;
    DragSlider* m_slider = nullptr;
    QDoubleSpinBox* m_spin = nullptr;
    bool m_updating = false;
};

} // namespace wisp
