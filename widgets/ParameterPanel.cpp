#include "widgets/ParameterPanel.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>

#include <cmath>

namespace wisp {

namespace {

int decimalsFor(const ParameterInfo& p)
{
    if (p.kind != ParamKind::Real)
        return 0;
    const double span = p.maximum - p.minimum;
    return span <= 0.1 ? 4 : span <= 2.0 ? 3 : 2;
}

QString tooltipFor(const ParameterInfo& p)
{
    QString unit = p.unit.empty() ? QString() : QStringLiteral(" ") + QString::fromUtf8(p.unit.data(), static_cast<int>(p.unit.size()));
    return QStringLiteral("<b>%1</b>%2<br>%3<br><small>%4 … %5, default %6</small>")
        .arg(QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size())),
             unit.isEmpty() ? QString() : QStringLiteral(" (%1)").arg(unit.trimmed()),
             QString::fromUtf8(p.help.data(), static_cast<int>(p.help.size())))
        .arg(p.minimum)
        .arg(p.maximum)
        .arg(p.defaultValue);
}

}  // namespace

ParameterPanel::ParameterPanel(std::vector<Param> parameters, QWidget* parent) : QWidget(parent)
{
    auto* form = new QFormLayout(this);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    for (Param id : parameters) {
        const ParameterInfo& p = parameterInfo(id);
        Row row{id};
        const QString tooltip = tooltipFor(p);
        auto* label = new QLabel(QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size())), this);
        label->setToolTip(tooltip);
        if (p.kind == ParamKind::Toggle) {
            row.check = new QCheckBox(this);
            row.check->setToolTip(tooltip);
            row.check->setObjectName(QString::fromUtf8(p.key.data(), static_cast<int>(p.key.size())));
            connect(row.check, &QCheckBox::toggled, this, [this, id](bool on) {
                if (!m_updating)
                    emit valueEdited(id, on ? 1.0 : 0.0, false);
            });
            form->addRow(label, row.check);
        } else {
            auto* line = new QWidget(this);
            auto* h = new QHBoxLayout(line);
            h->setContentsMargins(0, 0, 0, 0);
            row.slider = new QSlider(Qt::Horizontal, line);
            row.slider->setRange(0, kSliderSteps);
            row.slider->setToolTip(tooltip);
            row.slider->setObjectName(QString::fromUtf8(p.key.data(), static_cast<int>(p.key.size())));
            row.spin = new QDoubleSpinBox(line);
            row.spin->setRange(p.minimum, p.maximum);
            row.spin->setDecimals(decimalsFor(p));
            row.spin->setSingleStep(p.kind == ParamKind::Real ? (p.maximum - p.minimum) / 100.0 : 1.0);
            row.spin->setKeyboardTracking(false);
            row.spin->setToolTip(tooltip);
            if (!p.unit.empty())
                row.spin->setSuffix(QStringLiteral(" ") + QString::fromUtf8(p.unit.data(), static_cast<int>(p.unit.size())));
            row.spin->setMinimumWidth(110);
            h->addWidget(row.slider, 1);
            h->addWidget(row.spin);
            form->addRow(label, line);

            QSlider* slider = row.slider;
            QDoubleSpinBox* spin = row.spin;
            connect(slider, &QSlider::valueChanged, this, [this, id, spin](int position) {
                if (m_updating)
                    return;
                const double v = valueAt(id, position);
                {
                    const QSignalBlocker block(spin);
                    spin->setValue(v);
                }
                emit valueEdited(id, v, sliderFor(id)->isSliderDown());
            });
            connect(slider, &QSlider::sliderReleased, this, [this, id, slider] {
                if (!m_updating)
                    emit valueEdited(id, valueAt(id, slider->value()), false);
            });
            connect(spin, &QDoubleSpinBox::valueChanged, this, [this, id, slider](double v) {
                if (m_updating)
                    return;
                {
                    const QSignalBlocker block(slider);
                    slider->setValue(sliderPosition(id, v));
                }
                emit valueEdited(id, v, false);
            });
        }
        m_rows.push_back(row);
    }
    setValues(ParameterValues());
}

// Sliders are linear over the registry's range; the spin box gives the exact value.
int ParameterPanel::sliderPosition(Param id, double value) const
{
    const ParameterInfo& p = parameterInfo(id);
    const double t = (value - p.minimum) / (p.maximum - p.minimum);
    return static_cast<int>(std::lround(std::clamp(t, 0.0, 1.0) * kSliderSteps));
}

double ParameterPanel::valueAt(Param id, int position) const
{
    const ParameterInfo& p = parameterInfo(id);
    double v = p.minimum + (p.maximum - p.minimum) * static_cast<double>(position) / kSliderSteps;
    if (p.kind != ParamKind::Real)
        v = std::round(v);
    return std::clamp(v, p.minimum, p.maximum);
}

const ParameterPanel::Row* ParameterPanel::rowFor(Param id) const
{
    for (const Row& r : m_rows)
        if (r.id == id)
            return &r;
    return nullptr;
}

void ParameterPanel::showValue(const Row& row, double value)
{
    if (row.check) {
        row.check->setChecked(value != 0.0);
        return;
    }
    row.spin->setValue(value);
    if (!row.slider->isSliderDown())
        row.slider->setValue(sliderPosition(row.id, value));
}

void ParameterPanel::setValues(const ParameterValues& values)
{
    m_updating = true;
    for (const Row& row : m_rows)
        showValue(row, values.get(row.id));
    m_updating = false;
}

double ParameterPanel::value(Param id) const
{
    const Row* row = rowFor(id);
    if (!row)
        return 0.0;
    return row->check ? (row->check->isChecked() ? 1.0 : 0.0) : row->spin->value();
}

QSlider* ParameterPanel::sliderFor(Param id) const
{
    const Row* row = rowFor(id);
    return row ? row->slider : nullptr;
}

QDoubleSpinBox* ParameterPanel::spinBoxFor(Param id) const
{
    const Row* row = rowFor(id);
    return row ? row->spin : nullptr;
}

QCheckBox* ParameterPanel::checkBoxFor(Param id) const
{
    const Row* row = rowFor(id);
    return row ? row->check : nullptr;
}

}  // namespace wisp
