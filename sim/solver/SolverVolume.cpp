// The solver's hair volume (issue 13): the grid's bounds and target density, and the pass that
// splats the hair into HairVolumeGrid and reads its push back (Petrovic, Henne & Anderson 2005;
// McAdams et al. 2009). Members of Solver (Solver.h), kept apart from the step in Solver.cpp.
#include "sim/solver/Solver.h"

#include "sim/solver/HairVolumeGrid.h"
#include "sim/solver/SolverRows.h"
#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>
// The constants of the hair volume, for the kernels below (compiled once per target) and the rest.
#ifndef WISP_SOLVER_VOLUME_CONSTANTS_
#define WISP_SOLVER_VOLUME_CONSTANTS_
namespace wisp {
namespace {

// How hard hair denser than its target pushes down the density gradient: the acceleration is this
// times (density / target - 1, at most 1) times the gradient of density / target (1/m), so hair at
// twice its target that thins out over 2 cm pushes at 200 m/s² before the cap. Capped at
// kVolumeMaxAcceleration (3 g) so a particle deep in a knot is not flung. Measured on the default
// groom (tests/sim/VolumeTest.cpp): 1 m²/s² leaves the top at 8 mm, 4 gives 18 mm, 10 gives 20 mm.
constexpr float kVolumeStiffness = 4.0f; // m²/s²
constexpr float kVolumeMaxAcceleration = 30.0f; // m/s²
// The push's stiffness is at most this times (cell / substep)², measured: 1 substep at 60 Hz with
// 8 segments leaves 0 % of tips moving at 0.6 (VolumeTest's settling cases).
constexpr float kVolumeStableShare = 0.6f;
// The same for a dense groom's grid (HairVolumeGrid::Kernel::NearestSmoothed). Its [1 2 1]/4
// smoothing takes out the shortest waves, the ones an explicit spring overshoots first. In one
// dimension, for particles displaced by a wave of k (u = k x cell), the push's spring is
// stiffness x u sin(u) x T(u) / cell², where T is the grid's transfer: sinc⁴(u/2) for a
// trilinear splat and read, sinc²(u/2) cos²(u/2) = (sin u / u)² for the nearest node smoothed
// (the central-difference gradient gives the sin u). Its peak is 0.69 against the trilinear
// grid's 1.04, and a spring taken explicitly over T seconds is stable while ω T < 2. At 2.4 the
// peak is ω T = sqrt(2.4 x 0.69) = 1.3 (the trilinear grid at 0.6: 0.8), and groom-1m, its grid laid
// every 1/30 s (kVolumeDenseRefreshSeconds), keeps the stiffness it had laid every 1/60 s at 0.6.
// Measured: VolumeTest.cpp, Volume.ADenseGroomLaidEveryOtherStepSettles.
constexpr float kVolumeStableShareSmoothed = 2.4f;
// Damping of the motion along the push where hair is denser than its target, per second: the share
// 1 - exp(-this dt) of it is taken each substep (the same at any substep count).
constexpr float kVolumeDampingPerSecond = 30.0f;
// The grid is laid again after at least this long of substeps (Solver::step): 1/120 s, the default
// substep (two at 60 Hz), so the default scene lays it every substep.
constexpr float kVolumeRefreshSeconds = 1.0f / 120.0f;
// A dense groom (volumeDense(): more than kVolumeFullGridParticles, the NearestSmoothed grid) lays
// it only after this long, across steps when its substeps are longer (groom-1m, one substep at
// 60 Hz: every other step); the blocks still read it before every substep. The splat and the
// sums are per particle, as costly as the read (groom-1m: each about 0.27 of the solver's own
// step), so this halves them. Hair moving at 0.5 m/s moves 17 mm in 1/30 s, under one of
// groom-1m's 27 mm cells. The push's stiffness is capped for the longer interval as for any
// refresh (volumePass, kVolumeStableShareSmoothed). Reading it only once a pass with the
// interval's impulse would halve the read too, but the push, which holds the hair up against
// gravity, then comes in kicks and the tips saw up and down by about g dt² a step (VolumeTest's
// Volume.ADenseGroomLaidEveryOtherStepSettles: 18.7 % of a dense patch's tips moving after 10 s).
constexpr float kVolumeDenseRefreshSeconds = 1.0f / 30.0f;
// A particle that moved this far in one substep (or went non-finite) is left out of the grid.
constexpr float kVolumeMaxMoveMetres = 0.5f;

// A row's sixteen strands lie side by side on the scalp. Where a dense groom puts them much closer
// than a cell (groom-1m: 1-3 mm apart in 2 cm cells), the grid cannot tell them apart: only every
// stride-th strand splats, with the weight of those it stands for, and is sampled; the strands
// between blend the samples around them (HairVolumeGrid::sampleRow), as members follow their key.
// The stride is chosen per row (the particles at one distance from the roots): the largest power of
// two whose sampled strands are within kVolumeLodCellShare of a cell of each other there, where they
// are now (Solver::volumeSplat), so the roots and lengths that lie together are thinned even where
// the tips flutter apart; 1 for a block with padding, and in practice for the editor's keys (5-10 mm
// apart in 8-15 mm cells).
constexpr float kVolumeLodCellShare = 0.5f;
// For a dense groom (Kernel::NearestSmoothed, a particle meets one node) within one cell, as its
// rows (kVolumeRowCellShare): the lanes between two samples are then at the samples' node or the
// next.
constexpr float kVolumeNearestLodCellShare = 1.0f;

// How many rows of a block splat and are sampled as one, at their centroid (Solver::volumeSplat):
// for a dense groom (Kernel::NearestSmoothed), the most rows, a power of two up to
// kVolumeMaxRowsPerSample, whose stretch of strand (rows x the longest segment) is at most
// kVolumeRowGroupCells cells: the [1 2 1]/4 smoothing spreads every splat over three nodes along
// each axis anyway, so the field has no finer detail for the rows to miss. groom-1m's 20 mm
// segments in 27 mm cells go four by four (80 mm). The editor's keys (Kernel::Trilinear) go one by
// one.
constexpr float kVolumeRowGroupCells = 3.0f;
constexpr std::uint32_t kVolumeMaxRowsPerSample = 4;

} // namespace
} // namespace wisp
#endif

