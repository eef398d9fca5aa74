#include "app/editor/ProjectController.h"

#include "app/editor/Document.h"
#include "io/MeshReader.h"
#include "widgets/Viewport.h"

#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QSettings>
#include <QStandardPaths>

#include <unistd.h>

namespace wisp {

namespace {

constexpr int kAutosaveMinutes = 3;
const char* kRecentKey = "files/recent";

io::CameraState cameraOf(const OrbitCamera& camera)
{
    return {camera.pivot(), camera.yaw(), camera.pitch(), camera.distance(), camera.fovYDegrees()};
}

}  // namespace

ProjectController::ProjectController(Document* document, Viewport* viewport, QWidget* dialogParent)
    : QObject(dialogParent), m_document(document), m_viewport(viewport), m_dialogParent(dialogParent)
{
    QDir().mkpath(dataFolder());
    // A lock left by the last session means it did not close; its autosave is the work it lost.
    QFile lock(dataFolder() + QStringLiteral("/session.lock"));
    m_recoveryAvailable = lock.exists() && QFileInfo::exists(autosavePath());
    if (lock.open(QIODevice::WriteOnly | QIODevice::Truncate))
        lock.write(QByteArray::number(static_cast<qint64>(::getpid())));
    m_autosave.setInterval(kAutosaveMinutes * 60 * 1000);
    connect(&m_autosave, &QTimer::timeout, this, &ProjectController::autosaveNow);
    m_autosave.start();
}

ProjectController::~ProjectController()
{
    if (!m_recoveryAvailable)  // a recovery not yet taken or refused stays for the next start
        QFile::remove(autosavePath());
    QFile::remove(dataFolder() + QStringLiteral("/session.lock"));
}

QString ProjectController::dataFolder() const
{
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
}

QString ProjectController::autosavePath() const { return dataFolder() + QStringLiteral("/autosave.wisp"); }

bool ProjectController::isModified() const { return !m_document->undoStack()->isClean(); }

io::Project ProjectController::snapshot() const
{
    io::Project project = m_document->toProject();
    project.camera = cameraOf(m_viewport->camera());
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
        return false;  // never throw work away without being asked
    const QString name = m_path.isEmpty() ? tr("Untitled") : QFileInfo(m_path).fileName();
    const auto answer = QMessageBox::warning(
        m_dialogParent, tr("Unsaved changes"), tr("%1 has changes that are not saved. Save them?").arg(name),
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

bool ProjectController::load(const QString& path, bool asRecovered)
{
    const io::HeadLoader loader = [](const std::string& headPath) -> io::Result<TriangleMesh> {
        io::Result<io::MeshReadResult> mesh = io::readMesh(headPath);
        if (!mesh)
            return mesh.error();
        return std::move(mesh).value().mesh;
    };
    io::Result<io::ProjectReadResult> read = io::readProject(path.toStdString(), loader);
    if (!read) {
        fail(tr("Cannot open project"), QString::fromStdString(read.error().toString()));
        return false;
    }
    io::ProjectReadResult result = std::move(read).value();
    const io::CameraState camera = result.project.camera;
    m_document->loadProject(std::move(result.project));
    OrbitCamera& view = m_viewport->camera();
    view.setPivot(camera.pivot);
    view.setOrientation(camera.yawRadians, camera.pitchRadians);
    view.setDistance(camera.distanceMetres);
    view.setFovYDegrees(camera.fovYDegrees);
    m_viewport->update();
    for (const std::string& warning : result.warnings)
        emit message(QString::fromStdString(warning));
    if (asRecovered) {
        m_document->undoStack()->resetClean();  // recovered work is not saved anywhere yet
        setPath({});
    } else {
        setPath(path);
        addRecent(path);
    }
    return true;
}

bool ProjectController::open(const QString& chosen)
{
    QString path = chosen;
    if (path.isEmpty()) {
        if (!m_interactive)
            return false;
        path = QFileDialog::getOpenFileName(m_dialogParent, tr("Open Project"), QFileInfo(m_path).path(), tr(kFileFilter));
        if (path.isEmpty())
            return false;
    }
    if (!maybeSave())
        return false;
    return load(path, false);
}

QStringList ProjectController::recentFiles() const { return QSettings().value(kRecentKey).toStringList(); }

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
    const int index = m_document->undoStack()->index();
    if (!isModified() || index == m_autosavedIndex || m_document->inStroke())
        return false;
    if (!io::writeProject(autosavePath().toStdString(), snapshot()))
        return false;  // the next tick tries again; the artist's own saves are unaffected
    m_autosavedIndex = index;
    return true;
}

bool ProjectController::recover()
{
    if (!m_recoveryAvailable)
        return false;
    m_recoveryAvailable = false;
    if (!load(autosavePath(), true))
        return false;
    emit message(tr("Recovered the work of the last session; save it to keep it"));
    return true;
}

void ProjectController::discardRecovery()
{
    m_recoveryAvailable = false;
    QFile::remove(autosavePath());
}

}  // namespace wisp
