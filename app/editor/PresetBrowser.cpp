#include "app/editor/PresetBrowser.h"

#include "app/editor/Document.h"
#include "app/editor/ListMark.h"
#include "app/editor/PresetThumbnails.h"

#include <QDesktopServices>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QIcon>
#include <QInputDialog>
#include <QListWidget>
#include <QMessageBox>
#include <QPainter>
#include <QPixmap>
#include <QPushButton>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QUrl>
#include <QVBoxLayout>

#include <algorithm>

// The bundled presets are compiled into the static wisp_editor library (resources/presets.qrc);
// a static library's resources must be registered by hand, once, from the global namespace.
static void initPresetResources()
{
    static const bool registered = [] {
        Q_INIT_RESOURCE(presets);
        return true;
    }();
    (void)registered;
}

namespace wisp {

namespace {

constexpr int kMarkSizePx = kListMarkSizePx; // the bundled mark
constexpr int kIconSizePx = 48; // the list's icons: thumbnails, or the mark until they come
constexpr int kMaxFileStemChars = 64; // file names stay short whatever the preset's name

// The "bundled" mark: a small filled square in `colour` (ListMark.h); user presets get a blank
// icon of the same size so that all names line up.
QIcon bundledMark(const QColor& colour)
{
    return listMark(colour, ListMarkShape::Square);
}

// A file stem every system accepts, from a preset's name: lower case, letters and digits, every
// other run of characters one '-' ("My Look!" → "my-look"). Names that differ only in case or
// punctuation share a file; saving asks before overwriting it.
QString safeFileStem(const QString& name)
{
    QString stem;
    for (const QChar c : name.toLower()) {
        if (c.isLetterOrNumber())
            stem += c;
        else if (!stem.isEmpty() && !stem.endsWith(QLatin1Char('-')))
            stem += QLatin1Char('-');
    }
    stem.truncate(kMaxFileStemChars);
    while (stem.endsWith(QLatin1Char('-')))
        stem.chop(1);
    if (stem.isEmpty())
        return QStringLiteral("preset");
    // Windows reserves these device names, with any extension.
    static const QStringList reserved
        = { QStringLiteral("con"), QStringLiteral("prn"), QStringLiteral("aux"), QStringLiteral("nul") };
    static const QRegularExpression port(QStringLiteral("^(com|lpt)[0-9]$"));
    if (reserved.contains(stem) || port.match(stem).hasMatch())
        stem += QStringLiteral("-preset");
    return stem;
}

} // namespace

PresetBrowser::PresetBrowser(Document* document, QWidget* parent)
    : QWidget(parent)
    , m_document(document)
{
    initPresetResources();

    m_list = new QListWidget(this);
    m_list->setSelectionMode(QAbstractItemView::SingleSelection);
    m_list->setIconSize(QSize(kIconSizePx, kIconSizePx));
    m_thumbnails = new PresetThumbnails(this);
    connect(m_thumbnails, &PresetThumbnails::ready, this, &PresetBrowser::showThumbnail);
    m_apply = new QPushButton(tr("Apply"), this);
    m_apply->setToolTip(tr("Apply the selected preset to the hair (undoable)"));
    m_save = new QPushButton(tr("Save Current…"), this);
    m_save->setToolTip(tr("Save the current look as a preset of your own"));
    m_delete = new QPushButton(tr("Delete"), this);
    m_delete->setToolTip(tr("Delete the selected preset of your own"));
    m_refresh = new QPushButton(tr("Refresh"), this);
    m_refresh->setToolTip(tr("Read the presets again"));
    m_showFolder = new QPushButton(tr("Show Folder"), this);
    m_showFolder->setToolTip(tr("Open the folder that holds your presets"));

    auto* row1 = new QHBoxLayout;
    row1->addWidget(m_apply);
    row1->addWidget(m_save);
    row1->addWidget(m_delete);
    auto* row2 = new QHBoxLayout;
    row2->addWidget(m_refresh);
    row2->addWidget(m_showFolder);
    row2->addStretch();
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_list);
    layout->addLayout(row1);
    layout->addLayout(row2);

    connect(m_list, &QListWidget::currentRowChanged, this, &PresetBrowser::updateButtons);
    // Double-click or Enter (or a single click where the platform activates on one).
    connect(
        m_list, &QListWidget::itemActivated, this, [this](QListWidgetItem* item) { applyPreset(m_list->row(item)); });
    connect(m_apply, &QPushButton::clicked, this, &PresetBrowser::applyClicked);
    connect(m_save, &QPushButton::clicked, this, &PresetBrowser::saveClicked);
    connect(m_delete, &QPushButton::clicked, this, &PresetBrowser::deleteClicked);
    connect(m_refresh, &QPushButton::clicked, this, &PresetBrowser::refresh);
    connect(m_showFolder, &QPushButton::clicked, this, &PresetBrowser::showFolderClicked);

