#include "app/editor/TimelineDock.h"

#include "app/editor/BakeExport.h"
#include "app/editor/Document.h"
#include "sim/params/Parameters.h"

#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QStyle>
#include <QTimer>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>

#include <cmath>

namespace wisp {

TimelineDock::TimelineDock(Document* document, QWidget* parent)
    : QWidget(parent)
    , m_document(document)
    , m_bake(new BakeController(this))
{
    m_first = new QSpinBox;
    m_first->setObjectName(QStringLiteral("timelineFirstFrame"));
    m_first->setRange(1, BakeRange::kMaxFrame);
    m_first->setToolTip(tr("First frame of the range to bake (frame 1 is 0 s, the hair draped at rest)"));
    m_last = new QSpinBox;
    m_last->setObjectName(QStringLiteral("timelineLastFrame"));
    m_last->setRange(1, BakeRange::kMaxFrame);
    m_last->setToolTip(tr("Last frame of the range to bake (frame f is at (f − 1) / fps seconds)"));
    m_fps = new QDoubleSpinBox;
    m_fps->setObjectName(QStringLiteral("timelineFps"));
    m_fps->setRange(BakeRange::kMinFps, BakeRange::kMaxFps);
    m_fps->setDecimals(3);
    m_fps->setSuffix(tr(" fps"));
    m_fps->setToolTip(tr("Frames per second of the bake and of playback (frames/s)"));
    for (QAbstractSpinBox* box : { static_cast<QAbstractSpinBox*>(m_first), static_cast<QAbstractSpinBox*>(m_last),
             static_cast<QAbstractSpinBox*>(m_fps) })
        box->setKeyboardTracking(false); // one undo step per value entered, not per digit typed
    connect(m_first, &QSpinBox::valueChanged, this, &TimelineDock::commitRange);
    connect(m_last, &QSpinBox::valueChanged, this, &TimelineDock::commitRange);
    connect(m_fps, &QDoubleSpinBox::valueChanged, this, &TimelineDock::commitRange);

    m_playButton = new QToolButton;
    m_playButton->setObjectName(QStringLiteral("timelinePlay"));
    m_playButton->setCheckable(true);
    m_playButton->setIcon(style()->standardIcon(QStyle::SP_MediaPlay));
    m_playButton->setToolTip(tr("Play the baked cache at the timeline's fps, looping"));
    connect(m_playButton, &QToolButton::toggled, this, &TimelineDock::setPlayingCache);
    m_slider = new QSlider(Qt::Horizontal);
    m_slider->setObjectName(QStringLiteral("timelineSlider"));
    m_slider->setToolTip(tr("The current frame: where the head's keys are set; after a bake the viewport shows the "
                            "baked frame (Esc goes back to live)"));
    m_slider->setPageStep(1);
    connect(m_slider, &QSlider::valueChanged, this, &TimelineDock::scrubbedTo);
    m_frameLabel = new QLabel;
    m_frameLabel->setObjectName(QStringLiteral("timelineFrameLabel"));
    m_frameLabel->setMinimumWidth(fontMetrics().horizontalAdvance(QStringLiteral("frame 000000 (stale)")));

    m_bakeButton = new QPushButton(tr("&Bake"));
    m_bakeButton->setObjectName(QStringLiteral("timelineBake"));
    m_bakeButton->setToolTip(tr("Simulate the frame range with the head's motion into a cache in memory"));
    connect(m_bakeButton, &QPushButton::clicked, this, &TimelineDock::startBake);
    m_progress = new QProgressBar;
    m_progress->setObjectName(QStringLiteral("timelineProgress"));
    m_progress->setFormat(tr("frame %v of %m"));
    m_cancelButton = new QPushButton(tr("Cancel"));
    m_cancelButton->setObjectName(QStringLiteral("timelineCancel"));
    m_cancelButton->setToolTip(tr("Stop the bake within one step; the previous cache, if any, stays"));
    connect(m_cancelButton, &QPushButton::clicked, m_bake, &BakeController::cancel);
    m_exportButton = new QPushButton(tr("&Export…"));
    m_exportButton->setObjectName(QStringLiteral("timelineExport"));
    m_exportButton->setToolTip(tr("Write the bake as USD text (.usda, one time sample per frame) or as a "
                                  ".hair sequence (hair.####.hair, one file per frame)"));
    connect(m_exportButton, &QPushButton::clicked, this, &TimelineDock::chooseExport);
    m_status = new QLabel;
    m_status->setObjectName(QStringLiteral("timelineStatus"));
    m_status->setWordWrap(true);

    auto* rangeRow = new QHBoxLayout;
    rangeRow->addWidget(new QLabel(tr("Frames")));
    rangeRow->addWidget(m_first);
    rangeRow->addWidget(new QLabel(QStringLiteral("–")));
    rangeRow->addWidget(m_last);
    rangeRow->addWidget(m_fps);
    rangeRow->addSpacing(12);
    rangeRow->addWidget(m_playButton);
    rangeRow->addWidget(m_slider, 1);
    rangeRow->addWidget(m_frameLabel);
    auto* bakeRow = new QHBoxLayout;
    bakeRow->addWidget(m_bakeButton);
    bakeRow->addWidget(m_progress);
    bakeRow->addWidget(m_cancelButton);
    bakeRow->addWidget(m_exportButton);
    bakeRow->addWidget(m_status, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(rangeRow);
    layout->addLayout(bakeRow);

    m_playTimer = new QTimer(this);
    connect(m_playTimer, &QTimer::timeout, this, &TimelineDock::advancePlayback);

    connect(m_bake, &BakeController::progress, this, [this](int done, int total) {
        m_progress->setMaximum(total);
        m_progress->setValue(done);
    });
    connect(m_bake, &BakeController::finished, this, [this] {
        const BakeCache& cache = m_bake->baked()->cache;
        m_stale = m_changedDuringBake;
        m_staleReason = m_changeDuringBake;
        showSliderRange();
        {
            const QSignalBlocker quiet(m_slider);
            m_slider->setValue(cache.range.firstFrame);
        }
        scrubbedTo(cache.range.firstFrame);
        updateControls();
    });
    connect(m_bake, &BakeController::failed, this, [this](const QString& why) {
        m_bakeError = why;
        emit message(tr("Bake refused: %1").arg(why));
        updateControls();
    });
    connect(m_bake, &BakeController::cancelled, this, [this] {
        emit message(tr("Bake cancelled after %1 frames; nothing was kept").arg(m_bake->framesDone()));
        updateControls();
    });

    // Every change that changes the result marks the cache stale.
    connect(document, &Document::parameterChanged, this,
        [this](Param id) { markStale(tr("%1 changed").arg(QString::fromUtf8(parameterInfo(id).label))); });
    connect(document, &Document::parametersReplaced, this, [this] { markStale(tr("the parameters changed")); });
    connect(document, &Document::headChanged, this, [this] { markStale(tr("the head changed")); });
    connect(document, &Document::regionsChanged, this, [this] { markStale(tr("the regions changed")); });
    connect(document, &Document::regionParameterChanged, this, [this] { markStale(tr("a region's wisp changed")); });
    connect(document, &Document::regionWeightsChanged, this, [this] { markStale(tr("the painted weights changed")); });
    connect(document, &Document::styleChanged, this, [this] { markStale(tr("the styling changed")); });
    connect(document, &Document::headMotionChanged, this, [this] { markStale(tr("the head motion changed")); });
    connect(document, &Document::timelineChanged, this, [this] {
        showRange();
        markStale(tr("the frame range changed"));
    });
    // The undo command's text names the change better: it arrives just after the change itself.
    m_undoIndex = document->undoStack()->index();
    connect(document->undoStack(), &QUndoStack::indexChanged, this, [this](int index) {
        QUndoStack* stack = m_document->undoStack();
        if (m_nameFromUndoStack) {
            const QString text
                = index >= m_undoIndex ? stack->text(index - 1) : tr("undo of %1").arg(stack->text(index));
            if (!stack->text(index >= m_undoIndex ? index - 1 : index).isEmpty()) {
                if (m_bake->isRunning())
                    m_changeDuringBake = text;
                else
                    m_staleReason = text;
            }
            m_nameFromUndoStack = false;
        }
        m_undoIndex = index;
        updateStatus();
    });

    showRange();
    updateControls();
}

int TimelineDock::currentFrame() const
{
    return m_slider->value();
}

std::optional<double> TimelineDock::frameSeconds() const
{
    if (!m_onFrame)
        return std::nullopt;
    const double fps = m_showingCache ? m_bake->baked()->cache.range.fps : m_document->timeline().fps;
    return secondsOfFrame(m_slider->value(), fps);
}

void TimelineDock::goToFrame(int frame)
{
    {
        const QSignalBlocker quiet(m_slider); // once, below, even when the slider is there already
        m_slider->setValue(frame); // clamped to the range
    }
    scrubbedTo(m_slider->value());
}

void TimelineDock::goToSeconds(double seconds)
{
    goToFrame(frameAtSeconds(seconds, m_document->timeline().fps));
}

void TimelineDock::scrubbedTo(int frame)
{
    m_onFrame = true;
    showCacheFrame(frame);
    updateStatus();
}

void TimelineDock::showSliderRange()
{
    const BakeRange& range = m_bake->baked() ? m_bake->baked()->cache.range : m_document->timeline();
    const QSignalBlocker quiet(m_slider);
    m_slider->setRange(range.firstFrame, range.lastFrame);
}

bool TimelineDock::isPlayingCache() const
{
    return m_playTimer->isActive();
}

void TimelineDock::showRange()
{
    const BakeRange& range = m_document->timeline();
    const QSignalBlocker a(m_first), b(m_last), c(m_fps);
    m_first->setValue(range.firstFrame);
    m_last->setValue(range.lastFrame);
    m_fps->setValue(range.fps);
    showSliderRange();
}

void TimelineDock::commitRange()
{
    BakeRange range;
    range.firstFrame = m_first->value();
    range.lastFrame = m_last->value();
    range.fps = m_fps->value();
    const QString refusal = m_document->setTimeline(
        range, tr("Set timeline to frames %1–%2 at %3 fps").arg(range.firstFrame).arg(range.lastFrame).arg(range.fps));
    if (!refusal.isEmpty()) {
        emit message(tr("Timeline: %1").arg(refusal));
        showRange(); // back to what the document has
    }
}

void TimelineDock::startBake()
{
    leaveCache();
    const QString refusal = m_bake->start(*m_document);
    if (!refusal.isEmpty()) {
        m_bakeError = refusal;
        emit message(tr("Bake refused: %1").arg(refusal));
        updateControls();
        return;
    }
    m_bakeError.clear();
    m_changedDuringBake = false;
    m_changeDuringBake.clear();
    m_progress->setMaximum(m_document->timeline().lastFrame);
    m_progress->setValue(0);
    emit bakeStarted();
    updateControls();
}

void TimelineDock::chooseExport()
{
    if (!m_bake->baked())
        return;
    const QString path = QFileDialog::getSaveFileName(this, tr("Export Bake"), QStringLiteral("hair.usda"),
        tr("USD text (*.usda);;cyHair sequence, # is the frame number (*.hair)"));
    if (!path.isEmpty())
        exportBake(path);
}

QString TimelineDock::exportBake(const QString& path)
{
    if (!m_bake->baked())
        return tr("there is no bake to export");
    int files = 0;
    const QString error = wisp::exportBake(*m_bake->baked(), path, &files);
    if (!error.isEmpty())
        emit message(tr("Cannot export the bake: %1").arg(error));
    else
        emit message(tr("Exported %1 frames%2 to %3")
                         .arg(m_bake->baked()->cache.frames.size())
                         .arg(m_stale ? tr(" (stale)") : QString())
                         .arg(QDir::toNativeSeparators(path)));
    return error;
}

void TimelineDock::markStale(const QString& reason)
{
    if (m_bake->isRunning()) {
        m_changedDuringBake = true;
        m_changeDuringBake = reason;
        m_nameFromUndoStack = true;
        return;
    }
    if (!m_bake->baked())
        return;
    m_stale = true;
    m_staleReason = reason;
    m_nameFromUndoStack = true;
    updateStatus();
}

void TimelineDock::showCacheFrame(int frame)
{
    const FramePtr shown = m_bake->frameAt(frame);
    if (!shown)
        return;
    m_showingCache = true;
    emit cacheFrameShown(shown);
    updateStatus();
}

void TimelineDock::leaveCache()
{
    setPlayingCache(false);
    if (!m_showingCache && !m_onFrame)
        return;
    m_onFrame = false;
    if (m_showingCache) {
        m_showingCache = false;
        emit cacheLeft();
    }
    updateStatus();
}

void TimelineDock::setPlayingCache(bool playing)
{
    if (playing && !m_bake->baked())
        playing = false;
    if (playing) {
        const double fps = m_bake->baked()->cache.range.fps;
        m_playTimer->start(std::max(1, static_cast<int>(std::lround(1000.0 / fps))));
        scrubbedTo(m_slider->value());
    } else {
        m_playTimer->stop();
    }
    const QSignalBlocker quiet(m_playButton);
    m_playButton->setChecked(playing);
    m_playButton->setIcon(style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
}

// One frame per tick of the timer, looping: playback counts frames, and a slow machine shows every
// frame more slowly rather than skipping some.
void TimelineDock::advancePlayback()
{
    const int next = m_slider->value() < m_slider->maximum() ? m_slider->value() + 1 : m_slider->minimum();
    m_slider->setValue(next); // shows it
}

void TimelineDock::updateControls()
{
    const bool running = m_bake->isRunning();
    const bool cached = m_bake->baked() != nullptr;
    m_bakeButton->setEnabled(!running);
    m_cancelButton->setEnabled(running);
    m_progress->setVisible(running);
    m_playButton->setEnabled(cached);
    m_exportButton->setEnabled(cached && !running);
    updateStatus();
}

void TimelineDock::updateStatus()
{
    const bool cached = m_bake->baked() != nullptr;
    QString text;
    if (m_bake->isRunning())
        text = tr("baking frames %1–%2…").arg(m_document->timeline().firstFrame).arg(m_document->timeline().lastFrame);
    else if (!m_bakeError.isEmpty())
        text = tr("bake refused: %1").arg(m_bakeError);
    else if (!cached)
        text = tr("no bake");
    else if (m_stale)
        text = tr("cache stale: %1 — bake again").arg(m_staleReason);
    else {
        const BakedScene& baked = *m_bake->baked();
        text = tr("cache: %1 frames, %2 MB (%3 bytes a frame; groom and drape %4 s, then %5 ms a frame)")
                   .arg(baked.cache.frames.size())
                   .arg(static_cast<double>(baked.cache.memoryBytes()) / 1e6, 0, 'f', 1)
                   .arg(baked.cache.bytesPerFrame())
                   .arg(baked.drapeMilliseconds / 1000.0, 0, 'f', 1)
                   .arg(baked.millisecondsPerFrame, 0, 'f', 0);
    }
    m_status->setText(text);
    if (!m_onFrame)
        m_frameLabel->setText(tr("live"));
    else if (!m_showingCache)
        m_frameLabel->setText(tr("frame %1 (not baked)").arg(m_slider->value())); // the live simulation drawn
    else
        m_frameLabel->setText((m_stale ? tr("frame %1 (stale)") : tr("frame %1")).arg(m_slider->value()));
}

} // namespace wisp
