#pragma once
// The timeline dock (bottom of the window): the document's frame range and fps, the bake with its
// progress and Cancel, and playback and scrubbing of the baked cache.
//
// While a cache is shown (after a bake, or when the slider or the dock's Play moves through it),
// the viewport draws the cached frame, exactly the baked positions, and the live simulation is
// paused: cacheFrameShown asks the window for both. Leaving the cache (leaveCache: Esc, or Play in
// the main toolbar) hands the viewport back to the live simulation.
//
// Any document change that changes the result (parameters, regions, weights, style, head, head
// motion, range) marks the cache stale, named by its undo command's text where there is one; a
// stale cache still scrubs and plays, labelled so.
//
// Thread: GUI.

#include "app/editor/BakeController.h"
#include "sim/solver/Frame.h"

#include <QString>
#include <QWidget>

#include <optional>

class QDoubleSpinBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QSlider;
class QSpinBox;
class QTimer;
class QToolButton;

namespace wisp {

class Document;

class TimelineDock : public QWidget {
    Q_OBJECT
public:
    explicit TimelineDock(Document* document, QWidget* parent = nullptr);

    BakeController* bake() const { return m_bake; }
    bool showingCache() const { return m_showingCache; }
    bool isStale() const { return m_stale; }
    QString staleReason() const { return m_staleReason; }
    int currentFrame() const; // the slider's frame
    bool isPlayingCache() const;
    // True while the timeline is on a frame (scrubbed, gone to a key, a cached frame shown) rather
    // than following the live simulation; frameSeconds() is then that frame's time, (f - 1) / fps
    // (sim/motion/FrameTime.h), where the head drag and Set Key put keys.
    bool isOnFrame() const { return m_onFrame; }
    std::optional<double> frameSeconds() const;

    // Widgets, for tests and the window's wiring.
    QSpinBox* firstFrameBox() const { return m_first; }
    QSpinBox* lastFrameBox() const { return m_last; }
    QDoubleSpinBox* fpsBox() const { return m_fps; }
    QToolButton* playButton() const { return m_playButton; }
    QSlider* slider() const { return m_slider; }
    QLabel* frameLabel() const { return m_frameLabel; }
    QPushButton* bakeButton() const { return m_bakeButton; }
    QPushButton* cancelButton() const { return m_cancelButton; }
    QProgressBar* progressBar() const { return m_progress; }
    QLabel* statusLabel() const { return m_status; }
    QPushButton* exportButton() const { return m_exportButton; }

    // Writes the last bake (BakeExport.h): .usda, or a .hair sequence with # in the name. Returns
    // the error (also sent as message()); empty on success.
    QString exportBake(const QString& path);

public slots:
    void startBake();
    void leaveCache(); // back to the live simulation (nothing happens when it is already live)
    // The slider to `frame` (clamped to its range), as a scrub: the cached frame shown if baked.
    void goToFrame(int frame);
    // The slider to the frame nearest `seconds` at the document's fps (a selected key's time).
    void goToSeconds(double seconds);
    void setPlayingCache(bool playing);
    void chooseExport(); // asks where (a file dialog), then exportBake

signals:
    void bakeStarted(); // the window pauses the live simulation: both would share the cores
    void cacheFrameShown(wisp::FramePtr frame); // draw this instead of the live simulation
    void cacheLeft(); // draw the live simulation again
    void message(const QString& text); // for the status bar

private:
    void showRange(); // the spin boxes from the document
    void commitRange(); // the spin boxes to the document (one undo step)
    void markStale(const QString& reason);
    void showCacheFrame(int frame);
    void scrubbedTo(int frame); // the slider moved: on that frame, showing it if baked
    void showSliderRange(); // the cache's range once baked, the document's before
    void advancePlayback();
    void updateStatus();
    void updateControls();

    Document* m_document;
    BakeController* m_bake;
    QSpinBox* m_first = nullptr;
    QSpinBox* m_last = nullptr;
    QDoubleSpinBox* m_fps = nullptr;
    QToolButton* m_playButton = nullptr;
    QSlider* m_slider = nullptr;
    QLabel* m_frameLabel = nullptr;
    QPushButton* m_bakeButton = nullptr;
    QPushButton* m_cancelButton = nullptr;
    QPushButton* m_exportButton = nullptr;
    QProgressBar* m_progress = nullptr;
    QLabel* m_status = nullptr;
    QTimer* m_playTimer = nullptr;

    bool m_showingCache = false;
    bool m_onFrame = false;
    bool m_stale = false;
    QString m_staleReason;
    QString m_bakeError; // the last bake's refusal, shown until the next bake
    bool m_changedDuringBake = false;
    QString m_changeDuringBake;
    bool m_nameFromUndoStack = false; // a change was just marked: its undo text names it better
    int m_undoIndex = 0;
};

} // namespace wisp
