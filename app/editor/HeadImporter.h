#pragma once
// Reads a head file on a worker thread so the window never freezes, with a progress dialog for
// files that take a moment (a 270k-triangle scan takes about a second), then places it as
// io/HeadPlacement.h says (unit from its skull's width unless given, up axis from its shape unless
// given, centred).
//
// The readers report no fraction done, so the dialog is a busy indicator with Cancel; a cancelled
// read finishes in the background and its result is dropped.
//
// Thread: GUI, except the worker, which touches only its own Job.

#include "io/HeadPlacement.h"
#include "sim/geometry/TriangleMesh.h"

#include <QObject>
#include <QString>
#include <QStringList>

#include <memory>
#include <optional>
#include <thread>

class QProgressDialog;
class QWidget;

namespace wisp {

struct ImportedHead {
    TriangleMesh mesh; // placed: metres, centred, +Y up
    TriangleMesh asRead; // as the file holds it, to place again at another scale
    io::HeadPlacement placement;
    std::optional<io::Axis> chosenUp; // the up axis the artist named; nullopt: from the shape
    QString path;
    QStringList warnings;
};

class HeadImporter : public QObject {
    Q_OBJECT
public:
    explicit HeadImporter(QWidget* dialogParent);
    ~HeadImporter() override; // waits for a read still running

    // Starts reading; refused (false) while another read runs.
    bool start(const QString& path, const io::HeadPlacementSettings& settings = {});
    bool busy() const { return m_worker.joinable() && !m_finished; }
    // Blocks until the running read is delivered (tests, command-line start).
    void waitForFinished();

signals:
    void imported(std::shared_ptr<const wisp::ImportedHead> head);
    void failed(const QString& message);

private:
    struct Job;
    void deliver(std::shared_ptr<Job> job);

    QWidget* m_dialogParent;
    QProgressDialog* m_progress = nullptr;
    std::thread m_worker;
    std::shared_ptr<Job> m_job;
    bool m_finished = true;
};

} // namespace wisp
