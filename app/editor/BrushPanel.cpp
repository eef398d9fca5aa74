#include "app/editor/BrushPanel.h"

#include "app/editor/PaintTool.h"
#include "sim/params/Parameters.h"
#include "widgets/SliderRow.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QPushButton>
#include <QSignalBlocker>

namespace wisp {

namespace {

// A slider-and-spin-box row over a tool setting's range (toolSettingRange), shown in `unitScale`
// units of it (100: metres as centimetres).
SliderRow* settingRow(ToolSetting setting, double unitScale, int decimals, double step, const QString& suffix,
    const QString& tip, const QString& name)
{
    SliderRowSpec spec;
    spec.range = toolSettingRange(setting);
    spec.range.minimum *= unitScale;
    spec.range.maximum *= unitScale;
    spec.decimals = decimals;
    spec.singleStep = step;
    spec.suffix = suffix;
    spec.tooltip = tip;
    spec.objectName = name;
    return new SliderRow(std::move(spec));
}

} // namespace

BrushPanel::BrushPanel(PaintTool* tool, QWidget* parent)
    : QWidget(parent)
    , m_tool(tool)
{
    auto* form = new QFormLayout(this);
    m_paint = new QPushButton(tr("Paint growth"));
    m_paint->setCheckable(true);
    m_paint->setToolTip(tr("Paint where the current region's hair grows (B). Left drag paints, Ctrl erases, "
                           "Shift smooths, [ and ] resize; Alt or middle drag still moves the camera"));
    form->addRow(m_paint);

    m_mode = new QComboBox;
    m_mode->addItem(tr("Add"), static_cast<int>(BrushMode::Add));
    m_mode->addItem(tr("Erase"), static_cast<int>(BrushMode::Erase));
    m_mode->addItem(tr("Smooth"), static_cast<int>(BrushMode::Smooth));
    m_mode->setToolTip(tr("What a stroke does to the growth weights; hold Ctrl to erase, Shift to smooth"));
    form->addRow(tr("Mode"), m_mode);

    m_radius = settingRow(ToolSetting::BrushRadius, 100.0, 2, 0.25, tr(" cm"),
        tr("Brush radius on the head, in centimetres ([ and ] change it)"), QStringLiteral("brush_radius"));
    form->addRow(tr("Radius"), m_radius);
    m_strength = settingRow(ToolSetting::BrushStrength, 1.0, 2, 0.05, QString(),
        tr("Share of the way to the target a dab moves a weight, 0..1"), QStringLiteral("brush_strength"));
    form->addRow(tr("Strength"), m_strength);
    m_falloff = settingRow(ToolSetting::BrushFalloff, 1.0, 2, 0.05, QString(),
        tr("0: full strength to the rim; 1: fades smoothly from the centre to the rim"),
        QStringLiteral("brush_falloff"));
    form->addRow(tr("Falloff"), m_falloff);
    m_mirror = new QCheckBox(tr("X mirror"));
    m_mirror->setToolTip(tr("Paint both sides of the head at once (symmetry across the head's mid-plane)"));
    form->addRow(m_mirror);
    m_overlay = new QCheckBox(tr("Show growth weights"));
    m_overlay->setToolTip(tr("Tint the head by the current region's painted weights even when not painting"));
    m_overlay->setChecked(false); // the tint shows while painting anyway
    form->addRow(m_overlay);

    connect(m_paint, &QPushButton::toggled, m_tool, &PaintTool::setActive);
    connect(m_tool, &PaintTool::activeChanged, this, &BrushPanel::showSettings);
    connect(m_tool, &PaintTool::settingsChanged, this, &BrushPanel::showSettings);
    connect(m_mode, &QComboBox::currentIndexChanged, this, [this](int index) {
        if (!m_updating)
            m_tool->setMode(static_cast<BrushMode>(m_mode->itemData(index).toInt()));
    });
    connect(m_radius, &SliderRow::valueEdited, this, [this](double cm) {
        if (!m_updating)
            m_tool->setRadius(cm / 100.0);
    });
    connect(m_strength, &SliderRow::valueEdited, this, [this](double v) {
        if (!m_updating)
            m_tool->setStrength(v);
    });
    connect(m_falloff, &SliderRow::valueEdited, this, [this](double v) {
        if (!m_updating)
            m_tool->setFalloff(v);
    });
    connect(m_mirror, &QCheckBox::toggled, this, [this](bool on) {
        if (!m_updating)
            m_tool->setMirror(on);
    });
    connect(m_overlay, &QCheckBox::toggled, this, &BrushPanel::showOverlayToggled);
    showSettings();
}

void BrushPanel::showSettings()
{
    m_updating = true;
    const BrushSettings& s = m_tool->settings();
    m_paint->setChecked(m_tool->isActive());
    m_mode->setCurrentIndex(m_mode->findData(static_cast<int>(s.mode)));
    m_radius->setValue(s.radiusMetres * 100.0);
    m_strength->setValue(s.strength);
    m_falloff->setValue(s.falloff);
    m_mirror->setChecked(s.mirrorX);
    m_updating = false;
}

QDoubleSpinBox* BrushPanel::radiusBox() const
{
    return m_radius->spinBox();
}
QDoubleSpinBox* BrushPanel::strengthBox() const
{
    return m_strength->spinBox();
}
QDoubleSpinBox* BrushPanel::falloffBox() const
{
    return m_falloff->spinBox();
}

} // namespace wisp
