#pragma once
// Thumbnails of presets for the preset browser, as Blender's asset browser shows previews: the
// built-in head with the preset applied, groomed and draped at rest (SettledScene) and drawn by a
// hidden Viewport's renderImage, the same way `wisp --render` and File ▸ Render Image draw.
//
// Cached on disk under <cache>/preset-thumbnails/<hash>.png, the hash of the preset file's bytes
// (and of what the thumbnail is made with), so a preset saved anew gets a new thumbnail and an
// unchanged one is read back at once. Making one is one job at a time: the groom and the drape run
// on a worker thread (the UI keeps drawing), then the image is drawn on the GUI thread (a few
// milliseconds at this size). Jobs only run while enabled (the browser is on screen).
//
// Thread: GUI; the worker touches only its own job.

#include <QByteArray>
#include <QHash>
#include <QImage>
#include <QObject>
#include <QString>

#include <atomic>
#include <deque>
#include <memory>
#include <thread>

namespace wisp {

class Viewport;

class PresetThumbnails : public QObject {
    Q_OBJECT
public:
    static constexpr int kSidePixels = 64;

    explicit PresetThumbnails(QObject* parent = nullptr);
    ~PresetThumbnails() override; // cancels and waits for the running job

    // Where the thumbnails are cached.
    static QString cacheFolder();
    // The cache file of a preset with these bytes.
    static QString cachePath(const QByteArray& presetBytes);

    // A thumbnail for the preset at `path` holding `presetBytes`: ready() at once when cached,
    // else once made (a newer request for the same path replaces an older one still waiting).
    void request(const QString& path, const QByteArray& presetBytes);
    // Jobs run only while enabled; requests wait meanwhile.
    void setEnabled(bool enabled);
    bool busy() const { return m_running || !m_queue.empty(); }
    int made() const { return m_made; } // thumbnails rendered (not read from the cache) so far

signals:
    void ready(const QString& path, const QImage& thumbnail);

private:
    struct Job;
    void startNext();
    void finish(std::shared_ptr<Job> job);

    std::deque<std::shared_ptr<Job>> m_queue;
    std::shared_ptr<Job> m_running;
    std::thread m_worker;
    std::unique_ptr<Viewport> m_viewport; // hidden; made for the first thumbnail
    bool m_enabled = false;
    int m_made = 0;
};

} // namespace wisp
