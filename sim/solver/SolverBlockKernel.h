#pragma once
// The solver's step for one block of 16 strands (SolverBlockKernel.cpp): predict, bend, length,
// contact, root to tip, for a run of substeps; and the block's rest frames and rest pose.
// Internal to sim/solver. Thread: any; a block is touched by one thread at a time.

#include "sim/solver/SolverRows.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace wisp {

// Global shape (pullTowardGlobalShape): its share is given per step of this length, and fades from
// full at the root to none at this fraction of the strand's rest length (TressFX's "effective
// range"; the tips stay free to move, the part near the root keeps the groom).
constexpr float kGlobalShapeStepSeconds = 1.0f / 60.0f;
constexpr float kGlobalShapeReach = 0.75f;

// Substeps [firstSubstep, endSubstep) of the step; the last call of a step (endSubstep ==
// c.substeps) also puts back strands that went non-finite or flew away. `globalShape`: the
// block's global shape rows are set (Solver::updateGlobalShape).
void advanceBlock(Solver::Block& block, const StepConstants& c, int firstSubstep, int endSubstep, bool globalShape);

// Asks the cache for the block's own fields (its spans, per-lane scales and wind), which the
// kernel reads first thing: blocks are large (about 800 bytes, a dozen cache lines, mostly lanes
// the grid workloads leave alone), so the next one's are cold, and its first loads stalled every
// block (perf annotate: a tenth of the kernel's time on groom-1m). A hint only: nothing computed
// changes.
void prefetchBlock(const Solver::Block& block);

// The rest shape's parallel-transported frames: the follicle's normal (any unit vector across the
// root segment, chosen the same way every time) into row 0, and each rest direction's
// coordinates in its parent segment's frame into rows j > 0.
void storeRestFrames(Solver::Block& block, int lane);

// Puts one lane's strand at its rest shape, at rest, in world space; its clearance becomes unknown.
void placeLaneAtRest(Solver::Block& block, int lane, const glm::mat3& rotation, const glm::vec3& translation);

} // namespace wisp