// The splat and the read of a block are compiled once per SIMD target, as the solver's kernel
// (SolverBlockKernel.cpp); the rest of the file once.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/solver/SolverVolume.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/HairVolumeGridNearest-inl.h"
#include "sim/util/ShuffleLanes-inl.h"

#include "sim/solver/SolverConstraints.h"
#include "sim/solver/SolverLanes-inl.h"

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

using namespace lanes;

namespace {
#if WISP_LANES_AVX512 // (the tables of the permutes below)
// Lane l's neighbour `Ahead` lanes on (the last lane its own): compile-time tables (shuffleLanesBy).
template <int Ahead> constexpr std::array<int, kLanes> laneAhead()
{
    std::array<int, kLanes> lanes{};
    for (int l = 0; l < kLanes; ++l)
        lanes[l] = std::min(l + Ahead, kLanes - 1);
    return lanes;
}
template <int Ahead> constexpr std::array<int, kLanes> kLaneAhead = laneAhead<Ahead>();
#endif

// r[l] = v[min(l + Ahead, 15)]. A permute on AVX-512; on targets whose registers hold fewer lanes,
// through memory (GCC moved a 16-lane shuffle across AVX2's two registers lane by lane).
template <int Ahead> inline Lane lanesAhead(const Lane& v)
{
#if WISP_LANES_AVX512
    return shuffleLanesBy<kLaneAhead<Ahead>>(v);
#else
    alignas(64) float f[2 * kLanes];
    std::memcpy(f, &v, sizeof v);
    for (int l = kLanes; l < kLanes + Ahead; ++l)
        f[l] = f[kLanes - 1];
    Lane r;
    std::memcpy(&r, f + Ahead, sizeof r);
    return r;
#endif
}

std::uint32_t volumeRowsPerSample(const Solver::Block& b, const HairVolumeGrid& grid)
{
    if (grid.kernel() != HairVolumeGrid::Kernel::NearestSmoothed)
        return 1;
    Lane longest = splat(0.0f);
    for (std::uint32_t j = 1; j < b.points; ++j)
        longest = lmax(longest, b.rest[j].length);
    float segment = 0.0f;
    for (int l = 0; l < kLanes; ++l)
        segment = std::max(segment, longest[l]);
    std::uint32_t rows = 1;
    while (rows < kVolumeMaxRowsPerSample
        && static_cast<float>(2 * rows) * segment <= kVolumeRowGroupCells * grid.cellMetres())
        rows *= 2;
    return rows;
}

using Nearest = HairVolumeGridKernels<GridNearestTarget>;

// A group's sixteen lanes as the splat and the read take them. The lanes' own arithmetic (the
// centroid, the move, the grid's node) runs a register's width at a time, as the block kernel does
// (kernel::Lane: on AVX2 a 16-lane value is two registers, and this part spilled), with the same
// arithmetic lane by lane; what spans lanes (the spacing, the nodes' sums) reads these arrays.
struct GroupLanes {
    alignas(64) float x[kLanes + 1], y[kLanes + 1], z[kLanes + 1]; // the centroid (its last lane again after it)
    alignas(64) float headX[kLanes], headY[kLanes], headZ[kLanes]; // the centroid in head space
    alignas(64) float moveX[kLanes], moveY[kLanes], moveZ[kLanes]; // the mean move over the last substep
    alignas(64) std::int32_t tame[kLanes]; // -1: no particle of the lane gone wild in the group
    alignas(64) float weight[kLanes];
    Nearest::NearestRow nearest; // a dense groom's nodes (Kernel::NearestSmoothed)
};

template <class T> inline void storeLanes(T* to, const auto& value)
{
    std::memcpy(to, &value, sizeof value);
}
inline kernel::Lane loadLanes(const float* from)
{
    kernel::Lane v;
    std::memcpy(&v, from, sizeof v);
    return v;
}

// Rows first .. first + count - 1 of the block's slice `slice`: their centroid in head space and
// its grid node (`nearest`) into `out`, with (`WithMoves`: the splat; the read, every substep,
// needs only the centroid) their mean move and whether all are tame.
template <bool WithMoves>
void groupSlice(const HairVolumeGrid& grid, const Solver::Block& b, const StepConstants& c, const glm::mat3& toHead,
    std::uint32_t first, std::uint32_t count, int slice, bool nearest, GroupLanes& out)
{
    using VV3 = kernel::V3;
    const int at = slice * kernel::kVecLanes;
    const kernel::ParticleSlice* const rows = kernel::sliceOf<const kernel::ParticleSlice>(b.state.data(), slice);
    const kernel::ParticleSlice& r = rows[first];
    VV3 x{ r.x, r.y, r.z };
    VV3 move{};
    kernel::Mask tame{};
    if constexpr (WithMoves) {
        move = x - VV3{ r.px, r.py, r.pz };
        // A particle gone non-finite or flying off (its strand is put back at rest at the end of
        // the step) must not spread through the grid.
        tame = l1Length(move) < kVolumeMaxMoveMetres;
    }
    if (count > 1) {
        for (std::uint32_t j = first + 1; j < first + count; ++j) {
            const kernel::ParticleSlice& q = rows[j];
            const VV3 p{ q.x, q.y, q.z };
            x = x + p;
            if constexpr (WithMoves) {
                const VV3 moved = p - VV3{ q.px, q.py, q.pz };
                tame = tame & (l1Length(moved) < kVolumeMaxMoveMetres);
                move = move + moved;
            }
        }
        const float share = 1.0f / static_cast<float>(count);
        x = x * kernel::splat(share);
        if constexpr (WithMoves)
            move = move * kernel::splat(share);
    }
    if constexpr (WithMoves) {
        storeLanes(out.x + at, x.x);
        storeLanes(out.y + at, x.y);
        storeLanes(out.z + at, x.z);
        storeLanes(out.moveX + at, move.x);
        storeLanes(out.moveY + at, move.y);
        storeLanes(out.moveZ + at, move.z);
        storeLanes(out.tame + at, tame);
    }
    const VV3 head = c.transformed ? transform(toHead, x - kernel::splat(c.translation)) : x;
    if (nearest) {
        Nearest::nearestInto(grid, head.x, head.y, head.z, out.nearest, at);
    } else {
        storeLanes(out.headX + at, head.x);
        storeLanes(out.headY + at, head.y);
        storeLanes(out.headZ + at, head.z);
    }
}

// The largest squared distance between neighbouring lanes of a group's centroids (groupSlice);
// a NaN counts as 0 (a broken lane is not tame, splats 0).
float widestSpacingSquared(GroupLanes& lanes)
{
    lanes.x[kLanes] = lanes.x[kLanes - 1];
    lanes.y[kLanes] = lanes.y[kLanes - 1];
    lanes.z[kLanes] = lanes.z[kLanes - 1];
    kernel::Lane widest = kernel::splat(0.0f);
    for (int at = 0; at < kLanes; at += kernel::kVecLanes) {
        const kernel::Lane dx = loadLanes(lanes.x + at + 1) - loadLanes(lanes.x + at),
                           dy = loadLanes(lanes.y + at + 1) - loadLanes(lanes.y + at),
                           dz = loadLanes(lanes.z + at + 1) - loadLanes(lanes.z + at);
        const kernel::Lane w = dx * dx + dy * dy + dz * dz;
        widest = lmax(widest, select(w == w, w, kernel::splat(0.0f)));
    }
    float largest = widest[0];
    for (int l = 1; l < kernel::kVecLanes; ++l)
        largest = std::max(largest, widest[l]);
    return largest;
}
} // namespace

