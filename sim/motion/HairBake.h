#pragma once
// Baking: a frame range simulated with the head moving (HeadMotion.h), every drawn strand of each
// frame kept in memory for scrubbing and export, or handed on one frame at a time (a .hair
// sequence streamed to disk, with no bound on the frame count).
//
// Time: frame f is at (f - 1) / fps seconds; frame 1 is the draped rest with the head at its
// pose at 0 s. A bake always simulates from frame 1, whatever frame it starts keeping at, so a
// range split across machines (1:24 and 25:48) gives the same frames as one bake of 1:48. Each
// frame is a whole number of solver steps: the time step is the simulation's, shortened to
// 1 / (fps · stepsPerFrame) where it does not divide a frame (1/60 s at 24 fps: 3 steps of 1/72 s).
// Deterministic: the solver's results do not depend on the thread count.
//
// Memory: bytesPerBakedFrame(points, strands) = points x 12 bytes (float32 x, y, z) plus strands x
// 4 bytes (float32 wetness, kept only while some hair is wet: the bound counts it always) plus a
// frame's fixed part (its head transform and bookkeeping); a bake whose frames would not fit the
// memory bound is refused before it starts.
//
// Thread: bakeMotion runs on the calling thread and owns `sim` for the call; `progress` and
// `onFrame` are called on it, `cancelled` is asked from it between steps.

#include "sim/geometry/HairCurves.h"
#include "sim/motion/FrameTime.h"
#include "sim/motion/HeadMotion.h"

#include <glm/mat4x4.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace wisp {

class HairSimulation;

struct BakeRange {
    int firstFrame = 1; // >= 1
    int lastFrame = 48; // >= firstFrame, <= kMaxFrame
    double fps = 24.0; // kMinFps..kMaxFps

    int frameCount() const { return lastFrame - firstFrame + 1; }
    // Seconds at which `frame` is.
    double secondsOf(int frame) const { return secondsOfFrame(frame, fps); }
    bool operator==(const BakeRange&) const = default;

    static constexpr int kMaxFrame = 1'000'000;
    static constexpr double kMinFps = 1.0;
    static constexpr double kMaxFps = 1000.0;
};

// Empty when the range can be baked; otherwise what is wrong ("frames 5:2: the last frame comes before the first").
std::string validateBakeRange(const BakeRange& range);

struct BakedFrame {
    int frame = 0;
    glm::mat4 headToWorld{ 1.0f };
    std::vector<glm::vec3> positions; // world space, metres, in the layout of BakeCache::offsets
    // Per drawn strand, 0..1, as the live frame has it (Frame::wetness: wet hair is drawn darker
    // and clumped); empty when all the hair is dry.
    std::vector<float> wetness;
};

// Bytes one kept frame of `points` drawn points in `strands` strands takes at most (wet hair).
std::size_t bytesPerBakedFrame(std::size_t points, std::size_t strands);

// A bake kept in memory.
struct BakeCache {
    BakeRange range;
    std::vector<std::uint32_t> offsets{ 0 }; // every frame's strand layout (HairCurves::offsets)
    std::vector<BakedFrame> frames; // range.firstFrame onwards, in order; fewer if cancelled
    int stepsPerFrame = 0;
    double stepSeconds = 0.0;

    bool complete() const { return static_cast<int>(frames.size()) == range.frameCount(); }
    std::size_t pointCount() const { return offsets.empty() ? 0 : offsets.back(); }
    std::size_t strandCount() const { return offsets.empty() ? 0 : offsets.size() - 1; }
    std::size_t bytesPerFrame() const { return bytesPerBakedFrame(pointCount(), strandCount()); }
    // The kept frame `frame`, or null when it was not baked.
    const BakedFrame* find(int frame) const;
    // That frame's strands (empty when it was not baked).
    HairCurves curvesAt(int frame) const;
    std::size_t memoryBytes() const { return frames.size() * bytesPerFrame(); }
};

// 2 GiB: a minute at 24 fps of the default scene fits many times over (see the README's figures);
// a million-particle groom gets 182 frames (11.7 MB each).
inline constexpr std::size_t kDefaultBakeMemoryBytes = std::size_t(2) << 30;

struct BakeOptions {
    BakeRange range;
    std::size_t memoryBoundBytes = kDefaultBakeMemoryBytes;
    bool keepFrames = true; // false: frames go only to onFrame (streamed), none kept, no bound
    bool drapeFirst = true; // settle at rest before frame 1 (HairSimulation::drapeAtRest)
    std::function<void(int framesDone, int framesTotal)> progress; // after each simulated frame (pre-roll included)
    std::function<bool()> cancelled; // asked between steps
    // Each kept frame, as soon as it is simulated (a non-empty return stops the bake with that error).
    std::function<std::string(const BakedFrame& frame, const BakeCache& layout)> onFrame;
};

struct BakeResult {
    BakeCache cache; // the kept frames (none when keepFrames is false); layout and steps always
    std::string error; // empty on success
    bool cancelled = false;
    std::uint64_t stepsRun = 0;
};

// The step length a bake at `fps` uses for a simulation stepping `timeStepSeconds`: the largest
// 1 / (fps · n) not above it. n is returned in `stepsPerFrame`.
double bakeStepSeconds(double fps, double timeStepSeconds, int* stepsPerFrame = nullptr);

// Simulates range.firstFrame's pre-roll and the range with the head moving as `motion` says about
// `pivotHead` (HeadMotion.h). Refuses before stepping when the range or the motion is invalid, or
// the kept frames would exceed the memory bound. The simulation's settings are as before after it;
// its state is the last frame's.
BakeResult bakeMotion(
    HairSimulation& sim, const HeadMotion& motion, const glm::vec3& pivotHead, const BakeOptions& options);

} // namespace wisp
