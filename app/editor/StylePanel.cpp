#include "app/editor/StylePanel.h"

#include "sim/params/Parameters.h"
#include "widgets/SliderRow.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QLabel>
#include <QToolButton>

namespace wisp {

namespace {

constexpr StyleBrush kBrushes[] = { StyleBrush::Comb, StyleBrush::Cut, StyleBrush::Length, StyleBrush::Curl,
    StyleBrush::Wet, StyleBrush::Hairspray, StyleBrush::BlowDry };

QKeySequence shortcutFor(StyleBrush brush)
{
    switch (brush) {
    case StyleBrush::Comb:
        return QKeySequence(Qt::Key_C);
    case StyleBrush::Cut:
        return QKeySequence(Qt::Key_X);
    case StyleBrush::Length:
        return QKeySequence(Qt::Key_G);
    case StyleBrush::Curl:
        return QKeySequence(Qt::Key_P);
    case StyleBrush::Wet:
        return QKeySequence(Qt::Key_W);
    case StyleBrush::Hairspray:
        return QKeySequence(Qt::Key_S);
    case StyleBrush::BlowDry:
        return QKeySequence(Qt::Key_D);
    }
    return {};
}

} // namespace

StylePanel::StylePanel(StyleTool* tool, QWidget* parent)
    : QWidget(parent)
    , m_tool(tool)
{
    auto* form = new QFormLayout(this);
    auto* grid = new QGridLayout;
    int cell = 0;
    for (StyleBrush brush : kBrushes) {
        auto* action = new QAction(styleBrushName(brush), this);
        action->setCheckable(true);
        action->setShortcut(shortcutFor(brush));
        action->setToolTip(QStringLiteral("%1 (%2): %3")
                               .arg(styleBrushName(brush), shortcutFor(brush).toString(QKeySequence::NativeText),
                                   styleBrushHelp(brush)));
        connect(action, &QAction::toggled, this, [this, brush](bool on) {
            if (on)
                m_tool->setBrush(brush);
            else if (m_tool->brush() == brush)
                m_tool->setBrush(std::nullopt);
        });
        m_actions[brush] = action;
        auto* button = new QToolButton;
        button->setDefaultAction(action);
        button->setToolButtonStyle(Qt::ToolButtonTextOnly);
        button->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        grid->addWidget(button, cell / 2, cell % 2);
        ++cell;
    }
    form->addRow(grid);

    // The perm's curl: slider-and-spin-box rows over the tool settings' ranges (sim/params/Parameters.h).
    SliderRowSpec radius;
    radius.range = toolSettingRange(ToolSetting::PermRadius);
    radius.range.minimum *= 1000.0; // shown in millimetres
    radius.range.maximum *= 1000.0;
    radius.decimals = 1;
    radius.singleStep = 0.5;
    radius.suffix = tr(" mm");
    radius.tooltip = tr("Curl radius the perm gives, in millimetres (0: straight)");
    radius.objectName = QStringLiteral("perm_radius");
    m_curlRadius = new SliderRow(std::move(radius));
    m_curlRadius->setValue(m_tool->curlRadiusMetres() * 1000.0);
    form->addRow(tr("Perm radius"), m_curlRadius);
    SliderRowSpec turns;
    turns.range = toolSettingRange(ToolSetting::PermTurns);
    turns.decimals = 1;
    turns.singleStep = 1.0;
    turns.suffix = tr(" turns/m");
    turns.tooltip = tr("Curl turns per metre of hair the perm gives (period = 1 / turns)");
    turns.objectName = QStringLiteral("perm_turns");
    m_curlTurns = new SliderRow(std::move(turns));
    m_curlTurns->setValue(m_tool->curlTurnsPerMetre());
    form->addRow(tr("Perm turns"), m_curlTurns);
    connect(
        m_curlRadius, &SliderRow::valueEdited, m_tool, [this](double mm) { m_tool->setCurlRadiusMetres(mm / 1000.0); });
    connect(
        m_curlTurns, &SliderRow::valueEdited, m_tool, [this](double turns) { m_tool->setCurlTurnsPerMetre(turns); });

    m_hint = new QLabel;
    m_hint->setWordWrap(true);
    form->addRow(m_hint);
    auto* shared = new QLabel(tr("Radius, strength, falloff and mirror are set in the Brush panel."));
    shared->setWordWrap(true);
    shared->setEnabled(false);
    form->addRow(shared);
    connect(m_tool, &StyleTool::brushChanged, this, &StylePanel::showBrush);
    showBrush(m_tool->brush());
}

void StylePanel::showBrush(std::optional<StyleBrush> brush)
{
    for (const auto& [b, action] : m_actions)
        action->setChecked(brush == b); // re-entry is harmless: setBrush ignores the brush it has
    m_hint->setText(brush ? styleBrushHelp(*brush) : tr("Pick a styling tool to work on the moving hair."));
}

QDoubleSpinBox* StylePanel::curlRadiusBox() const
{
    return m_curlRadius->spinBox();
}
QDoubleSpinBox* StylePanel::curlTurnsBox() const
{
    return m_curlTurns->spinBox();
}

} // namespace wisp