// One block's splat into the grid's slot `slot`, a group of volumeRowsPerSample rows at a time (a
// row's sixteen strands lie side by side): each lane's weight and its move over the last substep,
// at the group's centroid in head space; a lane with a particle gone wild in the group splats nothing.
void volumeSplatOnTarget(HairVolumeGrid& grid, Solver::Block& b, const StepConstants& c, int slot)
{
    const glm::mat3 toHead = glm::transpose(c.rotation);
    // The level of detail (kVolumeLodCellShare), group by group: how far apart neighbouring lanes are now.
    bool full = true;
    for (int l = 0; l < kLanes; ++l)
        full = full && b.strand[l] >= 0;
    const std::uint32_t rows = b.volumeRowsPerSample = volumeRowsPerSample(b, grid);
    const std::uint32_t groups = (b.points + rows - 1) / rows;
    // At each group's first lane, the weight of its lanes, for strides 1, 2, 4, 8 and 16: a group
    // of 2s lanes is two of s (the other lanes hold partial sums that nothing reads).
    Lane groupWeight[5];
    groupWeight[0] = b.volumeWeight;
    groupWeight[1] = groupWeight[0] + lanesAhead<1>(groupWeight[0]);
    groupWeight[2] = groupWeight[1] + lanesAhead<2>(groupWeight[1]);
    groupWeight[3] = groupWeight[2] + lanesAhead<4>(groupWeight[2]);
    groupWeight[4] = groupWeight[3] + lanesAhead<8>(groupWeight[3]);
    const bool nearest = grid.kernel() == HairVolumeGrid::Kernel::NearestSmoothed;
    const float reach = (nearest ? kVolumeNearestLodCellShare : kVolumeLodCellShare) * grid.cellMetres();
    b.volumeGroups = groups;
    GroupLanes lanes;
    for (std::uint32_t g = 0; g < groups; ++g) {
        const std::uint32_t first = g * rows, count = std::min(rows, b.points - first);
        for (int slice = 0; slice < kLanes / kernel::kVecLanes; ++slice)
            groupSlice<true>(grid, b, c, toHead, first, count, slice, nearest, lanes);
        int level = 0; // log2 of the stride
        if (full) {
            const float spacing2 = widestSpacingSquared(lanes);
            while (level < 4 && std::isfinite(spacing2)
                && 4.0f * static_cast<float>(1 << (2 * level)) * spacing2 <= reach * reach)
                ++level;
        }
        if (g >= Solver::Block::kVolumeLevelGroups)
            level = 0; // (a very long strand's far groups: see Block::volumeLevels)
        b.setVolumeLevel(g, level);
        for (int slice = 0; slice < kLanes / kernel::kVecLanes; ++slice) {
            const int at = slice * kernel::kVecLanes;
            const kernel::Lane share = kernel::sliceOf(groupWeight[level], slice);
            kernel::Mask tame;
            std::memcpy(&tame, lanes.tame + at, sizeof tame);
            storeLanes(lanes.weight + at,
                select(tame, count > 1 ? share * static_cast<float>(count) : share, kernel::splat(0.0f)));
        }
        if (nearest) // the nodes' sums (HairVolumeGridNearest-inl.h)
            Nearest::splatNearest(
                grid, slot, lanes.nearest, lanes.weight, lanes.moveX, lanes.moveY, lanes.moveZ, 1 << level);
        else
            grid.splatRow(slot, lanes.headX, lanes.headY, lanes.headZ, lanes.weight, lanes.moveX, lanes.moveY,
                lanes.moveZ, HairVolumeGrid::kRowLanes, 1 << level);
    }
}

