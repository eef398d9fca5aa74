#pragma once
// A volumetric grid of hair around the head, for hair-hair interaction (Petrovic, Henne & Anderson
// 2005, "Volumetric Methods for Simulation and Rendering of Hair"; McAdams, Selle, Ward, Sifakis &
// Teran 2009, "Detail Preserving Continuum Simulation of Straight Hair"): particles splat their
// weight (metres of drawn hair they stand for) and their move over the last substep into the nodes
// around them (trilinear, cloud-in-cell); the solver then reads back, at each particle, the hair
// density, the hairs' mean move there and the density's gradient.
//
// Deterministic for any thread count and any schedule, without float atomics: each splatting thread
// adds into a slot of its own in 64-bit fixed point, and integer sums do not depend on their order;
// the slots are summed into floats once, in finish(). So the splat can run wherever a particle is
// in cache (the solver splats each block at the end of its substeps, Solver::step).
//
// Lives in head space, so it follows the head. Its resolution adapts to the box it is given, cells
// no finer than kFinestCellMetres, within a bound of kMaxBytes for all its arrays.
//
// Thread: one owner; splat() may be called concurrently for different slots (claimSlot()).

#include <glm/vec3.hpp>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace wisp {

class ThreadPool;
// The grid's loops compiled for one SIMD target (HairVolumeGrid.cpp): one specialisation per target.
template <class Target> struct HairVolumeGridKernels;

class HairVolumeGrid {
    template <class Target> friend struct HairVolumeGridKernels;

public:
    static constexpr int kMaxSlots = 8; // splatting threads at once (more wait for a free slot)
    static constexpr std::size_t kMaxBytes = std::size_t{ 32 } << 20; // 32 MiB
    static constexpr float kFinestCellMetres = 0.008f;

    // How a particle meets the nodes.
    enum class Kernel {
        // It splats into and reads the eight nodes around it, trilinear (cloud-in-cell): the field
        // is continuous in its position, what a groom with a few particles in a cell needs.
        Trilinear,
        // It splats into and reads its nearest node, one node instead of eight; the sums are smoothed
        // by [1 2 1]/4 along each axis before the density is taken (about the cloud-in-cell's spread).
        // For a dense groom (dozens of particles in a cell): one particle crossing between two nodes
        // moves a small share of either's hair, and a particle's read changes by the difference of
        // two smoothed neighbours.
        NearestSmoothed,
    };
    // Lays nodes over [lo, hi] (head space, metres), as fine as the memory bound allows (at most
    // `maxNodes`, at most kMaxNodes), with
    // `slots` (1..kMaxSlots) splat slots: the threads that splat at once. The cell does not depend
    // on `slots` (the same bits on any thread count). False (and an empty grid) when the box is not
    // finite or empty.
    bool setBounds(const glm::vec3& lo, const glm::vec3& hi, int slots = 1, std::size_t maxNodes = kMaxNodes,
        Kernel kernel = Kernel::Trilinear);
    Kernel kernel() const { return m_kernel; }
    bool empty() const { return m_nodes.empty(); }

    // The head as a solid in the grid (Petrovic et al. treat the body as solid too): each node's
    // share inside it, from the signed distance (metres, negative inside) at the node, ramped over
    // one cell. finish() counts a node's solid share as `solidDensity` of hair, so hair lying on the
    // skin is pushed out as by more hair beneath it, and the gradient there points away from the head.
    void setSolid(const std::function<float(const glm::vec3&)>& signedDistance);

    int slots() const { return m_slots; }
    // The most weight all splats between two finish() calls add up to: it sets the fixed point's
    // units (the sums cannot overflow). Call it with no splats pending.
    void setWeightBound(double totalWeight);
    // A move component beyond this (metres a substep) counts as this in the mean: the solver
    // leaves particles moving farther out of the grid.
    static constexpr float kMaxMoveMetres = 0.5f;
    // A slot no other thread holds, for this thread's splats until releaseSlot().
    int claimSlot();
    void releaseSlot(int slot);

