#pragma once
// The File menu and what it does: projects (new, open, recent, save, save as, autosave and
// recovery through ProjectController), heads (open on a worker thread with HeadImporter, change
// the import scale), hair (import cyHair / USC .data as a region of strands, export the frame or
// the rest pose), images (RenderActions: Render Image, Render Turntable), and quit.
//
// Thread: GUI.

#include "io/HeadOrientation.h"

#include <QObject>
#include <QString>

#include <functional>
#include <memory>
#include <optional>

class QAction;
class QMainWindow;
class QMenu;

namespace wisp {

class Document;
class HeadImporter;
class ProjectController;
class RenderActions;
class SimulationHost;
class Viewport;
struct ImportedHead;

class FileMenu : public QObject {
    Q_OBJECT
public:
    FileMenu(QMainWindow* window, Document* document, SimulationHost* simulation, Viewport* viewport);
    ~FileMenu() override;

    QMenu* menu() const { return m_menu; }
    ProjectController* projects() const { return m_projects; }
    HeadImporter* headImporter() const { return m_importer; }
    QAction* saveAsAction() const { return m_saveAs; } // Ctrl+Shift+S
    RenderActions* renderActions() const { return m_render; } // Render Image…, Render Turntable…

    // Opens whatever `path` is: a project (.wisp), else a head mesh. For `wisp FILE` and drops.
    bool openAny(const QString& path);
    // Starts reading a head; the document takes it when the read is done (see HeadImporter).
    bool openHead(const QString& path);
    // Reads cyHair / USC .data strands into a new region; errors in a dialog (and the result).
    QString importHair(const QString& path);
    // Writes the newest frame's hair; returns the error, empty on success.
    QString exportHair(const QString& path, bool restPose, bool keysOnly);
    // Places the last head read anew at `metresPerUnit`, with `up` as the file's up axis (nullopt:
    // found from its shape); one undo step (Head Scale, Head Up Axis). False when no head came
    // from a file.
    bool placeAgain(float metresPerUnit, std::optional<io::Axis> up);
    // After the window shows: offers the last session's unsaved work if it ended without closing.
    void offerRecovery();
    // What the artist answers to the recovery question: Later keeps the work for the next start.
    enum class RecoveryAnswer { Recover, Discard, Later };
    using RecoveryPrompt = std::function<RecoveryAnswer(const QString& question)>;
    // Replaces the recovery message box (tests; it is asked even when not interactive).
    void setRecoveryPrompt(RecoveryPrompt prompt) { m_recoveryPrompt = std::move(prompt); }
    // Without dialogs (tests): problems go only to message(); questions take their default.
    void setInteractive(bool interactive);

signals:
    void message(const QString& text);

private:
    void buildMenu();
    void rebuildRecentMenu();
    void takeHead(const std::shared_ptr<const ImportedHead>& head);
    void changeHeadScale();
    void warn(const QString& title, const QString& text);

    QMainWindow* m_window;
    Document* m_document;
    SimulationHost* m_simulation;
    Viewport* m_viewport;
    ProjectController* m_projects;
    HeadImporter* m_importer;
    QMenu* m_menu = nullptr;
    QMenu* m_recentMenu = nullptr;
    QAction* m_saveAs = nullptr;
    RenderActions* m_render = nullptr;
    QMenu* m_upMenu = nullptr; // Head Up Axis: "From Its Shape", then +Y, +Z, -Z, +X, -X, -Y
    std::shared_ptr<const ImportedHead> m_lastHead; // as read, to place again at another scale
    bool m_interactive = true;
    RecoveryPrompt m_recoveryPrompt;
};

} // namespace wisp