// What volumeReadOnTarget does with a group's fields (the Node's order, all 16 lanes) for the
// lanes of one slice: each particle's velocity is blended toward the hair's mean velocity there by
// the hair friction, and where the density is above the target it is accelerated down the density
// gradient. Rows first .. first + count - 1 of the block.
void readSlice(const Solver::VolumeRead& v, Solver::Block& b, const StepConstants& c, const Lane fields[8],
    const Lane& inverseKeepAll, std::uint32_t first, std::uint32_t count, int slice)
{
    using VLane = kernel::Lane;
    using VMask = kernel::Mask;
    using VV3 = kernel::V3;
    auto part = [&](const Lane& l) { return kernel::sliceOf(l, slice); };
    const VLane density = part(fields[0]);
    const VMask inHair = density > 0.0f;
    if (!anyOf(inHair))
        return;
    // What the group's particles share: the hair's mean move, and the push and its direction.
    const VLane inverseKeep = part(inverseKeepAll);
    const VLane hair = part(fields[7]);
    const VMask hasHair = hair > 0.0f;
    const VLane inverseHair = select(hasHair, kernel::splat(1.0f) / hair, kernel::splat(0.0f));
    const VV3 mean = VV3{ part(fields[4]), part(fields[5]), part(fields[6]) } * inverseHair;
    const VLane excess = density * inverseKeep - 1.0f;
    const VMask pushing = excess > 0.0f;
    const bool anyPushing = anyOf(pushing);
    VV3 push{}, direction{};
    if (anyPushing) {
        push = VV3{ part(fields[1]), part(fields[2]), part(fields[3]) }
            * ((-v.stiffness) * lmin(excess, kernel::splat(1.0f)) * inverseKeep);
        const VLane length = lsqrt(dot(push, push));
        const VLane inverseLength = kernel::splat(1.0f) / length; // one division where there were four
        push = push
            * select(length > kVolumeMaxAcceleration, kVolumeMaxAcceleration * inverseLength, kernel::splat(1.0f));
        if (c.transformed)
            push = transform(c.rotation, push);
        // Pressure alone makes hair bounce on the hair beneath it (a stiff spring taken
        // explicitly): the motion along the push is damped where it pushes.
        const VMask along = pushing & (length > 0.0f);
        direction = select(along, push * inverseLength, VV3{});
        push = push * kernel::splat(c.dt * c.dt);
    }
    kernel::ParticleSlice* const rows = kernel::sliceOf<kernel::ParticleSlice>(b.state.data(), slice);
    for (std::uint32_t j = std::max<std::uint32_t>(first, 1); j < first + count; ++j) {
        kernel::ParticleSlice& r = rows[j];
        const VV3 at{ r.x, r.y, r.z };
        VV3 move = at - VV3{ r.px, r.py, r.pz };
        move = select(hasHair, move + (mean - move) * kernel::splat(v.blend), move);
        if (anyPushing) {
            const VV3 damped = move - direction * (v.pushDamping * dot(move, direction));
            move = select(pushing, damped + push, move);
        }
        const VV3 now = select(inHair, at - move, VV3{ r.px, r.py, r.pz });
        r.px = now.x;
        r.py = now.y;
        r.pz = now.z;
    }
}

