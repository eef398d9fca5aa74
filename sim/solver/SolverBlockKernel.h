#pragma once
// The solver's step for one block of 16 strands (SolverBlockKernel.cpp): predict, bend, length,
// contact, root to tip, for a run of substeps; and the block's rest frames and rest pose.
// Internal to sim/solver. Thread: any; a block is touched by one thread at a time.

#include "sim/solver/SolverRows.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

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

// The rest shape's parallel-transported frames, from the follicle's (the root segment's direction
// and anyPerpendicular of it): each rest direction's coordinates in its parent segment's frame
// into rows j > 0 (as RestRow u, v), and the root segment's direction into the block's shape row 1. `directions[j]`:
// the unit direction from rest point j - 1 to j, head space, for j = 1 .. block.points - 1 (directions[0] is not read).
void storeRestFrames(Solver::Block& block, int lane, std::span<const glm::vec3> directions);

// A lane's rest directions, root to tip, rebuilt from the root segment's (shape row 1) and the rest
// frames (storeRestFrames): the block keeps no row of directions beyond the root's, which only a
// reset and the global shape read (12 bytes a particle less). Rebuilt, a direction is within a few
// float roundings of the one stored (each is renormalised).
class RestDirections {
public:
    RestDirections(const Solver::Block& block, int lane);
    // The direction of segment j (from particle j - 1 to j), for j = 1, 2, ... in turn.
    glm::vec3 next();

private:
    const Solver::Block& m_block;
    int m_lane;
    std::uint32_t m_next = 1;
    glm::vec3 m_direction{ 0.0f };
    glm::vec3 m_normal{ 0.0f };
};

// Puts one lane's strand at its rest shape, at rest, in world space; its clearance becomes unknown.
void placeLaneAtRest(Solver::Block& block, int lane, const glm::mat3& rotation, const glm::vec3& translation);

} // namespace wisp
