#pragma once
// Where a paint's milliseconds go, pass by pass: shadow maps, backdrop (background, head, body,
// grid and their MSAA resolve, or the cached copy), hair, present (the frame composed with the HUD
// into the window and swapped). Measured only when asked (Viewport::setPassTiming or the
// WISP_PASS_TIMES environment variable), by finishing the GL work at each pass's end and reading a
// steady clock: the same on every driver, and no queries to collect a frame later. The stalls take
// the overlap between passes away, so a timed paint costs a little more than an untimed one.
//
// Thread: GUI, with the viewport's context current.

#include "widgets/GlSupport.h"

#include <QString>

#include <chrono>

namespace wisp {

struct PassTimes {
    double uploadMs = 0.0; // the frame's points (and children) into their buffer
    double shadowMs = 0.0;
    double backdropMs = 0.0;
    double hairMs = 0.0;
    double presentMs = 0.0;
    double totalMs() const { return uploadMs + shadowMs + backdropMs + hairMs + presentMs; }
    QString describe() const; // "upload 1.2, shadow 0.0, backdrop 12.3, hair 45.6, present 7.8 ms"
};

// Laps between glFinish()es. Disabled, it does nothing and costs nothing.
class PassClock {
public:
    void start(GlFunctions* gl, bool enabled);
    // The GL work queued since the last lap (or start), in milliseconds; 0 when disabled.
    double lap();

private:
    GlFunctions* m_gl = nullptr;
    std::chrono::steady_clock::time_point m_last;
};

} // namespace wisp