// The read of volumePass's grid for one block, all 16 lanes at once, a group of the splat's rows at
// a time (sampled at their centroid): each particle's velocity is blended toward the hair's mean
// velocity there by the hair friction, and where the density is above the target it is
// accelerated down the density gradient (see volumePass).
void volumeReadOnTarget(
    const HairVolumeGrid& grid, const Solver::VolumeRead& v, Solver::Block& b, const StepConstants& c)
{
    const Lane keep = v.target * b.volumeTargetScale;
    const Lane inverseKeep = splat(1.0f) / keep;
    const glm::mat3 toHead = glm::transpose(c.rotation);
    const std::uint32_t rows = std::max<std::uint32_t>(1, b.volumeRowsPerSample);
    // A dense groom's grid is read in registers (HairVolumeGridNearest-inl.h), the trilinear one through
    // the grid's row arrays: the same values.
    const bool nearest = grid.kernel() == HairVolumeGrid::Kernel::NearestSmoothed;
    HairVolumeGrid::SampleRow here;
    GroupLanes lanes;
    auto lane = [](const float* p) {
        Lane l;
        std::memcpy(&l, p, sizeof l);
        return l;
    };
    for (std::uint32_t first = 0, g = 0; first < b.points; first += rows, ++g) {
        const std::uint32_t count = std::min(rows, b.points - first);
        if (first + count <= 1)
            continue; // roots are pinned
        for (int slice = 0; slice < kLanes / kernel::kVecLanes; ++slice)
            groupSlice<false>(grid, b, c, toHead, first, count, slice, nearest, lanes);
        const int stride = b.volumeStride(g);
        Lane fields[8]; // the Node's order: density, gradient x y z, momentum x y z, hair
        if (nearest)
            Nearest::readNearest(grid, lanes.nearest, stride, fields);
        else {
            grid.sampleRow(lanes.headX, lanes.headY, lanes.headZ, here, HairVolumeGrid::kRowLanes, stride);
            const float* const from[8] = { here.density, here.gradX, here.gradY, here.gradZ, here.momentumX,
                here.momentumY, here.momentumZ, here.hair };
            for (int f = 0; f < 8; ++f)
                fields[f] = lane(from[f]);
        }
        // The rest is each lane's own, a register's width at a time again.
        for (int slice = 0; slice < kLanes / kernel::kVecLanes; ++slice)
            readSlice(v, b, c, fields, inverseKeep, first, count, slice);
    }
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

namespace wisp {

HWY_EXPORT(volumeSplatOnTarget);
HWY_EXPORT(volumeReadOnTarget);

namespace {

// The scalp area the simulated roots cover, m², when nobody said: the cells of a 1 cm grid that
// hold a root, each about 1 cm² / 1.5 of surface (a plane cuts 1.5 cells per cell area on average).
float estimatedScalpArea(std::span<const Solver::Block> blocks)
{
    constexpr float kCell = 0.01f;
    std::vector<std::int64_t> cells;
    for (const Solver::Block& b : blocks)
        for (int l = 0; l < kLanes; ++l)
            if (b.strand[l] >= 0) {
                const glm::ivec3 c(glm::floor(glm::vec3(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]) / kCell));
                cells.push_back((static_cast<std::int64_t>(c.x & 0x1FFFFF) << 42)
                    | (static_cast<std::int64_t>(c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF));
            }
    std::sort(cells.begin(), cells.end());
    const auto distinct = std::unique(cells.begin(), cells.end()) - cells.begin();
    return static_cast<float>(distinct) * kCell * kCell / 1.5f;
}

} // namespace

// The head-space box every particle stays in (its root's box grown by its strand's length), and
// the hair per scalp area from the particles' weights.
void Solver::updateVolumeBounds()
{
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    double hair = 0.0;
    for (const Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l) {
            if (b.strand[l] < 0)
                continue;
            const glm::vec3 root(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]);
            lo = glm::min(lo, root - b.strandLength[l]);
            hi = glm::max(hi, root + b.strandLength[l]);
            hair += static_cast<double>(b.volumeWeight[l]) * (b.points - 1);
        }
    m_volumeLo = lo;
    m_volumeHi = hi;
    m_volumeUnitsStale = true; // the weights changed: the grid's fixed point is set on the next pass
    if (!(m_scalpArea > 0.0f))
        m_scalpArea = estimatedScalpArea(m_blocks);
    m_hairPerScalpArea = m_scalpArea > 0.0f ? static_cast<float>(hair / m_scalpArea) : 0.0f;
    // A regroom (a brush dab) barely moves the box: the grid is kept while the new box fits in it
    // and fills at least half of it; laying it out again (32 MiB and the head's solid) costs about
    // 0.3 s, far more than a dab.
    if (m_volumeGrid && !m_volumeGrid->empty()) {
        const glm::vec3 gridLo = m_volumeGrid->origin();
        const glm::vec3 gridHi = gridLo + m_volumeGrid->cellMetres() * glm::vec3(m_volumeGrid->dims() - 1);
        const glm::vec3 size = glm::max(hi - lo, glm::vec3(0.0f)), gridSize = gridHi - gridLo;
        const bool fits = glm::all(glm::greaterThanEqual(lo, gridLo)) && glm::all(glm::lessThanEqual(hi, gridHi));
        if (fits && size.x * size.y * size.z >= 0.5f * gridSize.x * gridSize.y * gridSize.z)
            return;
    }
    m_volumeGrid.reset(); // laid out again on the next step with volume on
}

float Solver::volumeTargetDensity() const
{
    return m_settings.volume > 0.0f ? m_hairPerScalpArea / (m_settings.volume * kVolumeDepthMetres) : 0.0f;
}

std::string Solver::setStrandVolume(std::span<const float> drawnStrands, float scalpAreaSquareMetres)
{
    if (!drawnStrands.empty() && drawnStrands.size() != m_strandCount)
        return "drawn strands: " + std::to_string(drawnStrands.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < drawnStrands.size(); ++i)
        if (!(drawnStrands[i] >= 0.0f && drawnStrands[i] <= 1e6f))
            return "drawn strands of strand " + std::to_string(i) + ": " + std::to_string(drawnStrands[i])
                + " is not a finite number of at least 0";
    if (!(scalpAreaSquareMetres >= 0.0f && scalpAreaSquareMetres <= 1e4f))
        return "scalp area: " + std::to_string(scalpAreaSquareMetres) + " m² is not a finite area of at least 0";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        Block& b = m_blocks[slot.block];
        const float drawn = drawnStrands.empty() ? 1.0f : drawnStrands[i];
        b.volumeWeight[slot.lane] = drawn * b.strandLength[slot.lane] / static_cast<float>(b.points - 1);
    }
    m_scalpArea = scalpAreaSquareMetres;
    updateVolumeBounds();
    return {};
}

