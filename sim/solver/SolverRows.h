#pragma once
// The solver's memory as its kernels read it: a block of 16 strands of equal particle count, its
// rows of particles interleaved lane by lane (Solver.h), one step's settings, and the head's
// distance field laid out for lookups. Internal to sim/solver (Solver*.cpp).

#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/Solver.h"
#include "sim/solver/SolverLanes.h"

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace wisp {

// Particle j of the block's 8 strands: position and previous position (Verlet keeps no velocity).
struct Solver::ParticleRow {
    Lane x, y, z;
    Lane px, py, pz;
    // A lower bound on (distance to the nearest collider, the head or a capsule in reach - hair
    // offset) at x: while it stays positive nothing can be touched and the lookups are skipped.
    // Negative means unknown.
    Lane clearance;
};
// Rest shape, head space, as a step reads it: row j > 0 holds the segment from particle j-1 to j
// (row 0 the follicle's frame). The rest directions themselves (ShapeRow) are kept apart: a step
// reads only the first two rows of them, and every byte a step streams costs time on a large groom.
struct Solver::RestRow {
    Lane length; // (its reciprocal is divided out beside the chain: four fewer bytes to stream)
    // Bending (BendingModel.h): the shares of this segment's bend error t_j - x_j added to
    // particle j, taken from its parent j-1 and added to j-2, for this substep (they sum to zero
    // momentum).
    Lane bendChild; // share of the bend error moved onto particle j this substep
    Lane bendDamping; // share of its move relative to its parent taken away this substep
    Lane bendParentRatio; // m_j / m_{j-1}
    // Row j > 0: the rest direction in the parent segment's rest frame (direction, normal,
    // binormal; see advanceBlock), as its stereographic projection from the frame's -direction
    // pole, (u, v) = (l_y, l_z) / (1 + l_x): two floats for a unit vector, with no sign to keep
    // (restCoordinates in SolverConstraints.h turns them back). Row 0: zeros (the follicle's normal
    // is anyPerpendicular of the root segment's rest direction, worked out where it is needed).
    Lane u, v;
};
// A block keeps two (Block::kShapeRows): row 0 the root position, row 1 the unit direction from
// particle 0 to 1, head space; the directions beyond are in the rest frames (RestRow u, v, rebuilt
// by RestDirections in SolverBlockKernel.h), as only a reset and the global shape need them.
struct Solver::ShapeRow {
    Lane x, y, z;
};

// Global shape (pullTowardGlobalShape), only while it is on: particle j's rest position (head
// space) and the share of the way to it this particle moves per substep.
struct Solver::GlobalShapeRow {
    Lane x, y, z;
    Lane share;
};

static_assert(kLanes <= 16, "Solver::Slot keeps a strand's lane in four bits");

// A block's strands' winds of their own, m/s world, per lane (Solver::setStrandAir).
struct Solver::BlockWind {
    Lane x, y, z;
};

using ParticleRow = Solver::ParticleRow;
using RestRow = Solver::RestRow;
using ShapeRow = Solver::ShapeRow;
using GlobalShapeRow = Solver::GlobalShapeRow;

// (The 64-byte lanes first, then the rest largest first: no padding between, 576 bytes.)
struct Solver::Block {
    Lane strandLength{}; // rest arc length per lane, metres
    Lane stiffnessScale{}; // per lane: multiplies the settings' stiffness
    Lane dragScale{}; // per lane: multiplies the drag toward the wind (wet hair)
    Lane volumeWeight{}; // per lane: metres of drawn hair one particle stands for (0: padding)
    Lane volumeTargetScale{}; // per lane: multiplies the density the hair keeps (wet hair)
    std::array<std::int32_t, kLanes> strand{}; // index into the caller's curves, -1 for padding
    // The grid's level of detail at the block's last splat (Solver::volumeSplat): the rows are taken
    // volumeRowsPerSample at a time (their centroid splats and is sampled for all of them), and
    // every volumeStride(g)-th lane of group g splats the weight of the lanes it stands for.
    // In the block itself, four bits a group (log2 of the stride), so the read before each substep
    // finds it in the block's own cache lines (a separate array cost a cache miss a block); the
    // groups beyond the first kVolumeLevelGroups (a strand of more than 128 points) take stride 1.
    static constexpr std::uint32_t kVolumeLevelGroups = 128;
    std::array<std::uint8_t, kVolumeLevelGroups / 2> volumeLevels{};
    std::uint32_t volumeGroups = 0; // groups at the last splat (0: none yet)
    std::uint32_t volumeRowsPerSample = 1;
    int volumeStride(std::uint32_t group) const
    {
        return group < std::min(volumeGroups, kVolumeLevelGroups)
            ? 1 << ((volumeLevels[group / 2] >> (4 * (group % 2))) & 0xF)
            : 1;
    }
    void setVolumeLevel(std::uint32_t group, int level)
    {
        if (group >= kVolumeLevelGroups)
            return;
        std::uint8_t& pair = volumeLevels[group / 2];
        const int shift = 4 * static_cast<int>(group % 2);
        pair = static_cast<std::uint8_t>((pair & ~(0xF << shift)) | ((level & 0xF) << shift));
    }
    // Views into the solver's two row arrays: every block's rows follow the previous block's, so
    // a thread streams through memory in one sequential run that the prefetcher can follow.
    std::span<ParticleRow> state;
    std::span<RestRow> rest;
    std::span<ShapeRow> shape; // kShapeRows rows (ShapeRow)
    static constexpr std::uint32_t kShapeRows = 2;
    std::span<const GlobalShapeRow> globalShape; // empty while the global shape is off
    const BlockWind* wind = nullptr; // per lane: wind of its own (a hair dryer); null: none
    std::uint32_t points = 0;
    // Whether any lane has a bend share (Solver::updateBendShares): a limp block (stiffness 0 on
    // every lane) skips the bend and its frames, which would move nothing.
    bool bends = true;
};

struct StepConstants {
    float dt = 0.0f; // substep, seconds
    float keep = 1.0f; // exp(-damping dt): share of velocity kept
    float friction = 0;
    float offset = 0;
    float velocityCorrection = 0;
    float drag = 0;
    float turbulence = 0;
    int substeps = 1;
    int substep = 0; // the volume pass's substep (Solver::volumePass)
    double time = 0;
    glm::vec3 gravity{ 0.0f };
    glm::vec3 wind{ 0.0f };
    glm::mat3 rotation{ 1.0f }; // head to world
    glm::vec3 translation{ 0.0f };
    glm::mat3 previousRotation{ 1.0f };
    glm::vec3 previousTranslation{ 0.0f };
    bool transformed = false; // head is not at the identity: SDF lookups need head space
    // Whether the kernel asks for the next block's rows while it runs a block (Solver::step): only
    // where the rows are too many to stay in the caches from one step to the next.
    bool prefetchNextBlock = true;
    // The head's own motion over one substep at a world point x on it (or on the body, which moves
    // with it): headMoveLinear x + headMoveOffset, the step's rigid motion of the head point now at
    // x shared evenly over the substeps, as the roots move. Friction takes the slide relative to it.
    glm::mat3 headMoveLinear{ 0.0f };
    glm::vec3 headMoveOffset{ 0.0f };
    const Solver::CollisionField* field = nullptr;
    std::vector<Capsule> capsulesWorld;
    std::uint64_t* resetCounter = nullptr;
};

// The head as the solver reads it: for every node of the baked signed-distance grid, the distance
// and the unit outward normal there (SignedDistanceField::samplesWithNormals, built once per head
// and shared by every solver colliding with it: a comb release's rest solve and regroom no longer
// rebuild it, which was most of their cost). A lookup takes the nearest node and
// extends it to first order, d(p) = d_n + n . (p - x_n): one 16-byte load per particle instead of
// the eight scattered loads of trilinear interpolation, which dominated the step. The error is
// about h^2 / (2 R) for a surface of curvature radius R (0.03 mm for a 2.5 mm grid on a head).
struct Solver::CollisionField {
    const glm::vec4* nodes = nullptr; // (distance, normal) per node, metres: the field's own table
    glm::ivec3 dims{ 0 };
    glm::vec3 origin{ 0.0f };
    float cellSize = 0.0f;

    explicit CollisionField(const SignedDistanceField& sdf)
        : nodes(sdf.samplesWithNormals().data())
        , dims(sdf.dims())
        , origin(sdf.origin())
        , cellSize(sdf.cellSize())
    {
    }
};

} // namespace wisp