    refresh();
}

QString PresetBrowser::userFolder()
{
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + QStringLiteral("/presets");
}

QString PresetBrowser::userPresetPath(const QString& name)
{
    return userFolder() + QLatin1Char('/') + safeFileStem(name.trimmed()) + QStringLiteral(".json");
}

// --- Loading -------------------------------------------------------------------------------------

PresetBrowser::Entry PresetBrowser::load(const QString& path, bool bundled)
{
    Entry entry;
    entry.path = path;
    entry.bundled = bundled;
    io::Result<io::PresetReadResult> result = io::IoError{};
    if (bundled) {
        QFile file(path);
        if (file.open(QIODevice::ReadOnly))
            result = io::parsePreset(file.readAll().toStdString(), path.toStdString());
        else
            result = io::IoError{ path.toStdString(), "", file.errorString().toStdString() };
    } else {
        result = io::readPreset(path.toStdString());
    }
    if (result) {
        io::PresetReadResult read = std::move(result).value();
        entry.displayName = QString::fromStdString(read.preset.name);
        for (const std::string& w : read.warnings)
            entry.warnings << QString::fromStdString(w);
        entry.preset = std::move(read.preset);
    } else {
        // The file name is enough here; the tooltip has no room for the whole path.
        io::IoError error = result.error();
        error.file = QFileInfo(path).fileName().toStdString();
        entry.error = QString::fromStdString(error.toString());
        entry.displayName = QFileInfo(path).completeBaseName();
    }
    return entry;
}

void PresetBrowser::refresh()
{
    const int oldRow = m_list->currentRow();
    const QString selected = oldRow >= 0 ? m_entries[static_cast<std::size_t>(oldRow)].path : QString();

    const auto byName = [](const Entry& a, const Entry& b) {
        const int c = QString::localeAwareCompare(a.displayName, b.displayName);
        return c != 0 ? c < 0 : a.path < b.path;
    };
    const auto scan = [&](const QString& folder, bool bundled) {
        std::vector<Entry> entries;
        const QDir dir(folder);
        for (const QString& file : dir.entryList({ QStringLiteral("*.json") }, QDir::Files | QDir::Readable))
            entries.push_back(load(dir.filePath(file), bundled));
        std::sort(entries.begin(), entries.end(), byName);
        return entries;
    };

    m_list->clear();
    m_entries = scan(QStringLiteral(":/presets"), true);
    for (Entry& e : scan(userFolder(), false))
        m_entries.push_back(std::move(e));
    int newRow = -1;
    for (std::size_t i = 0; i < m_entries.size(); ++i) {
        addRow(m_entries[i]);
        if (m_entries[i].path == selected)
            newRow = static_cast<int>(i);
    }
    m_list->setCurrentRow(newRow);
    updateButtons();
}

void PresetBrowser::addRow(const Entry& entry)
{
    auto* item = new QListWidgetItem(entry.displayName, m_list);
    item->setData(kPathRole, entry.path);
    item->setData(kBundledRole, entry.bundled);
    item->setData(kErrorRole, entry.error);
    item->setIcon(bundledMark(entry.bundled ? m_list->palette().color(QPalette::Highlight) : QColor()));
    if (!entry.preset) {
        // Greyed but still selectable, so that a broken user preset can be deleted.
        item->setForeground(m_list->palette().color(QPalette::Disabled, QPalette::Text));
        item->setToolTip(tr("Cannot be applied: %1").arg(entry.error));
        return;
    }
    QFile file(entry.path);
    if (file.open(QIODevice::ReadOnly))
        m_thumbnails->request(entry.path, file.readAll());
    QString tip = QString::fromStdString(entry.preset->description);
    tip += (tip.isEmpty() ? QString() : QStringLiteral("\n"))
        + (entry.bundled ? tr("Bundled with Wisp") : QDir::toNativeSeparators(entry.path));
    item->setToolTip(tip);
}

void PresetBrowser::showThumbnail(const QString& path, const QImage& thumbnail)
{
    for (int row = 0; row < m_list->count(); ++row) {
        QListWidgetItem* item = m_list->item(row);
        if (item->data(kPathRole).toString() != path)
            continue;
        item->setData(kThumbnailRole, thumbnail);
        QPixmap pixmap = QPixmap::fromImage(thumbnail);
        if (item->data(kBundledRole).toBool()) { // the bundled mark in its corner
            QPainter painter(&pixmap);
            bundledMark(m_list->palette().color(QPalette::Highlight)).paint(&painter, 0, 0, kMarkSizePx, kMarkSizePx);
        }
        item->setIcon(QIcon(pixmap));
    }
}

void PresetBrowser::showEvent(QShowEvent* event)
{
    QWidget::showEvent(event);
    m_thumbnails->setEnabled(true);
}

