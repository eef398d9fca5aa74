#include "widgets/SliderRow.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QMouseEvent>
#include <QSignalBlocker>

#include <algorithm>
#include <cmath>

namespace wisp {

DragSlider::DragSlider(QWidget* parent)
    : QSlider(Qt::Horizontal, parent)
{
    setRange(0, kSteps);
    setPageStep(kSteps / 20);
}

double DragSlider::fractionPerPixel() const
{
    return 1.0 / std::max(static_cast<double>(width()), kMinTravelPixels);
}

void DragSlider::mousePressEvent(QMouseEvent* event)
{
    if (event->button() != Qt::LeftButton) {
        QSlider::mousePressEvent(event);
        return;
    }
    // No jump to where the groove was clicked: the drag moves the value from where it is.
    m_dragging = true;
    m_lastX = event->position().x();
    m_fraction = static_cast<double>(value()) / kSteps;
    setSliderDown(true);
    event->accept();
}

void DragSlider::mouseMoveEvent(QMouseEvent* event)
{
    if (!m_dragging) {
        QSlider::mouseMoveEvent(event);
        return;
    }
    const double dx = event->position().x() - m_lastX;
    m_lastX = event->position().x();
    const double fine = (event->modifiers() & Qt::ShiftModifier) ? kFineFactor : 1.0;
    m_fraction = std::clamp(m_fraction + dx * fractionPerPixel() * fine, 0.0, 1.0);
    emit dragged(m_fraction, event->modifiers());
    event->accept();
}

void DragSlider::mouseReleaseEvent(QMouseEvent* event)
{
    if (!m_dragging || event->button() != Qt::LeftButton) {
        QSlider::mouseReleaseEvent(event);
        return;
    }
    m_dragging = false;
    setSliderDown(false);
    emit dragFinished(event->modifiers());
    event->accept();
}

SliderRow::SliderRow(SliderRowSpec spec, QWidget* parent)
    : QWidget(parent)
    , m_spec(std::move(spec))
{
    auto* h = new QHBoxLayout(this);
    h->setContentsMargins(0, 0, 0, 0);
    m_slider = new DragSlider(this);
    m_slider->setToolTip(m_spec.tooltip);
    m_slider->setObjectName(m_spec.objectName);
    m_spin = new QDoubleSpinBox(this);
    m_spin->setRange(m_spec.range.minimum, m_spec.range.maximum);
    m_spin->setDecimals(m_spec.decimals);
    m_spin->setSingleStep(m_spec.singleStep);
    m_spin->setKeyboardTracking(false);
    m_spin->setToolTip(m_spec.tooltip);
    m_spin->setSuffix(m_spec.suffix);
    m_spin->setMinimumWidth(110);
    h->addWidget(m_slider, 1);
    h->addWidget(m_spin);

    // A drag: the value at the dragged fraction (snapped with Ctrl), shown in the spin box.
    connect(m_slider, &DragSlider::dragged, this, [this](double fraction, Qt::KeyboardModifiers modifiers) {
        double v = sliderValueAt(m_spec.range, fraction);
        if (modifiers & Qt::ControlModifier)
            v = snappedSliderValue(m_spec.range, v);
        v = shown(v);
        if (v == m_spin->value())
            return;
        {
            const QSignalBlocker block(m_spin);
            m_spin->setValue(v);
        }
        showOnSlider(v);
        emit valueEdited(v, true);
    });
    connect(m_slider, &DragSlider::dragFinished, this, [this] { emit valueEdited(m_spin->value(), false); });
    // Keys and the wheel on the slider.
    connect(m_slider, &QSlider::valueChanged, this, [this](int position) {
        if (m_updating || m_slider->isSliderDown())
            return;
        const double v = shown(sliderValueAt(m_spec.range, static_cast<double>(position) / DragSlider::kSteps));
        {
            const QSignalBlocker block(m_spin);
            m_spin->setValue(v);
        }
        emit valueEdited(v, false);
    });
    connect(m_spin, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (m_updating)
            return;
        showOnSlider(v);
        emit valueEdited(v, false);
    });
}

double SliderRow::shown(double value) const
{
    const double scale = std::pow(10.0, m_spec.decimals);
    return std::clamp(std::round(value * scale) / scale, m_spec.range.minimum, m_spec.range.maximum);
}

void SliderRow::showOnSlider(double value)
{
    const bool was = m_updating;
    m_updating = true;
    {
        const QSignalBlocker block(m_slider);
        m_slider->setValue(static_cast<int>(std::lround(sliderFractionOf(m_spec.range, value) * DragSlider::kSteps)));
    }
    m_updating = was;
}

void SliderRow::setValue(double value)
{
    m_updating = true;
    {
        const QSignalBlocker block(m_spin);
        m_spin->setValue(value);
    }
    if (!m_slider->isSliderDown())
        showOnSlider(value);
    m_updating = false;
}

double SliderRow::value() const
{
    return m_spin->value();
}

} // namespace wisp
