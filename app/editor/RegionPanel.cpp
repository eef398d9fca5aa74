#include "app/editor/RegionPanel.h"

#include "app/editor/Document.h"
#include "app/editor/ListMark.h"
#include "sim/groom/GrowthRegion.h"

#include <QHBoxLayout>
#include <QIcon>
#include <QListWidget>
#include <QScopedValueRollback>
#include <QStyle>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>

#include <algorithm>

namespace wisp {

namespace {

// The solo mark: a filled dot in the selection colour (ListMark.h). Rows without it get a blank
// icon of the same size, so that solo'ing a region does not shift its name sideways.
QIcon soloMark(const QColor& colour)
{
    return listMark(colour, ListMarkShape::Dot);
}

QToolButton* makeButton(QWidget* parent, const QIcon& icon, const QString& text, const QString& tooltip)
{
    auto* button = new QToolButton(parent);
    button->setAutoRaise(true);
    button->setText(text); // shown when neither the theme nor the style has the icon
    button->setIcon(icon);
    button->setToolButtonStyle(icon.isNull() ? Qt::ToolButtonTextOnly : Qt::ToolButtonIconOnly);
    button->setToolTip(tooltip);
    return button;
}

bool grows(const std::vector<const GrowthRegion*>& growing, const GrowthRegion& region)
{
    return std::find(growing.begin(), growing.end(), &region) != growing.end();
}

} // namespace

RegionPanel::RegionPanel(Document* document, QWidget* parent)
    : QWidget(parent)
    , m_document(document)
{
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    m_list = new QListWidget(this);
    m_list->setObjectName(QStringLiteral("regionList"));
    m_list->setSelectionMode(QAbstractItemView::SingleSelection);
    m_list->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
    m_list->setIconSize(QSize(kListMarkSizePx, kListMarkSizePx));
    m_list->setToolTip(tr("Growth regions: each grows its own hair where it is painted.\n"
                          "Double-click or F2 renames; the check box shows or hides a region."));
    layout->addWidget(m_list, 1);
    createButtons();

    connect(m_list, &QListWidget::itemChanged, this, &RegionPanel::itemEdited);
    connect(m_list, &QListWidget::currentRowChanged, this, [this](int row) {
        if (m_showing || row < 0)
            return;
        m_document->setCurrentRegion(row);
        refresh();
    });
    connectDocument();
    refresh();
}

void RegionPanel::createButtons()
{
    auto* row = new QHBoxLayout;
    row->setSpacing(2);
    m_add = makeButton(
        this, QIcon::fromTheme(QStringLiteral("list-add")), tr("Add"), tr("Add a region (painted nowhere yet)"));
    m_remove = makeButton(this, QIcon::fromTheme(QStringLiteral("list-remove")), tr("Remove"),
        tr("Remove the selected region (the last one stays)"));
    m_up = makeButton(this, style()->standardIcon(QStyle::SP_ArrowUp), tr("Up"), tr("Move the selected region up"));
    m_down = makeButton(
        this, style()->standardIcon(QStyle::SP_ArrowDown), tr("Down"), tr("Move the selected region down"));
    m_solo = makeButton(this, QIcon(), tr("Solo"), tr("Grow only the selected region's hair, hiding the others"));
    m_solo->setCheckable(true);
    m_add->setObjectName(QStringLiteral("addRegion"));
    m_remove->setObjectName(QStringLiteral("removeRegion"));
    m_up->setObjectName(QStringLiteral("moveRegionUp"));
    m_down->setObjectName(QStringLiteral("moveRegionDown"));
    m_solo->setObjectName(QStringLiteral("soloRegion"));
    row->addWidget(m_add);
    row->addWidget(m_remove);
    row->addStretch(1);
    row->addWidget(m_up);
    row->addWidget(m_down);
    row->addWidget(m_solo);
    static_cast<QVBoxLayout*>(layout())->addLayout(row);

    connect(m_add, &QToolButton::clicked, this, &RegionPanel::addRegion);
    connect(m_remove, &QToolButton::clicked, this, &RegionPanel::removeCurrent);
    connect(m_up, &QToolButton::clicked, this, [this] { moveCurrent(-1); });
    connect(m_down, &QToolButton::clicked, this, [this] { moveCurrent(+1); });
    // clicked, not toggled: only the artist's click is an edit, not the panel showing solo state.
    connect(m_solo, &QToolButton::clicked, this, &RegionPanel::soloToggled);
}

void RegionPanel::connectDocument()
{
    connect(m_document, &Document::regionsChanged, this, &RegionPanel::refresh);
    connect(m_document, &Document::currentRegionChanged, this, &RegionPanel::refresh);
    connect(m_document, &Document::headChanged, this, &RegionPanel::refresh);
    // Undo and redo come back through the signals above; this also catches a step that changed
    // nothing the panel was told about.
    connect(m_document->undoStack(), &QUndoStack::indexChanged, this, &RegionPanel::refresh);
}

// --- Document → rows ----------------------------------------------------------------------------

void RegionPanel::refresh()
{
    const QScopedValueRollback<bool> showing(m_showing, true);
    const int count = m_document->regionCount();
    while (m_list->count() > count)
        delete m_list->takeItem(m_list->count() - 1);
    while (m_list->count() < count) {
        auto* item = new QListWidgetItem(m_list);
        item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable | Qt::ItemIsEditable | Qt::ItemIsUserCheckable);
    }
    for (int row = 0; row < count; ++row)
        showRegion(row);
    showCurrent();
    updateButtons();
}