    // Forgets the splats since the last finish(). `pool` null: on the calling thread (for few
    // particles, waking the pool costs more than the work).
    void clear(ThreadPool* pool);
    // Adds `weight` and `weight * move` at head-space `p` to slot `slot`. Points outside the grid add
    // nothing.
    inline void splat(int slot, const glm::vec3& p, float weight, const glm::vec3& move);
    // The same for a row of kRowLanes particles (structure of arrays: head-space positions, weights,
    // moves), one after the other in lane order; lanes with weight <= 0 add nothing. The grid
    // coordinates of the row are taken in one vector pass, then each particle adds its eight nodes
    // as four pairs of neighbours along x (one 32-byte add each).
    static constexpr int kRowLanes = 16;
    // `stride` (a power of two, full rows only): only every stride-th lane splats (lanes 0, stride,
    // ...), each with the weight of the lanes it stands for (see sampleRow).
    void splatRow(int slot, const float* x, const float* y, const float* z, const float* weight, const float* moveX,
        const float* moveY, const float* moveZ, int count = kRowLanes, int stride = 1);
    // Sums the slots (and empties them) and derives the density (weight / m³), the mean move and
    // the density gradient (central differences at nodes) that sample() reads.
    void finish(ThreadPool* pool, float solidDensity = 0.0f);

    struct Sample {
        float density = 0.0f; // weight per m³ (the head's solid counted as solidDensity)
        float hair = 0.0f; // interpolated weight of the hair splatted at the nodes around (0: no hair, no move)
        glm::vec3 move{ 0.0f }; // weighted mean move of the hair here
        glm::vec3 gradient{ 0.0f }; // d density / d position, head space, weight per m⁴
    };
    // Trilinear at head-space `p` over the eight nodes around it, of what finish() left at each node
    // (density, its central-difference gradient, the hair's move weighted by its weight); zeros
    // outside the grid. Continuous in `p`: a particle crossing a cell feels no jump (a nearest-node
    // read made curls jitter, README "Hair volume").
    inline Sample sample(const glm::vec3& p) const;
    // sample() for a row of kRowLanes head-space positions, in one vector pass for the coordinates;
    // `momentum` is the hair's summed weight x move (divide by `hair` for the mean move).
    struct SampleRow {
        alignas(64) float density[kRowLanes];
        alignas(64) float hair[kRowLanes];
        alignas(64) float momentumX[kRowLanes];
        alignas(64) float momentumY[kRowLanes];
        alignas(64) float momentumZ[kRowLanes];
        alignas(64) float gradX[kRowLanes];
        alignas(64) float gradY[kRowLanes];
        alignas(64) float gradZ[kRowLanes];
    };
    //
    // `stride` (a power of two, full rows only) is the level of detail of a dense groom, where a row's
    // sixteen strands lie side by side much closer than a cell (Solver::volumeSplat): the
    // grid is sampled at lanes 0, stride, 2 stride, ... and 15, and the lanes between take the linear
    // blend of the two samples around them, as member hairs follow their keys. The blend is fixed
    // per lane, not chosen by position, so it is as continuous in time as the samples.
    void sampleRow(
        const float* x, const float* y, const float* z, SampleRow& out, int count = kRowLanes, int stride = 1) const;
    float cellMetres() const { return m_cell; }
    glm::ivec3 dims() const { return m_dims; }
    glm::vec3 origin() const { return m_origin; }
    std::size_t memoryBytes() const;
    // Total weight splatted (after finish), for tests: a splat conserves it.
    double totalWeight() const;

    // What one node takes, and each slot more: at most kMaxNodes nodes keep the grid within
    // kMaxBytes with kMaxSlots slots.
    static constexpr std::size_t kBytesPerNode = 10 * sizeof(float), kBytesPerNodeSlot = 4 * sizeof(std::int64_t);
    static constexpr std::size_t kMaxNodes = kMaxBytes / (kBytesPerNode + kMaxSlots * kBytesPerNodeSlot);
    // Kernel::NearestSmoothed's two arrays for the smoothing passes, and its node bound.
    static constexpr std::size_t kBytesPerSmoothedNode = 2 * 4 * sizeof(float);
    static constexpr std::size_t kMaxSmoothedNodes
        = kMaxBytes / (kBytesPerNode + kBytesPerSmoothedNode + kMaxSlots * kBytesPerNodeSlot);

private:
    // A node's splats in a slot, fixed point (m_weightUnits and m_moveUnits): a pair of nodes
    // along x is added in one vector instruction.
    struct Accumulator {
        std::int64_t weight, moveX, moveY, moveZ;
    };
    // What sample() reads, eight floats: one node of a pair (x even, x odd) shares a cache line.
    struct alignas(32) Node {
        float density; // hair and head, weight per m³
        float gradX, gradY, gradZ; // its central differences, weight per m⁴
        float moveX, moveY, moveZ; // the hair's summed weight x move (momentum; divided in sample())
        float weight; // the hair's summed weight
    };
    // Grid coordinates of a row: per lane the index of the cell's low node (-1: outside the grid or
    // not finite), the node's coordinates and the position within the cell (0..1 each way).
    struct CellRow {
        alignas(64) int node[kRowLanes];
        alignas(64) int nearest[kRowLanes]; // the index of the nearest node (-1: outside)
        alignas(64) int ix[kRowLanes];
        alignas(64) int iy[kRowLanes];
        alignas(64) int iz[kRowLanes];
        alignas(64) float fx[kRowLanes];
        alignas(64) float fy[kRowLanes];
        alignas(64) float fz[kRowLanes];
    };
    // Hair and head at a node (clamped into the grid), for the central differences.
    float densityAt(int i, int j, int k) const
    {
        const std::size_t n
            = index(std::clamp(i, 0, m_dims.x - 1), std::clamp(j, 0, m_dims.y - 1), std::clamp(k, 0, m_dims.z - 1));
        return m_hairDensity[n] + m_solid[n] * m_solidDensity;
    }
    float m_solidDensity = 0.0f;
    std::size_t index(int i, int j, int k) const
    {
        return static_cast<std::size_t>(i)
            + static_cast<std::size_t>(m_dims.x)
            * (static_cast<std::size_t>(j) + static_cast<std::size_t>(m_dims.y) * k);
    }