std::string Solver::setVolumeTargetScales(std::span<const float> perStrand)
{
    if (!perStrand.empty() && perStrand.size() != m_strandCount)
        return "volume target scales: " + std::to_string(perStrand.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < perStrand.size(); ++i)
        if (!(perStrand[i] >= 0.01f && perStrand[i] <= 1e3f))
            return "volume target scale of strand " + std::to_string(i) + ": " + std::to_string(perStrand[i])
                + " is not a finite number within 0.01..1000";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        m_blocks[slot.block].volumeTargetScale[slot.lane] = perStrand.empty() ? 1.0f : perStrand[i];
    }
    return {};
}

// One substep's hair-hair interaction, before the blocks advance (so contact, after it, stays the
// last word): every particle splats its weight and its move over the last substep into the grid;
// then each particle's velocity is blended toward the hair's mean velocity there by the hair
// friction (PIC/FLIP-style, Petrovic et al. 2005 sec. 4; McAdams et al. 2009), and where the
// density is above the target the particle is accelerated down the density gradient (the hair's
// own volume: Petrovic et al.'s pressure term, here only above the target, so hair at or below
// its volume feels nothing). Both change only the previous position (the velocity): the position
// is as the last substep left it, so length and contact stay as they were.
int Solver::volumeRefreshSubsteps(float substepSeconds, bool dense)
{
    const float refresh = dense ? kVolumeDenseRefreshSeconds : kVolumeRefreshSeconds;
    return std::max(1, static_cast<int>(refresh / substepSeconds + 1e-3f));
}

