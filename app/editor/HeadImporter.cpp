#include "app/editor/HeadImporter.h"

#include "io/MeshReader.h"

#include <QCoreApplication>
#include <QFileInfo>
#include <QMetaObject>
#include <QProgressDialog>

#include <atomic>
#include <exception>

namespace wisp {

struct HeadImporter::Job {
    QString path;
    io::HeadPlacementSettings settings;
    std::shared_ptr<ImportedHead> head; // the result, or
    QString error; // why there is none
    std::atomic<bool> cancelled{ false };
    std::atomic<bool> done{ false };
};

HeadImporter::HeadImporter(QWidget* dialogParent)
    : QObject(dialogParent)
    , m_dialogParent(dialogParent)
{
}

HeadImporter::~HeadImporter()
{
    if (m_job)
        m_job->cancelled = true;
    if (m_worker.joinable())
        m_worker.join();
}

bool HeadImporter::start(const QString& path, const io::HeadPlacementSettings& settings)
{
    if (busy())
        return false;
    if (m_worker.joinable())
        m_worker.join();
    auto job = std::make_shared<Job>();
    job->path = path;
    job->settings = settings;
    m_job = job;
    m_finished = false;

    m_progress
        = new QProgressDialog(tr("Reading %1…").arg(QFileInfo(path).fileName()), tr("Cancel"), 0, 0, m_dialogParent);
    m_progress->setWindowTitle(tr("Open Head"));
    m_progress->setMinimumDuration(300); // quick files never flash a dialog
    m_progress->setAttribute(Qt::WA_DeleteOnClose);
    connect(m_progress, &QProgressDialog::canceled, this, [this, job] {
        job->cancelled = true;
        m_finished = true;
        m_progress = nullptr;
    });

    m_worker = std::thread([this, job] {
        try {
            io::Result<io::MeshReadResult> read = io::readMesh(job->path.toStdString());
            if (!read) {
                job->error = QString::fromStdString(read.error().toString());
            } else {
                auto head = std::make_shared<ImportedHead>();
                io::MeshReadResult result = std::move(read).value();
                head->asRead = std::move(result.mesh);
                head->mesh = head->asRead;
                io::HeadPlacementSettings settings = job->settings;
                head->chosenUp = settings.up;
                if (io::formatFixesUpAxis(job->path.toStdString()))
                    settings.up = io::Axis::PosY;
                head->placement = io::placeHead(head->mesh, settings);
                head->path = job->path;
                for (const std::string& w : result.warnings)
                    head->warnings << QString::fromStdString(w);
                // The same check as wisp-cli's: a flat or absurdly large head is refused here,
                // before the BVH, the collider and the groom are built on it.
                if (std::string problem = io::checkPlacedHead(head->mesh); !problem.empty())
                    job->error = job->path + QStringLiteral(": ") + QString::fromStdString(problem);
                else
                    job->head = std::move(head);
            }
        } catch (const std::exception& e) { // out of memory on a huge file
            job->error = job->path + QStringLiteral(": ") + QString::fromUtf8(e.what());
        }
        job->done = true;
        QMetaObject::invokeMethod(
            this, [this, job] { deliver(job); }, Qt::QueuedConnection);
    });
    return true;
}

void HeadImporter::deliver(std::shared_ptr<Job> job)
{
    if (job != m_job)
        return;
    const bool wanted = !job->cancelled;
    if (m_progress) {
        m_progress->disconnect(this); // closing a progress dialog emits canceled(): not the artist's
        m_progress->close();
        m_progress = nullptr;
    }
    m_finished = true;
    if (!wanted)
        return;
    if (job->head)
        emit imported(job->head);
    else
        emit failed(job->error);
}

void HeadImporter::waitForFinished()
{
    if (m_worker.joinable())
        m_worker.join();
    QCoreApplication::sendPostedEvents(this); // the queued delivery
}

} // namespace wisp
