#include "app/editor/ProjectController.h"

#include "app/editor/Document.h"
#include "io/AtomicFile.h"
#include "io/MeshReader.h"
#include "widgets/Viewport.h"

#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QSettings>
#include <QStandardPaths>
#include <QUndoStack>

#include <unistd.h>

namespace wisp {

namespace {

const char* kRecentKey = "files/recent";
const QString kLockPrefix = QStringLiteral("session");
const QString kAutosavePrefix = QStringLiteral("autosave");

io::CameraState cameraOf(const OrbitCamera& camera)
{
    return { camera.pivot(), camera.yaw(), camera.pitch(), camera.distance(), camera.fovYDegrees() };
}

// A lock's pid (first line) and project path (second line; absent in locks of older versions).
struct LockContent {
    long pid = 0;
    QString projectPath;
};

LockContent readLock(const QString& path)
{
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly))
        return {};
    const QList<QByteArray> lines = file.read(64 * 1024).split('\n');
    LockContent lock;
    lock.pid = lines.value(0).trimmed().toLong();
    lock.projectPath = QString::fromUtf8(lines.value(1));
    return lock;
}

} // namespace

ProjectController::ProjectController(Document* document, Viewport* viewport, QWidget* dialogParent)
    : QObject(dialogParent)
    , m_document(document)
    , m_viewport(viewport)
    , m_dialogParent(dialogParent)
{
    QDir().mkpath(dataFolder());
    // Saves killed mid-way left temporaries; their writers are gone (a live writer's stay).
    io::removeStaleTemporaryFiles(dataFolder().toStdString());
    for (const QString& recent : recentFiles())
        io::removeStaleTemporaryFiles(QFileInfo(recent).absolutePath().toStdString());
    findRecovery(); // before claiming a session, so that its files are never mistaken for ours
    claimSession();

    QUndoStack* stack = m_document->undoStack();
    connect(stack, &QUndoStack::indexChanged, this, &ProjectController::documentChanged);
    connect(stack, &QUndoStack::cleanChanged, this, [this](bool clean) {
        if (clean)
            documentSaved();
    });
    m_autosaveSoon.setSingleShot(true);
    m_autosaveSoon.setInterval(0);
    connect(&m_autosaveSoon, &QTimer::timeout, this, [this] {
        if (autosaveNow())
            m_autosaveDue = false;
    });
    m_autosave.setInterval(kAutosaveIntervalMs);
    connect(&m_autosave, &QTimer::timeout, this, &ProjectController::autosaveTick);
    m_autosave.start();
}

ProjectController::~ProjectController()
{
    // A clean exit: this session's work is saved or knowingly dropped. Another session's stays.
    QFile::remove(autosavePath());
    QFile::remove(sessionLockPath());
}

QString ProjectController::dataFolder() const
{
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
}

// The newest autosave of a session whose process is gone. Locks of live processes belong to other
// editors running now; a dead session's lock without an autosave had nothing unsaved and goes.
void ProjectController::findRecovery()
{
    QDateTime newest;
    const QDir folder(dataFolder());
    for (const QString& lockName : folder.entryList({ kLockPrefix + QStringLiteral("*.lock") }, QDir::Files)) {
        const QString lockPath = folder.filePath(lockName);
        const LockContent lock = readLock(lockPath);
        if (io::isProcessAlive(lock.pid))
            continue;
        // "session-<id>.lock" goes with "autosave-<id>.wisp" ("session.lock" with "autosave.wisp").
        const QString id = lockName.mid(kLockPrefix.size(), lockName.size() - kLockPrefix.size() - 5);
        const QFileInfo autosave(folder.filePath(kAutosavePrefix + id + QStringLiteral(".wisp")));
        if (!autosave.exists()) {
            QFile::remove(lockPath);
            continue;
        }
        if (newest.isValid() && autosave.lastModified() <= newest)
            continue;
        newest = autosave.lastModified();
        m_recovery = { lockPath, autosave.filePath(), lock.projectPath };
        m_recoveryAvailable = true;
    }
}

