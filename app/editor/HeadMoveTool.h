#pragma once
// Turning and moving the head in the viewport with a modifier drag, while the hair simulates:
//   Ctrl+Alt + left drag            turn the head (left/right turns it about the vertical, up/down
//                                   tilts it about the view's horizontal), about its pivot
//   Ctrl+Alt + middle drag,
//   or Ctrl+Alt+Shift + left drag   move the head in the view's plane
// (Alt alone stays the camera's: Alt+left orbits, Alt+middle pans, as before.)
//
// A drag writes a key of the head's pose (see keyedMotion): while dragging, the simulation gets the
// changed motion at once (live, nothing pushed); on release the document gets it as one undo step.
// An event filter on the viewport, like the paint tool; it takes only the events named above.
//
// Thread: GUI.

#include "sim/motion/HeadMotion.h"

#include <QObject>
#include <QPointF>

#include <functional>
#include <optional>

namespace wisp {

class Document;
class SimulationHost;
class Viewport;

// `motion` with the key pose at `timeSeconds` set to `pose`: when the motion has no keys the key
// goes at 0 s (one key holds the head there at every time: a rest offset), otherwise at
// `timeSeconds` rounded to the timeline's frame at `fps`. The drag and the panel's Set Key both
// write keys this way.
double keySecondsFor(const HeadMotion& motion, double timeSeconds, double fps);
HeadMotion keyedMotion(HeadMotion motion, double timeSeconds, double fps, const HeadPose& pose);

class HeadMoveTool : public QObject {
    Q_OBJECT
public:
    HeadMoveTool(Document* document, Viewport* viewport, SimulationHost* simulation, QObject* parent = nullptr);

    bool dragging() const { return m_drag.has_value(); }
    // The time the editor is at, where keys are set: the timeline's frame while the timeline is on
    // one (scrubbed, a key selected, a cached frame shown), else the live simulation's newest frame's.
    double currentSeconds() const;
    // Where the timeline's time comes from (TimelineDock::frameSeconds); nullopt: live.
    void setTimelineSeconds(std::function<std::optional<double>()> seconds) { m_timelineSeconds = std::move(seconds); }

    static constexpr float kDegreesPerPixel = 0.4f;

signals:
    void message(const QString& text); // a refused edit

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    enum class Kind { Turn, Move };
    struct Drag {
        Kind kind = Kind::Turn;
        QPointF start;
        QPointF last;
        double keySeconds = 0.0;
        HeadPose startPose; // the keyed pose when the drag began
        HeadPose pose; // as dragged so far
        HeadMotion motion; // the document's when the drag began
    };
    void update(QPointF position);
    HeadMotion draggedMotion() const;

    Document* m_document;
    Viewport* m_viewport;
    SimulationHost* m_simulation;
    std::optional<Drag> m_drag;
    std::function<std::optional<double>()> m_timelineSeconds;
};

} // namespace wisp