// The grid's nodes (HairVolumeGrid::setBounds) for a scene of `particles`: all the memory bound
// allows up to kVolumeFullGridParticles, and fewer in proportion beyond (a quarter at a million,
// cells 1.6 times as wide): the splat and the read wait on cache misses in a grid much larger than
// the cache, and a dense groom has hair enough in every cell of the coarser grid. Beyond it, too,
// each particle meets only its nearest node (HairVolumeGrid::Kernel::NearestSmoothed): a cell
// holds dozens of particles (groom-1m: a million in 27,000 nodes), so one crossing between nodes
// barely changes either, and the splat and the read cost a node, not eight.
constexpr std::size_t kVolumeFullGridParticles = 250'000;
std::size_t volumeGridNodes(std::size_t particles)
{
    return particles <= kVolumeFullGridParticles
        ? HairVolumeGrid::kMaxNodes
        : static_cast<std::size_t>(static_cast<double>(HairVolumeGrid::kMaxNodes)
            * (static_cast<double>(kVolumeFullGridParticles) / static_cast<double>(particles)));
}

int Solver::volumeRowsPerSampleOfStrand(std::size_t strand) const
{
    return strand < m_slotOfStrand.size() ? static_cast<int>(m_blocks[m_slotOfStrand[strand].block].volumeRowsPerSample)
                                          : 0;
}

int Solver::volumeStrideOfStrand(std::size_t strand) const
{
    if (strand >= m_slotOfStrand.size())
        return 0;
    const Block& b = m_blocks[m_slotOfStrand[strand].block];
    int finest = b.volumeStride(0);
    for (std::uint32_t g = 1; g < b.volumeGroups; ++g)
        finest = std::min(finest, b.volumeStride(g));
    return finest;
}

