#include "app/editor/WispPanel.h"

#include "app/editor/Document.h"
#include "sim/groom/GrowthRegion.h"
#include "widgets/ParameterPanel.h"

#include <QColorDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QPixmap>
#include <QPushButton>
#include <QUndoStack>
#include <QVBoxLayout>

#include <algorithm>
#include <vector>

namespace wisp {

namespace {

constexpr QSize kSwatchSizePx(32, 16);

// The registry's Wisp group in registry order: the panel states no parameter list of its own.
std::vector<Param> wispParameters()
{
    std::vector<Param> ids;
    for (const ParameterInfo& p : allParameters())
        if (p.group == ParamGroup::Wisp)
            ids.push_back(p.id);
    return ids;
}

// Region colours are sRGB 0..1, as QColor's float components are.
QColor toQColor(const glm::vec3& c)
{
    return QColor::fromRgbF(std::clamp(c.x, 0.0f, 1.0f), std::clamp(c.y, 0.0f, 1.0f), std::clamp(c.z, 0.0f, 1.0f));
}

glm::vec3 toVec3(const QColor& c)
{
    return { static_cast<float>(c.redF()), static_cast<float>(c.greenF()), static_cast<float>(c.blueF()) };
}

QIcon swatch(const QColor& colour, const QColor& border)
{
    QPixmap pixmap(kSwatchSizePx);
    pixmap.fill(colour);
    QPainter painter(&pixmap);
    painter.setPen(border);
    painter.drawRect(pixmap.rect().adjusted(0, 0, -1, -1));
    return QIcon(pixmap);
}

} // namespace

WispPanel::WispPanel(Document* document, QWidget* parent)
    : QWidget(parent)
    , m_document(document)
{
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    m_title = new QLabel(this);
    m_title->setObjectName(QStringLiteral("wispRegionTitle"));
    m_title->setTextFormat(Qt::PlainText);
    QFont bold = m_title->font();
    bold.setBold(true);
    m_title->setFont(bold);
    layout->addWidget(m_title);
    m_parameters = new ParameterPanel(wispParameters(), this);
    layout->addWidget(m_parameters);
    layout->addWidget(createColourRow());
    layout->addStretch(1);

    connect(m_parameters, &ParameterPanel::valueEdited, this, &WispPanel::parameterEdited);
    connectDocument();
    refresh();
}

QWidget* WispPanel::createColourRow()
{
    auto* row = new QWidget(this);
    auto* h = new QHBoxLayout(row);
    h->setContentsMargins(0, 0, 0, 0);
    h->addWidget(new QLabel(tr("Colour"), row));
    m_rootColour = new QPushButton(tr("Root"), row);
    m_rootColour->setObjectName(QStringLiteral("rootColour"));
    m_rootColour->setToolTip(tr("The hair's colour at its root; it blends to the tip colour along the strand"));
    m_tipColour = new QPushButton(tr("Tip"), row);
    m_tipColour->setObjectName(QStringLiteral("tipColour"));
    m_tipColour->setToolTip(tr("The hair's colour at its tip"));
    for (QPushButton* button : { m_rootColour, m_tipColour }) {
        button->setIconSize(kSwatchSizePx);
        h->addWidget(button);
    }
    h->addStretch(1);
    connect(m_rootColour, &QPushButton::clicked, this, [this] { pickColour(HairEnd::Root); });
    connect(m_tipColour, &QPushButton::clicked, this, [this] { pickColour(HairEnd::Tip); });
    return row;
}

void WispPanel::connectDocument()
{
    connect(m_document, &Document::currentRegionChanged, this, &WispPanel::refresh);
    connect(m_document, &Document::regionsChanged, this, &WispPanel::refresh); // renamed, recoloured, reordered
    connect(m_document, &Document::headChanged, this, &WispPanel::refresh);
    connect(m_document, &Document::regionParameterChanged, this, [this](int index, Param) {
        if (index == m_document->currentRegion())
            showValues();
    });
    // Undo and redo come back through the signals above; this also catches a step that changed
    // nothing the panel was told about.
    connect(m_document->undoStack(), &QUndoStack::indexChanged, this, &WispPanel::refresh);
}

// --- Document → widgets -------------------------------------------------------------------------

void WispPanel::refresh()
{
    const int current = validCurrent();
    const bool hasRegion = current >= 0;
    setEnabled(hasRegion);
    m_title->setText(hasRegion ? QString::fromStdString(m_document->region(current).name) : tr("No region"));
    showValues();
    showColours();
}

void WispPanel::showValues()
{
    const int current = validCurrent();
    if (current >= 0)
        m_parameters->setValues(m_document->region(current).values); // emits nothing
}

void WispPanel::showColours()
{
    const int current = validCurrent();
    if (current < 0)
        return;
    const GrowthRegion& region = m_document->region(current);
    const QColor border = palette().color(QPalette::Mid);
    m_rootColour->setIcon(swatch(toQColor(region.rootColour), border));
    m_tipColour->setIcon(swatch(toQColor(region.tipColour), border));
}

// The document announces new regions before it moves the current index onto them, so in between
// its current index may point past the end: that is "no current region yet".
int WispPanel::validCurrent() const
{
    const int current = m_document->currentRegion();
    return current >= 0 && current < m_document->regionCount() ? current : -1;
}

// --- Widgets → document -------------------------------------------------------------------------

void WispPanel::parameterEdited(Param id, double value, bool dragging)
{
    const int current = validCurrent();
    if (current < 0)
        return;
    const QString refusal = m_document->editRegionParameter(current, id, value, dragging);
    if (!refusal.isEmpty()) {
        showValues(); // back to the value the document kept
        emit editRefused(refusal);
    }
}

// The dialog is window-modal and answers through a signal, so the event loop keeps running (the
// hair keeps moving behind it) and tests can answer it.
void WispPanel::pickColour(HairEnd end)
{
    const int current = validCurrent();
    if (current < 0)
        return;
    const GrowthRegion& region = m_document->region(current);
    const std::uint32_t regionId = region.id;
    auto* dialog = new QColorDialog(toQColor(end == HairEnd::Root ? region.rootColour : region.tipColour), this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->setWindowTitle(end == HairEnd::Root ? tr("Root Colour of %1").arg(QString::fromStdString(region.name))
                                                : tr("Tip Colour of %1").arg(QString::fromStdString(region.name)));
    // By id: the region may have moved while the dialog was open.
    connect(dialog, &QColorDialog::colorSelected, this,
        [this, regionId, end](const QColor& colour) { applyColour(regionId, end, colour); });
    dialog->open();
}

void WispPanel::applyColour(std::uint32_t regionId, HairEnd end, const QColor& colour)
{
    const int index = m_document->indexOfRegion(regionId);
    if (index < 0 || !colour.isValid())
        return;
    const GrowthRegion& region = m_document->region(index);
    const glm::vec3 root = end == HairEnd::Root ? toVec3(colour) : region.rootColour;
    const glm::vec3 tip = end == HairEnd::Tip ? toVec3(colour) : region.tipColour;
    if (root != region.rootColour || tip != region.tipColour)
        m_document->setRegionColours(index, root, tip);
}

} // namespace wisp
