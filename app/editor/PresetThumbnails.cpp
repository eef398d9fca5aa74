#include "app/editor/PresetThumbnails.h"

#include "app/editor/Document.h"
#include "app/editor/ImageFiles.h"
#include "app/editor/SettledScene.h"
#include "io/PresetFile.h"
#include "sim/geometry/Body.h"
#include "widgets/Viewport.h"

#include <QCryptographicHash>

#include <QDir>
#include <QFileInfo>
#include <QMetaObject>
#include <QStandardPaths>
#include <cmath>

namespace wisp {

namespace {
// Changes whenever thumbnails are made differently, so old cache entries are not reused.
constexpr int kSupersampling = 4;
constexpr char kRecipe[] = "wisp-thumbnail 3: built-in head, drape only, framed above the chin, 256 px scaled to 64";
} // namespace

struct PresetThumbnails::Job {
    QString path;
    QByteArray bytes;
    SceneToSettle scene; // filled on the GUI thread
    SettledFrame settled; // the worker's result
    std::atomic<bool> cancelled{ false };
};

PresetThumbnails::PresetThumbnails(QObject* parent)
    : QObject(parent)
{
}

PresetThumbnails::~PresetThumbnails()
{
    if (m_running)
        m_running->cancelled = true;
    if (m_worker.joinable())
        m_worker.join();
}

QString PresetThumbnails::cacheFolder()
{
    return QStandardPaths::writableLocation(QStandardPaths::CacheLocation) + QStringLiteral("/preset-thumbnails");
}

QString PresetThumbnails::cachePath(const QByteArray& presetBytes)
{
    QCryptographicHash hash(QCryptographicHash::Sha1);
    hash.addData(QByteArrayView(kRecipe));
    hash.addData(presetBytes);
    return cacheFolder() + QLatin1Char('/') + QString::fromLatin1(hash.result().toHex()) + QStringLiteral(".png");
}

void PresetThumbnails::request(const QString& path, const QByteArray& presetBytes)
{
    const QImage cached(cachePath(presetBytes));
    if (!cached.isNull()) {
        emit ready(path, cached);
        return;
    }
    for (auto it = m_queue.begin(); it != m_queue.end();)
        it = (*it)->path == path ? m_queue.erase(it) : it + 1;
    auto job = std::make_shared<Job>();
    job->path = path;
    job->bytes = presetBytes;
    m_queue.push_back(std::move(job));
    startNext();
}

void PresetThumbnails::setEnabled(bool enabled)
{
    m_enabled = enabled;
    startNext();
}

void PresetThumbnails::startNext()
{
    if (!m_enabled || m_running || m_queue.empty())
        return;
    std::shared_ptr<Job> job = m_queue.front();
    m_queue.pop_front();
    io::Result<io::PresetReadResult> read = io::parsePreset(job->bytes.toStdString(), job->path.toStdString());
    if (!read) { // the browser lists it greyed; no thumbnail
        startNext();
        return;
    }
    Document document; // the built-in head and hairstyle
    document.applyPreset(read.value().preset);
    job->scene = SceneToSettle{ document.head(), document.regions(), document.soloRegion(), document.parameters(), {} };
    m_running = job;
    if (m_worker.joinable())
        m_worker.join();
    m_worker = std::thread([this, job] {
        job->settled = settleScene(job->scene, 0, 1, [job] { return job->cancelled.load(); });
        QMetaObject::invokeMethod(
            this, [this, job] { finish(job); }, Qt::QueuedConnection);
    });
}

void PresetThumbnails::finish(std::shared_ptr<Job> job)
{
    if (job != m_running)
        return;
    m_running.reset();
    if (job->settled.frame) {
        if (!m_viewport) {
            m_viewport = std::make_unique<Viewport>();
            m_viewport->setShowGrowthOverlay(false);
            m_viewport->setShowGrid(false);
            m_viewport->resize(kSidePixels, kSidePixels);
        }
        m_viewport->setHead(job->scene.head);
        m_viewport->setBody(
            job->scene.values.get(Param::Body) != 0.0 ? defaultBody(job->scene.head) : std::vector<Capsule>{});
        m_viewport->setFrame(job->settled.frame);
        // Framed on the head above the chin, where a hairstyle shows, not the whole bust; drawn at
        // four times the size and scaled down, because one strand at 64 pixels is a fiftieth of a
        // pixel wide and its coverage would round away in an 8-bit frame.
        Aabb bounds = boundsOf(job->scene.head);
        bounds.min.y = bounds.max.y - 0.6f * (bounds.max.y - bounds.min.y);
        Viewport::ImageOptions options;
        options.frameBounds = bounds;
        const QImage large = m_viewport->renderImage(QSize(kSidePixels, kSidePixels) * kSupersampling, options);
        const QImage image = large.isNull()
            ? QImage()
            : large.scaled(kSidePixels, kSidePixels, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
        if (!image.isNull()) {
            ++m_made;
            QDir().mkpath(cacheFolder());
            writePngAtomically(cachePath(job->bytes), image); // a cache: a failed write only costs a redraw
            emit ready(job->path, image);
        }
    }
    startNext();
}

} // namespace wisp