    Kernel m_kernel = Kernel::Trilinear;
    struct Sums {
        float weight, moveX, moveY, moveZ;
    };
    // Per node (Kernel::NearestSmoothed only): the sums, smoothed along one axis after another
    // ([1 2 1]/4 along x into a scratch of one brick layer, along y back into m_sums, along z into
    // the nodes).
    std::vector<Sums> m_sums;

    glm::ivec3 m_dims{ 0 };
    glm::vec3 m_origin{ 0.0f };
    float m_cell = 0.0f;
    std::vector<Accumulator> m_accumulators; // m_slots grids, one after the other
    int m_slots = 1;
    // Fixed-point units per unit of weight and of weight x move (setWeightBound), powers of two.
    float m_weightUnits = 0x1p20f, m_moveUnits = 0x1p24f;
    std::atomic<std::uint32_t> m_claimed{ 0 }; // a bit per slot held
    std::vector<Node> m_nodes;
    std::vector<float> m_hairDensity; // per node: the hair's weight per m³ (0 outside the live bricks)
    std::vector<float> m_solid; // per node: 0..1 inside the head
    // Bricks of kBrick³ nodes: only those a splat touched are cleared, summed and differenced, so a
    // pass costs what the hair occupies, not the whole grid (the editor's 7,600 particles would
    // otherwise pay for 200,000 nodes in eight chunks). Kernel::NearestSmoothed also the bricks
    // beside them, where the smoothing spreads the sums.
    static constexpr int kBrick = 4;
    std::size_t brickIndex(int bx, int by, int bz) const
    {
        return static_cast<std::size_t>(bx)
            + static_cast<std::size_t>(m_bricks.x)
            * (static_cast<std::size_t>(by) + static_cast<std::size_t>(m_bricks.y) * bz);
    }
    template <typename Fn> void forNodesOf(std::size_t brick, Fn&& fn) const;
    // fn(i0, j, k, n0, nodes) for each row of a brick along x: `nodes` nodes from n0 = index(i0, j, k)
    // (kBrick, fewer at the grid's far x face).
    template <typename Fn> void forRowsOf(std::size_t brick, Fn&& fn) const;
    std::size_t brickLayerSize() const { return static_cast<std::size_t>(m_bricks.x) * m_bricks.y; }
    glm::ivec3 m_bricks{ 0 };
    std::vector<std::uint8_t> m_touched; // per slot and brick: a splat of the slot wrote there
    std::vector<std::uint8_t> m_live; // per brick: its nodes hold the last finish's sums
    std::vector<std::uint32_t> m_liveList;
};

inline void HairVolumeGrid::splat(int slot, const glm::vec3& p, float weight, const glm::vec3& move)
{
    splatRow(slot, &p.x, &p.y, &p.z, &weight, &move.x, &move.y, &move.z, 1);
}

inline HairVolumeGrid::Sample HairVolumeGrid::sample(const glm::vec3& p) const
{
    SampleRow row;
    sampleRow(&p.x, &p.y, &p.z, row, 1);
    Sample s;
    s.density = row.density[0];
    s.gradient = glm::vec3(row.gradX[0], row.gradY[0], row.gradZ[0]);
    s.hair = row.hair[0];
    if (s.hair > 0.0f)
        s.move = glm::vec3(row.momentumX[0], row.momentumY[0], row.momentumZ[0]) * (1.0f / s.hair);
    return s;
}

} // namespace wisp
