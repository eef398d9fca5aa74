#pragma once
// The editor's project files: new, open, save, save as, recent files, the unsaved-changes prompt,
// autosave and recovery after a crash.
//
// Saving is atomic (io/AtomicFile.h, io/ProjectFile.h: never a half-written file, the previous
// version kept as .bak). Each editor session holds its own lock, session-<id>.lock, in the per-user
// data folder: the lock holds the session's pid on its first line and its project's path (empty
// for Untitled) on the second, and its autosave is autosave-<id>.wisp beside it. A clean exit, or a
// save that makes the document clean, removes the autosave; a clean exit removes the lock.
//
// Autosave: the first change after a save, an open or a quiet interval is autosaved at once; while
// changes go on, at most once an interval (1 minute; setAutosaveIntervalMs), never mid-stroke.
//
// Recovery: a start that finds a lock whose pid is not alive and an autosave beside it offers that
// work (the newest such session first); a lock of a live process is another editor's running
// session and is left alone. Recovered work keeps its project's path and comes back unsaved.
// Temporary files of killed saves are removed at start from the data folder and from the folders
// of the recent projects (io::removeStaleTemporaryFiles).
//
// Thread: GUI.

#include "io/ProjectFile.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <QTimer>

#include <cstdint>

class QWidget;

namespace wisp {

class Document;
class Viewport;

class ProjectController : public QObject {
    Q_OBJECT
public:
    ProjectController(Document* document, Viewport* viewport, QWidget* dialogParent);
    ~ProjectController() override; // a clean exit: the lock and the autosave go

    const QString& currentPath() const { return m_path; }
    bool isModified() const;
    // Without dialogs (tests, scripts): errors go to lastError(), questions take their default.
    void setInteractive(bool interactive) { m_interactive = interactive; }
    const QString& lastError() const { return m_lastError; }

    bool newProject(); // after maybeSave()
    bool open(const QString& path = {}); // a dialog when empty; errors are shown, nothing changes then
    bool save(); // to the current path, or save as
    bool saveAs(const QString& path = {}); // a dialog when empty
    bool maybeSave(); // Save, Discard or Cancel when there are unsaved changes

    QStringList recentFiles() const;
    static constexpr int kMaxRecentFiles = 8;

    QString autosavePath() const; // this session's
    QString sessionLockPath() const; // this session's
    bool autosaveNow(); // when changed since the last autosave; true if written
    static constexpr int kAutosaveIntervalMs = 60 * 1000;
    void setAutosaveIntervalMs(int ms) { m_autosave.setInterval(ms); }
    int autosaveIntervalMs() const { return m_autosave.interval(); }

    // A session that did not close left work behind (found at construction).
    bool recoveryAvailable() const { return m_recoveryAvailable; }
    QString recoveryProjectPath() const { return m_recovery.projectPath; } // empty: it was Untitled
    QString recoveryAutosavePath() const { return m_recovery.autosavePath; }
    bool recover(); // opens that autosave as unsaved work at its path
    void discardRecovery(); // removes that session's autosave and lock

    static constexpr const char* kFileFilter = "Wisp projects (*.wisp)";

signals:
    void currentPathChanged(const QString& path);
    void recentFilesChanged();
    void message(const QString& text);
    void autosaved(const QString& autosavePath);

private:
    io::Project snapshot() const;
    bool write(const QString& path);
    bool load(const QString& path, bool asRecovered, const QString& projectPath);
    void addRecent(const QString& path);
    void fail(const QString& title, const QString& text);
    void setPath(const QString& path);
    QString dataFolder() const;
    bool writeAutosave();
    void findRecovery();
    void claimSession();
    void writeLock();
    void documentChanged();
    void autosaveTick();
    void documentSaved();

    struct LostSession {
        QString lockPath;
        QString autosavePath;
        QString projectPath;
    };

    Document* m_document;
    Viewport* m_viewport;
    QWidget* m_dialogParent;
    QString m_path;
    QString m_lastError;
    bool m_interactive = true;
    bool m_recoveryAvailable = false;
    LostSession m_recovery;
    QString m_sessionId; // "<pid>-<n>": the lock's and the autosave's names
    std::uint64_t m_changes = 0; // undo stack changes seen (an undo index alone repeats)
    std::uint64_t m_autosavedChanges = 0;
    bool m_autosaveDue = true; // no autosave this interval yet: the next change goes at once
    QTimer m_autosave; // every interval while changed
    QTimer m_autosaveSoon; // 0 ms: one autosave for a burst of changes in one event
};

} // namespace wisp