// This session's lock, under a name no other lock or autosave has (a pid may come back after a
// reboot while a lost session's files are still waiting to be recovered).
void ProjectController::claimSession()
{
    for (int n = 0; n < 1000; ++n) {
        m_sessionId = QStringLiteral("%1-%2").arg(::getpid()).arg(n);
        if (QFileInfo::exists(autosavePath()))
            continue;
        QFile lock(sessionLockPath());
        if (lock.open(QIODevice::WriteOnly | QIODevice::NewOnly)) {
            lock.write(QByteArray::number(static_cast<qint64>(::getpid())) + '\n');
            return;
        }
        if (!lock.exists())
            return; // the data folder cannot be written: nothing to protect the work with
    }
}

// The lock names the project, so that recovered work goes back to its file.
void ProjectController::writeLock()
{
    const QByteArray text = QByteArray::number(static_cast<qint64>(::getpid())) + '\n' + m_path.toUtf8() + '\n';
    // Best effort: a lock that cannot be written only means that a crash offers no recovery; the
    // artist's saves do not depend on it, so there is nothing to tell them.
    static_cast<void>(io::writeFileAtomically(
        sessionLockPath().toStdString(), [&](std::ostream& out) { out.write(text.data(), text.size()); }));
}

QString ProjectController::sessionLockPath() const
{
    return dataFolder() + QStringLiteral("/%1-%2.lock").arg(kLockPrefix, m_sessionId);
}

QString ProjectController::autosavePath() const
{
    return dataFolder() + QStringLiteral("/%1-%2.wisp").arg(kAutosavePrefix, m_sessionId);
}

bool ProjectController::isModified() const
{
    return !m_document->undoStack()->isClean();
}

io::Project ProjectController::snapshot() const
{
    io::Project project = m_document->toProject();
    project.camera = cameraOf(m_viewport->camera());
    project.displayDensity = m_viewport->displayDensity();
    return project;
}

void ProjectController::fail(const QString& title, const QString& text)
{
    m_lastError = text;
    if (m_interactive)
        QMessageBox::warning(m_dialogParent, title, text);
    emit message(text);
}

void ProjectController::setPath(const QString& path)
{
    m_path = path;
    writeLock();
    emit currentPathChanged(path);
}

bool ProjectController::write(const QString& path)
{
    const auto written = io::writeProject(path.toStdString(), snapshot());
    if (!written) {
        fail(tr("Cannot save"), QString::fromStdString(written.error().toString()));
        return false;
    }
    return true;
}

bool ProjectController::save()
{
    if (m_path.isEmpty())
        return saveAs();
    if (!write(m_path))
        return false;
    m_document->undoStack()->setClean();
    addRecent(m_path);
    emit message(tr("Saved %1").arg(QDir::toNativeSeparators(m_path)));
    return true;
}

bool ProjectController::saveAs(const QString& chosen)
{
    QString path = chosen;
    if (path.isEmpty()) {
        if (!m_interactive)
            return false;
        path = QFileDialog::getSaveFileName(m_dialogParent, tr("Save Project"), m_path, tr(kFileFilter));
        if (path.isEmpty())
            return false;
    }
    if (QFileInfo(path).suffix().isEmpty())
        path += QStringLiteral(".wisp");
    if (!write(path))
        return false;
    setPath(path);
    m_document->undoStack()->setClean();
    addRecent(path);
    emit message(tr("Saved %1").arg(QDir::toNativeSeparators(path)));
    return true;
}