bool Solver::volumeDense() const
{
    return m_volumeGrid ? m_volumeGrid->kernel() == HairVolumeGrid::Kernel::NearestSmoothed
                        : m_particleCount > kVolumeFullGridParticles;
}

void Solver::volumePass(const StepConstants& c, int substepsUntilNext)
{
    if (!m_volumeGrid) {
        m_volumeGrid = std::make_unique<HairVolumeGrid>();
        m_volumeUnitsStale = true;
        const HairVolumeGrid::Kernel kernel = m_particleCount > kVolumeFullGridParticles
            ? HairVolumeGrid::Kernel::NearestSmoothed
            : HairVolumeGrid::Kernel::Trilinear;
        if (m_volumeGrid->setBounds(m_volumeLo, m_volumeHi, threadCount(), volumeGridNodes(m_particleCount), kernel)
            && m_sdf)
            m_volumeGrid->setSolid([&](const glm::vec3& p) { return m_sdf->distance(p); });
    }
    HairVolumeGrid& grid = *m_volumeGrid;
    if (grid.empty())
        return;
    if (m_volumeUnitsStale) {
        double total = 0.0; // the most weight a pass splats: every particle's
        for (const Block& b : m_blocks)
            for (int l = 0; l < kLanes; ++l)
                total += static_cast<double>(b.volumeWeight[l]) * b.points;
        grid.clear(nullptr);
        grid.setWeightBound(total);
        m_volumeSplatted = false;
        m_volumeUnitsStale = false;
    }
    ++m_volumePasses;
    // Few particles (the editor's keys): the calling thread does it all; waking the pool for each of
    // the pass's loops would cost more than they do.
    constexpr std::size_t kParallelVolumeParticles = 50'000;
    ThreadPool* pool = m_particleCount >= kParallelVolumeParticles ? m_pool.get() : nullptr;
    // The blocks splatted their end state at the end of the last run of substeps (step()); only
    // when something moved particles since (or there was no run) do they splat here, in a sweep.
    if (!m_volumeSplatted) {
        grid.clear(pool);
        auto splatBlocks = [&](std::size_t begin, std::size_t end) {
            const int slot = grid.claimSlot();
            for (std::size_t i = begin; i < end; ++i)
                volumeSplat(m_blocks[i], c, slot);
            grid.releaseSlot(slot);
        };
        forRange(pool, m_blocks.size(), 4, splatBlocks);
    }
    m_volumeSplatted = false;
    VolumeRead& v = m_volumeRead;
    v.target = volumeTargetDensity();
    grid.finish(pool, v.target);

    // The share of the difference from the hair's mean velocity lost this substep: hair_friction
    // is the share lost per 1/60 s, the same at any substep.
    v.blend = 1.0f - std::pow(1.0f - m_settings.hairFriction, c.dt * 60.0f);
    // The push is a stiff spring taken explicitly: past about (cell / dt)² it overshoots and hair
    // bounces on hair (one substep at 60 Hz did, 22 % of tips moving after 10 s), so its stiffness
    // is capped there; at the default two substeps the cap is about 2 m²/s².
    // (The grid is read for substepsUntilNext substeps: the spring's step is that long.)
    const float cell = grid.cellMetres();
    const float refreshSeconds = c.dt * static_cast<float>(substepsUntilNext);
    const float stableShare
        = grid.kernel() == HairVolumeGrid::Kernel::NearestSmoothed ? kVolumeStableShareSmoothed : kVolumeStableShare;
    v.stiffness = std::min(kVolumeStiffness, stableShare * cell * cell / (refreshSeconds * refreshSeconds));
    v.pushDamping = 1.0f - std::exp(-kVolumeDampingPerSecond * c.dt);
}

void Solver::volumeSplat(Block& b, const StepConstants& c, int slot)
{
    HWY_DYNAMIC_DISPATCH(volumeSplatOnTarget)(*m_volumeGrid, b, c, slot);
}

void Solver::volumeRead(Block& b, const StepConstants& c) const
{
    HWY_DYNAMIC_DISPATCH(volumeReadOnTarget)(*m_volumeGrid, m_volumeRead, b, c);
}

} // namespace wisp

#endif // HWY_ONCE
