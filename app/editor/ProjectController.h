#pragma once
// The editor's project files: new, open, save, save as, recent files, the unsaved-changes prompt,
// autosave every few minutes and recovery after a crash.
//
// Saving is atomic (io/ProjectFile.h: never a half-written file, the previous version kept as
// .bak). While the editor runs it holds a session lock file in the per-user data folder; a clean
// exit removes it together with the autosave. If the next start finds the lock still there and an
// autosave beside it, the last session ended without closing and its work can be recovered.
//
// Thread: GUI.

#include "io/ProjectFile.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <QTimer>

class QWidget;

namespace wisp {

class Document;
class Viewport;

class ProjectController : public QObject {
    Q_OBJECT
public:
    ProjectController(Document* document, Viewport* viewport, QWidget* dialogParent);
    ~ProjectController() override;  // a clean exit: the lock and the autosave go

    const QString& currentPath() const { return m_path; }
    bool isModified() const;
    // Without dialogs (tests, scripts): errors go to lastError(), questions take their default.
    void setInteractive(bool interactive) { m_interactive = interactive; }
    const QString& lastError() const { return m_lastError; }

    bool newProject();                        // after maybeSave()
    bool open(const QString& path = {});      // a dialog when empty; errors are shown, nothing changes then
    bool save();                              // to the current path, or save as
    bool saveAs(const QString& path = {});    // a dialog when empty
    bool maybeSave();                         // Save, Discard or Cancel when there are unsaved changes

    QStringList recentFiles() const;
    static constexpr int kMaxRecentFiles = 8;

    QString autosavePath() const;
    bool autosaveNow();                       // when changed since the last autosave; true if written
    void setAutosaveIntervalMs(int ms) { m_autosave.setInterval(ms); }
    bool recoveryAvailable() const { return m_recoveryAvailable; }
    bool recover();                           // opens the autosave as unsaved work
    void discardRecovery();

    static constexpr const char* kFileFilter = "Wisp projects (*.wisp)";

signals:
    void currentPathChanged(const QString& path);
    void recentFilesChanged();
    void message(const QString& text);

private:
    io::Project snapshot() const;
    bool write(const QString& path);
    bool load(const QString& path, bool asRecovered);
    void addRecent(const QString& path);
    void fail(const QString& title, const QString& text);
    void setPath(const QString& path);
    QString dataFolder() const;

    Document* m_document;
    Viewport* m_viewport;
    QWidget* m_dialogParent;
    QString m_path;
    QString m_lastError;
    bool m_interactive = true;
    bool m_recoveryAvailable = false;
    int m_autosavedIndex = -1;  // undo index the last autosave holds
    QTimer m_autosave;
};

}  // namespace wisp
