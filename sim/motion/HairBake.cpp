#include "sim/motion/HairBake.h"

#include "sim/solver/HairSimulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wisp {

namespace {

std::string mebibytes(std::size_t bytes)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return text;
}

} // namespace

std::string validateBakeRange(const BakeRange& r)
{
    const std::string frames = "frames " + std::to_string(r.firstFrame) + ":" + std::to_string(r.lastFrame);
    if (r.firstFrame < 1)
        return frames + ": frames start at 1 (frame 1 is 0 s)";
    if (r.lastFrame < r.firstFrame)
        return frames + ": the last frame comes before the first";
    if (r.lastFrame > BakeRange::kMaxFrame)
        return frames + ": the last frame is beyond " + std::to_string(BakeRange::kMaxFrame);
    if (!std::isfinite(r.fps) || r.fps < BakeRange::kMinFps || r.fps > BakeRange::kMaxFps) {
        char text[96];
        std::snprintf(text, sizeof text, "fps %g is outside %g..%g", r.fps, BakeRange::kMinFps, BakeRange::kMaxFps);
        return text;
    }
    return {};
}

std::size_t bytesPerBakedFrame(std::size_t points, std::size_t strands)
{
    return sizeof(BakedFrame) + points * sizeof(glm::vec3) + strands * sizeof(float);
}

const BakedFrame* BakeCache::find(int frame) const
{
    if (frames.empty() || frame < frames.front().frame || frame > frames.back().frame)
        return nullptr;
    return &frames[static_cast<std::size_t>(frame - frames.front().frame)];
}

HairCurves BakeCache::curvesAt(int frame) const
{
    HairCurves out;
    if (const BakedFrame* f = find(frame)) {
        out.offsets = offsets;
        out.positions = f->positions;
    }
    return out;
}

double bakeStepSeconds(double fps, double timeStepSeconds, int* stepsPerFrame)
{
    const double frameSeconds = 1.0 / fps;
    // The tolerance keeps 1/60 s at 60 fps one step (floats make the ratio 1.0000001).
    const int n = std::max(1, static_cast<int>(std::ceil(frameSeconds / timeStepSeconds - 1e-4)));
    if (stepsPerFrame)
        *stepsPerFrame = n;
    return frameSeconds / n;
}

BakeResult bakeMotion(
    HairSimulation& sim, const HeadMotion& motion, const glm::vec3& pivotHead, const BakeOptions& options)
{
    BakeResult result;
    BakeCache& cache = result.cache;
    const BakeRange& range = options.range;
    cache.range = range;
    if (std::string e = validateBakeRange(range); !e.empty()) {
        result.error = std::move(e);
        return result;
    }
    if (std::string e = motion.validate(); !e.empty()) {
        result.error = "head motion: " + e;
        return result;
    }
    cache.offsets = sim.groom().rest.offsets;
    const std::size_t perFrame = cache.bytesPerFrame();
    if (options.keepFrames) {
        const std::size_t frames = static_cast<std::size_t>(range.frameCount());
        if (frames > options.memoryBoundBytes / perFrame) {
            result.error = "a bake of " + std::to_string(frames) + " frames of " + std::to_string(cache.pointCount())
                + " points needs " + mebibytes(frames * perFrame) + " (" + std::to_string(perFrame)
                + " bytes a frame), more than the bake's memory bound of " + mebibytes(options.memoryBoundBytes)
                + "; bake fewer frames, or export a .hair sequence, which is written one frame at a time";
            return result;
        }
        cache.frames.reserve(frames);
    }

    const SolverSettings settings = sim.solver().settings();
    cache.stepSeconds = bakeStepSeconds(range.fps, settings.timeStepSeconds, &cache.stepsPerFrame);

    // Frame 1: the head at its pose at 0 s, the hair at rest there (resetToRest places it by the
    // head transform), then draped.
    glm::mat4 head = motion.headToWorldAt(0.0, pivotHead);
    sim.solver().setHeadTransform(head);
    sim.resetToRest();
    if (options.drapeFirst)
        sim.drapeAtRest(HairSimulation::kDrapeMaxSteps, 2e-4f, options.cancelled);
    if (options.cancelled && options.cancelled()) {
        result.cancelled = true;
        return result;
    }
    SolverSettings baking = settings;
    baking.timeStepSeconds = static_cast<float>(cache.stepSeconds);
    if (std::string e = sim.solver().setSettings(baking); !e.empty()) {
        result.error = "bake step: " + e;
        return result;
    }

    auto keep = [&](int frame) -> bool {
        BakedFrame baked;
        baked.frame = frame;
        baked.headToWorld = head; // as the solver has it
        HairCurves curves;
        sim.buildFrame(curves);
        baked.positions = std::move(curves.positions);
        if (sim.anyWet())
            sim.strandWetness(baked.wetness);
        if (options.onFrame) {
            if (std::string e = options.onFrame(baked, cache); !e.empty()) {
                result.error = std::move(e);
                return false;
            }
        }
        if (options.keepFrames)
            cache.frames.push_back(std::move(baked));
        return true;
    };

    std::uint64_t step = 0; // steps since frame 1
    for (int frame = 1; frame <= range.lastFrame; ++frame) {
        if (frame > 1) {
            for (int k = 0; k < cache.stepsPerFrame; ++k) {
                if (options.cancelled && options.cancelled()) {
                    result.cancelled = true;
                    (void)sim.solver().setSettings(settings); // the solver's own, valid a moment ago
                    return result;
                }
                ++step;
                // The head's pose at the end of this step; the solver moves the roots there over
                // the step's substeps.
                head = motion.headToWorldAt(static_cast<double>(step) * cache.stepSeconds, pivotHead);
                sim.solver().setHeadTransform(head);
                sim.step();
                ++result.stepsRun;
            }
        }
        if (frame >= range.firstFrame && !keep(frame))
            break;
        if (options.progress)
            options.progress(frame, range.lastFrame);
    }
    (void)sim.solver().setSettings(settings); // the solver's own, valid a moment ago
    return result;
}

} // namespace wisp