void RegionPanel::showRegion(int row)
{
    const GrowthRegion& region = m_document->region(row);
    QListWidgetItem* item = m_list->item(row);
    const QString name = QString::fromStdString(region.name);
    // Rewriting an unchanged text would close the name editor the artist may have open on it.
    if (item->text() != name)
        item->setText(name);
    item->setCheckState(region.visible ? Qt::Checked : Qt::Unchecked);
    item->setData(kRegionIdRole, QVariant::fromValue(region.id));
    const bool solo = region.id == m_document->soloRegion();
    item->setData(kSoloRole, solo);
    item->setIcon(soloMark(solo ? palette().color(QPalette::Highlight) : QColor()));
    // A region that grows no hair (hidden, or another is solo'd) is drawn greyed.
    const bool growing = grows(growingRegions(m_document->regions(), m_document->soloRegion()), region);
    item->setData(
        Qt::ForegroundRole, growing ? QVariant() : QVariant(palette().brush(QPalette::Disabled, QPalette::Text)));
    item->setToolTip(solo ? tr("%1 (solo: only its hair grows)").arg(name)
            : growing     ? name
                          : tr("%1 (grows no hair now)").arg(name));
}

void RegionPanel::showCurrent()
{
    const int current = validCurrent();
    if (m_list->currentRow() != current)
        m_list->setCurrentRow(current);
    if (current >= 0 && !m_list->item(current)->isSelected())
        m_list->item(current)->setSelected(true);
}

void RegionPanel::updateButtons()
{
    const int count = m_document->regionCount();
    const int current = validCurrent();
    const bool hasCurrent = current >= 0;
    // The last region cannot be removed: an artist should not lose all hair by accident.
    m_remove->setEnabled(hasCurrent && count > 1);
    m_up->setEnabled(hasCurrent && current > 0);
    m_down->setEnabled(hasCurrent && current < count - 1);
    m_solo->setEnabled(hasCurrent);
    m_solo->setChecked(hasCurrent && m_document->region(current).id == m_document->soloRegion());
}

// The document announces new regions before it moves the current index onto them, so in between
// its current index may point past the end: that is "no current region yet".
int RegionPanel::validCurrent() const
{
    const int current = m_document->currentRegion();
    return current >= 0 && current < m_document->regionCount() ? current : -1;
}

// --- Rows → document ----------------------------------------------------------------------------

// An item changes for a rename (its text) or a click on its check box (its check state).
void RegionPanel::itemEdited(QListWidgetItem* item)
{
    if (m_showing)
        return;
    const int row = m_list->row(item);
    if (row < 0 || row >= m_document->regionCount())
        return;
    // Copies: each edit replaces the document's regions.
    const QString oldName = QString::fromStdString(m_document->region(row).name);
    const bool wasVisible = m_document->region(row).visible;
    const QString name = item->text().trimmed();
    const bool visible = item->checkState() == Qt::Checked;
    if (!name.isEmpty() && name != oldName)
        m_document->renameRegion(row, name);
    if (visible != wasVisible)
        m_document->setRegionVisible(row, visible);
    // Shows what the document kept: the old name again when the new one was refused (empty).
    refresh();
}

void RegionPanel::addRegion()
{
    m_document->addRegion(unusedRegionName());
    refresh();
}

void RegionPanel::removeCurrent()
{
    const int current = validCurrent();
    if (current >= 0 && m_document->regionCount() > 1)
        m_document->removeRegion(current);
    refresh();
}

void RegionPanel::moveCurrent(int offset)
{
    const int from = validCurrent();
    const int to = from + offset;
    if (from < 0 || to < 0 || to >= m_document->regionCount())
        return;
    const std::uint32_t id = m_document->region(from).id;
    m_document->moveRegion(from, to);
    // The selection follows the region the artist moved, so that repeated clicks keep moving it.
    if (const int at = m_document->indexOfRegion(id); at >= 0 && m_document->currentRegion() != at)
        m_document->setCurrentRegion(at);
    refresh();
}

void RegionPanel::soloToggled(bool on)
{
    const int current = validCurrent();
    if (current < 0)
        return;
    m_document->setSoloRegion(on ? m_document->region(current).id : kNoSolo);
    refresh();
}

QString RegionPanel::unusedRegionName() const
{
    for (int n = m_document->regionCount() + 1;; ++n) {
        const QString name = tr("Region %1").arg(n);
        const std::string candidate = name.toStdString();
        const auto& regions = m_document->regions();
        if (std::none_of(regions.begin(), regions.end(), [&](const GrowthRegion& r) { return r.name == candidate; }))
            return name;
    }
}

} // namespace wisp