void PresetBrowser::hideEvent(QHideEvent* event)
{
    QWidget::hideEvent(event);
    m_thumbnails->setEnabled(false);
}

void PresetBrowser::updateButtons()
{
    const int row = m_list->currentRow();
    const Entry* entry = row >= 0 ? &m_entries[static_cast<std::size_t>(row)] : nullptr;
    m_apply->setEnabled(entry && entry->preset);
    m_delete->setEnabled(entry && !entry->bundled);
}

// --- Actions -------------------------------------------------------------------------------------

bool PresetBrowser::applyPreset(int row)
{
    if (row < 0 || row >= static_cast<int>(m_entries.size()))
        return false;
    const Entry& entry = m_entries[static_cast<std::size_t>(row)];
    if (!entry.preset) {
        emit message(tr("Preset “%1” cannot be applied: %2").arg(entry.displayName, entry.error));
        return false;
    }
    m_document->applyPreset(*entry.preset);
    if (entry.warnings.isEmpty())
        emit message(tr("Applied preset “%1”").arg(entry.displayName));
    else
        emit message(tr("Applied preset “%1”; %2").arg(entry.displayName, entry.warnings.join(QStringLiteral("; "))));
    return true;
}

bool PresetBrowser::savePreset(const QString& name, bool overwrite)
{
    const QString trimmed = name.trimmed();
    if (trimmed.isEmpty()) {
        emit message(tr("A preset needs a name"));
        return false;
    }
    if (static_cast<std::size_t>(trimmed.toUtf8().size()) > io::kMaxNameBytes) {
        emit message(tr("A preset's name is at most %1 bytes").arg(io::kMaxNameBytes));
        return false;
    }
    const QString path = userPresetPath(trimmed);
    if (!overwrite && QFileInfo::exists(path)) {
        emit message(tr("A preset file %1 already exists").arg(QDir::toNativeSeparators(path)));
        return false;
    }
    if (!QDir().mkpath(userFolder())) {
        emit message(tr("Cannot create the folder %1").arg(QDir::toNativeSeparators(userFolder())));
        return false;
    }
    const io::Result<void> written = io::writePreset(path.toStdString(), m_document->toPreset(trimmed));
    if (!written) {
        emit message(tr("Cannot save the preset: %1").arg(QString::fromStdString(written.error().toString())));
        return false;
    }
    refresh();
    for (int row = 0; row < m_list->count(); ++row)
        if (m_entries[static_cast<std::size_t>(row)].path == path)
            m_list->setCurrentRow(row);
    emit message(tr("Saved preset “%1”").arg(trimmed));
    return true;
}

bool PresetBrowser::deletePreset(int row)
{
    if (row < 0 || row >= static_cast<int>(m_entries.size()) || m_entries[static_cast<std::size_t>(row)].bundled)
        return false;
    const Entry entry = m_entries[static_cast<std::size_t>(row)];
    QFile file(entry.path);
    if (!file.remove()) {
        emit message(tr("Cannot delete %1: %2").arg(QDir::toNativeSeparators(entry.path), file.errorString()));
        return false;
    }
    refresh();
    emit message(tr("Deleted preset “%1”").arg(entry.displayName));
    return true;
}

// --- Buttons -------------------------------------------------------------------------------------

void PresetBrowser::applyClicked()
{
    applyPreset(m_list->currentRow());
}

void PresetBrowser::saveClicked()
{
    bool ok = false;
    const QString name
        = QInputDialog::getText(this, tr("Save Preset"), tr("Preset name:"), QLineEdit::Normal, QString(), &ok)
              .trimmed();
    if (!ok)
        return;
    if (name.isEmpty()) {
        QMessageBox::warning(this, tr("Save Preset"), tr("A preset needs a name."));
        return;
    }
    bool overwrite = false;
    if (QFileInfo::exists(userPresetPath(name))) {
        const auto answer = QMessageBox::question(this, tr("Save Preset"),
            tr("A preset saved as %1 already exists. Replace it?").arg(QFileInfo(userPresetPath(name)).fileName()),
            QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
        if (answer != QMessageBox::Yes)
            return;
        overwrite = true;
    }
    savePreset(name, overwrite);
}

void PresetBrowser::deleteClicked()
{
    const int row = m_list->currentRow();
    if (row < 0 || m_entries[static_cast<std::size_t>(row)].bundled)
        return;
    const auto answer = QMessageBox::question(this, tr("Delete Preset"),
        tr("Delete the preset “%1”? Its file is removed.").arg(m_entries[static_cast<std::size_t>(row)].displayName),
        QMessageBox::Yes | QMessageBox::No, QMessageBox::No);
    if (answer == QMessageBox::Yes)
        deletePreset(row);
}

void PresetBrowser::showFolderClicked()
{
    QDir().mkpath(userFolder());
    QDesktopServices::openUrl(QUrl::fromLocalFile(userFolder()));
}

} // namespace wisp
