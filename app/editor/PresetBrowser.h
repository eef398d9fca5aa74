#pragma once
// The preset browser: the presets bundled with Wisp (Qt resources under ":/presets", marked with
// a small dot), then the artist's own (*.json in userFolder()), each group sorted by name. Apply
// (or double-click / Enter on a row) hands the selected preset to Document::applyPreset, one undo
// step that the running simulation picks up like any other edit. Save Current… writes the
// document's look as a new user preset; Delete removes a user preset (bundled ones cannot be).
//
// A preset that fails to load stays in the list, greyed, with the error as its tooltip; it cannot
// be applied (a user one can still be deleted). Loading warnings (unknown keys, …) are reported
// through message() when the preset is applied.
//
// Each preset that loads shows a thumbnail (PresetThumbnails: rendered as `wisp --render` renders,
// cached on disk by the file's content, so saving a preset anew refreshes its thumbnail); they are
// made one at a time while the browser is on screen, and a row shows its mark until its arrives.
//
// The buttons ask their questions (name, overwrite?, delete?) in dialogs and then call the public
// methods below, which never block: tests call those directly.
//
// Thread: GUI.

#include "io/PresetFile.h"

#include <QString>
#include <QStringList>
#include <QWidget>

#include <optional>
#include <vector>

class QListWidget;
class QPushButton;

namespace wisp {

class Document;
class PresetThumbnails;

class PresetBrowser : public QWidget {
    Q_OBJECT
public:
    explicit PresetBrowser(Document* document, QWidget* parent = nullptr);

    // Item data the rows carry besides their name and tooltip.
    static constexpr int kPathRole = Qt::UserRole; // QString: ":/presets/x.json" or the user file
    static constexpr int kBundledRole = Qt::UserRole + 1; // bool
    static constexpr int kErrorRole = Qt::UserRole + 2; // QString: why it did not load; empty if it did
    static constexpr int kThumbnailRole = Qt::UserRole + 3; // QImage: its thumbnail, once made

    // Where the artist's presets live: <per-user app data>/presets (it may not exist yet).
    static QString userFolder();

    // Rescans the bundled and user presets, keeping the selected preset selected if it is still there.
    void refresh();
    // Applies the preset in `row` (one undo step) and reports it through message(). Returns false,
    // changing nothing, for a preset that did not load or a row that does not exist.
    bool applyPreset(int row);
    // Writes the document's look as a user preset named `name` (file name made safe from it) and
    // selects it. Refuses an empty or over-long name, and an existing file unless `overwrite`.
    // Failures are reported through message(); returns whether it saved.
    bool savePreset(const QString& name, bool overwrite);
    // Removes the user preset in `row` (its file and its row). Bundled presets are refused.
    bool deletePreset(int row);
    // The file savePreset(name, …) writes.
    static QString userPresetPath(const QString& name);

    QListWidget* listWidget() const { return m_list; }
    QPushButton* applyButton() const { return m_apply; }
    QPushButton* saveButton() const { return m_save; }
    QPushButton* deleteButton() const { return m_delete; }
    QPushButton* refreshButton() const { return m_refresh; }
    QPushButton* showFolderButton() const { return m_showFolder; }
    PresetThumbnails* thumbnails() const { return m_thumbnails; }

signals:
    // For the status bar: what was applied, saved or deleted, loading warnings, failures.
    void message(const QString& text);

protected:
    void showEvent(QShowEvent* event) override; // thumbnails are made while it is on screen
    void hideEvent(QHideEvent* event) override;

private:
    // One row: where it came from and what loading it gave.
    struct Entry {
        QString path;
        bool bundled = false;
        std::optional<io::Preset> preset; // empty when it failed to load
        QStringList warnings;
        QString error;
        QString displayName;
    };

    static Entry load(const QString& path, bool bundled);
    void addRow(const Entry& entry);
    void updateButtons();
    void showThumbnail(const QString& path, const QImage& thumbnail);

    // Button handlers: ask, then call the methods above.
    void applyClicked();
    void saveClicked();
    void deleteClicked();
    void showFolderClicked();

    Document* m_document;
    std::vector<Entry> m_entries; // one per row, in row order
    QListWidget* m_list = nullptr;
    QPushButton* m_apply = nullptr;
    QPushButton* m_save = nullptr;
    QPushButton* m_delete = nullptr;
    QPushButton* m_refresh = nullptr;
    QPushButton* m_showFolder = nullptr;
    PresetThumbnails* m_thumbnails = nullptr;
};

} // namespace wisp
