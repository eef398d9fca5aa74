#pragma once
// Frames and seconds on the timeline, one definition for the bake, the timeline dock, the head
// drag and the Motion panel's keys: frame f is at (f - 1) / fps seconds (frame 1 is 0 s, the
// draped rest), as in Blender's and Maya's timelines starting at frame 1.
//
// Thread safety: any thread; pure functions.

#include <cmath>

namespace wisp {

// Seconds at which `frame` is, at `fps` frames per second.
inline double secondsOfFrame(int frame, double fps)
{
    return (frame - 1) / fps;
}

// The frame nearest to `seconds` (halves away from zero, as std::lround).
inline int frameAtSeconds(double seconds, double fps)
{
    return 1 + static_cast<int>(std::lround(seconds * fps));
}

// `seconds` on the nearest frame: where keys are set.
inline double snappedToFrame(double seconds, double fps)
{
    return secondsOfFrame(frameAtSeconds(seconds, fps), fps);
}

} // namespace wisp