bool ProjectController::maybeSave()
{
    if (!isModified())
        return true;
    if (!m_interactive)
        return false; // never throw work away without being asked
    const QString name = m_path.isEmpty() ? tr("Untitled") : QFileInfo(m_path).fileName();
    const auto answer = QMessageBox::warning(m_dialogParent, tr("Unsaved changes"),
        tr("%1 has changes that are not saved. Save them?").arg(name),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
    if (answer == QMessageBox::Save)
        return save();
    return answer == QMessageBox::Discard;
}

bool ProjectController::newProject()
{
    if (!maybeSave())
        return false;
    m_document->reset();
    m_viewport->frameHead();
    setPath({});
    return true;
}

bool ProjectController::load(const QString& path, bool asRecovered, const QString& projectPath)
{
    io::Result<io::ProjectReadResult> read = io::readProject(path.toStdString(), io::readHeadFile);
    if (!read) {
        fail(tr("Cannot open project"), QString::fromStdString(read.error().toString()));
        return false;
    }
    io::ProjectReadResult result = std::move(read).value();
    const io::CameraState camera = result.project.camera;
    const float displayDensity = result.project.displayDensity;
    m_document->loadProject(std::move(result.project));
    setPath(projectPath);
    OrbitCamera& view = m_viewport->camera();
    view.setPivot(camera.pivot);
    view.setOrientation(camera.yawRadians, camera.pitchRadians);
    view.setDistance(camera.distanceMetres);
    view.setFovYDegrees(camera.fovYDegrees);
    m_viewport->setDisplayDensity(displayDensity);
    m_viewport->update();
    for (const std::string& warning : result.warnings)
        emit message(QString::fromStdString(warning));
    if (asRecovered)
        m_document->undoStack()->resetClean(); // recovered work is not saved anywhere yet
    else
        addRecent(path);
    return true;
}

bool ProjectController::open(const QString& chosen)
{
    QString path = chosen;
    if (path.isEmpty()) {
        if (!m_interactive)
            return false;
        path = QFileDialog::getOpenFileName(
            m_dialogParent, tr("Open Project"), QFileInfo(m_path).path(), tr(kFileFilter));
        if (path.isEmpty())
            return false;
    }
    if (!maybeSave())
        return false;
    return load(path, false, path);
}

QStringList ProjectController::recentFiles() const
{
    return QSettings().value(kRecentKey).toStringList();
}

void ProjectController::addRecent(const QString& path)
{
    QStringList recent = recentFiles();
    const QString absolute = QFileInfo(path).absoluteFilePath();
    recent.removeAll(absolute);
    recent.prepend(absolute);
    while (recent.size() > kMaxRecentFiles)
        recent.removeLast();
    QSettings().setValue(kRecentKey, recent);
    emit recentFilesChanged();
}

bool ProjectController::autosaveNow()
{
    if (!isModified() || m_changes == m_autosavedChanges || m_document->inStroke())
        return false;
    return writeAutosave();
}

bool ProjectController::writeAutosave()
{
    if (!io::writeProject(autosavePath().toStdString(), snapshot(), io::Backup::None))
        return false; // the next tick tries again; the artist's own saves are unaffected
    m_autosavedChanges = m_changes;
    emit autosaved(autosavePath());
    return true;
}

void ProjectController::documentChanged()
{
    ++m_changes;
    if (m_autosaveDue && isModified())
        m_autosaveSoon.start();
}

void ProjectController::autosaveTick()
{
    // A tick with nothing to save ends a quiet interval: the next change is autosaved at once.
    m_autosaveDue = !autosaveNow();
}

void ProjectController::documentSaved()
{
    // The file holds the work now; an older autosave must not be offered over it after a crash.
    QFile::remove(autosavePath());
    m_autosavedChanges = m_changes;
    m_autosaveDue = true;
}

bool ProjectController::recover()
{
    if (!m_recoveryAvailable)
        return false;
    m_recoveryAvailable = false;
    if (!load(m_recovery.autosavePath, true, m_recovery.projectPath))
        return false;
    // The work is this session's now: its own autosave protects it, the lost session's files go.
    writeAutosave();
    QFile::remove(m_recovery.autosavePath);
    QFile::remove(m_recovery.lockPath);
    emit message(m_recovery.projectPath.isEmpty() ? tr("Recovered the work of the last session; save it to keep it")
                                                  : tr("Recovered the unsaved work on %1; save it to keep it")
                                                        .arg(QDir::toNativeSeparators(m_recovery.projectPath)));
    return true;
}

void ProjectController::discardRecovery()
{
    if (!m_recoveryAvailable)
        return;
    m_recoveryAvailable = false;
    QFile::remove(m_recovery.autosavePath);
    QFile::remove(m_recovery.lockPath);
}

} // namespace wisp
