#include "widgets/ParameterPanel.h"

#include "widgets/SliderRow.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QSlider>

#include <cmath>

namespace wisp {

namespace {

// What the panel shows: the value times this, in shownUnit (the registry's display unit, if any).
double shownScale(const ParameterInfo& p)
{
    return p.displayUnit.empty() || !(p.displayScale > 0.0) ? 1.0 : p.displayScale;
}

QString shownUnit(const ParameterInfo& p)
{
    const std::string_view unit = p.displayUnit.empty() ? p.unit : p.displayUnit;
    return QString::fromUtf8(unit.data(), static_cast<int>(unit.size()));
}

int decimalsFor(const ParameterInfo& p)
{
    if (p.kind != ParamKind::Real)
        return 0;
    const double span = (p.maximum - p.minimum) * shownScale(p);
    // Tiny ranges need a hundredth of their span to show.
    if (span <= 0.001)
        return 6;
    return span <= 0.1 ? 4 : span <= 2.0 ? 3 : 2;
}

QString tooltipFor(const ParameterInfo& p)
{
    const QString unit = shownUnit(p);
    const double scale = shownScale(p);
    return QStringLiteral("<b>%1</b>%2<br>%3<br><small>%4 … %5, default %6</small>")
        .arg(QString::fromUtf8(p.label.data(), static_cast<int>(p.label.size())),
            unit.isEmpty() ? QString() : QStringLiteral(" (%1)").arg(unit),
            QString::fromUtf8(p.help.data(), static_cast<int>(p.help.size())))
        .arg(p.minimum * scale)
        .arg(p.maximum * scale)
        .arg(p.defaultValue * scale);
}

} // namespace

ParameterPanel::ParameterPanel(std::vector<Param> parameters, QWidget* parent)
    : QWidget(parent)
{
    auto* form = new QFormLayout(this);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    for (Param id : parameters) {
        const ParameterInfo& p = parameterInfo(id);
        Row row{ id };
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
            // The row works in the shown unit; the panel speaks the registry's.
            row.scale = shownScale(p);
            SliderRowSpec spec;
            spec.range = sliderRangeOf(p);
            spec.range.minimum *= row.scale;
            spec.range.maximum *= row.scale;
            spec.decimals = decimalsFor(p);
            spec.singleStep = p.kind == ParamKind::Real ? (spec.range.maximum - spec.range.minimum) / 100.0 : 1.0;
            if (!shownUnit(p).isEmpty())
                spec.suffix = QStringLiteral(" ") + shownUnit(p);
            spec.tooltip = tooltip;
            spec.objectName = QString::fromUtf8(p.key.data(), static_cast<int>(p.key.size()));
            row.numbers = new SliderRow(std::move(spec), this);
            form->addRow(label, row.numbers);
            connect(row.numbers, &SliderRow::valueEdited, this, [this, id, scale = row.scale](double v, bool dragging) {
                if (!m_updating)
                    emit valueEdited(id, v / scale, dragging);
            });
        }
        m_rows.push_back(row);
    }
    setValues(ParameterValues());
}

const ParameterPanel::Row* ParameterPanel::find(Param id) const
{
    for (const Row& r : m_rows)
        if (r.id == id)
            return &r;
    return nullptr;
}

void ParameterPanel::setValues(const ParameterValues& values)
{
    m_updating = true;
    for (const Row& row : m_rows) {
        if (row.check)
            row.check->setChecked(values.get(row.id) != 0.0);
        else
            row.numbers->setValue(values.get(row.id) * row.scale);
    }
    m_updating = false;
}

double ParameterPanel::value(Param id) const
{
    const Row* row = find(id);
    if (!row)
        return 0.0;
    return row->check ? (row->check->isChecked() ? 1.0 : 0.0) : row->numbers->value() / row->scale;
}

QSlider* ParameterPanel::sliderFor(Param id) const
{
    const Row* row = find(id);
    return row && row->numbers ? row->numbers->slider() : nullptr;
}

QDoubleSpinBox* ParameterPanel::spinBoxFor(Param id) const
{
    const Row* row = find(id);
    return row && row->numbers ? row->numbers->spinBox() : nullptr;
}

QCheckBox* ParameterPanel::checkBoxFor(Param id) const
{
    const Row* row = find(id);
    return row ? row->check : nullptr;
}

SliderRow* ParameterPanel::rowFor(Param id) const
{
    const Row* row = find(id);
    return row ? row->numbers : nullptr;
}

} // namespace wisp
