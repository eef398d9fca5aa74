#include "sim/solver/HairVolumeGrid.h"

#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <thread>

#ifndef WISP_HAIR_VOLUME_GRID_ONCE_
#define WISP_HAIR_VOLUME_GRID_ONCE_
namespace wisp {

} // namespace wisp
#endif

// The per-particle and per-node loops (the splat, the read and finish()) are compiled once per SIMD
// target, as the solver's kernels (SolverBlockKernel.cpp), and the members below run the best the
// CPU has; the rest of the file once. Each target's loops are the static members of
// HairVolumeGridKernels<its tag> (a friend: they read the grid's arrays).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/solver/HairVolumeGrid.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/HairVolumeGridNearest-inl.h"

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace wisp {

namespace HWY_NAMESPACE {
struct GridTarget { }; // this target's HairVolumeGridKernels

} // namespace HWY_NAMESPACE

template <> struct HairVolumeGridKernels<HWY_NAMESPACE::GridTarget> {
    using G = HairVolumeGrid;
    using CellRow = G::CellRow;
    using SampleRow = G::SampleRow;
    using Node = G::Node;
    using Sums = G::Sums;
    using Accumulator = G::Accumulator;
    using Kernel = G::Kernel;
    // A dense groom's rows (HairVolumeGridNearest-inl.h), shared with the solver's splat and read.
    using Nearest = HairVolumeGridKernels<HWY_NAMESPACE::GridNearestTarget>;
    static constexpr int kBrick = G::kBrick, kRowLanes = G::kRowLanes;
    static constexpr float kMaxMoveMetres = G::kMaxMoveMetres;
    // A row of kBrick (4) nodes along x in finish(): their four sums each (Sums), one AVX-512 register
    // of floats (two of AVX2); the slots' fixed point and its conversion through doubles.
    using Float16 = float __attribute__((vector_size(16 * sizeof(float))));
    using Fixed16 = std::int64_t __attribute__((vector_size(16 * sizeof(std::int64_t))));
    using Double16 = double __attribute__((vector_size(16 * sizeof(double))));
    using Float4 = float __attribute__((vector_size(4 * sizeof(float)))); // one value of four nodes
    // Eight floats, one AVX register: a pair of neighbouring nodes along x (splat), or one node (sample).
    using Float8 = float __attribute__((vector_size(8 * sizeof(float))));
    using Fixed8 = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));
    static Float8 load8(const float* p)
    {
        Float8 v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }

    // The row's grid coordinates (CellRow), in one vector pass.
    static void cellsOf(const G& g, const float* x, const float* y, const float* z, int count, CellRow& out);
    static void splatRow(G& g, int slot, const float* x, const float* y, const float* z, const float* weight,
        const float* moveX, const float* moveY, const float* moveZ, int count, int stride);
    static void sampleRow(
        const G& g, const float* x, const float* y, const float* z, SampleRow& out, int count, int stride);
    static void finish(G& g, ThreadPool* pool, float solidDensity);
};

void HairVolumeGridKernels<HWY_NAMESPACE::GridTarget>::finish(G& g, ThreadPool* pool, float solidDensity)
{
    const std::size_t count = g.m_nodes.size(), bricks = g.m_live.size();
    // The bricks any slot touched; the nodes of bricks touched last time and not now go empty.
    std::vector<std::uint32_t> now;
    for (std::size_t b = 0; b < bricks; ++b) {
        bool any = false;
        for (int c = 0; c < g.m_slots; ++c) {
            std::uint8_t& touched = g.m_touched[static_cast<std::size_t>(c) * bricks + b];
            any = any || touched != 0;
            touched = 0; // emptied below
        }
        if (any)
            now.push_back(static_cast<std::uint32_t>(b));
    }
    if (g.m_kernel == Kernel::NearestSmoothed) {
        // The smoothing spreads a node's sums one node each way: into the bricks beside.
        std::vector<std::uint8_t> near(bricks, 0);
        for (const std::uint32_t b : now) {
            const int bx = static_cast<int>(b % static_cast<std::uint32_t>(g.m_bricks.x));
            const int by = static_cast<int>(
                (b / static_cast<std::uint32_t>(g.m_bricks.x)) % static_cast<std::uint32_t>(g.m_bricks.y));
            const int bz = static_cast<int>(b / (static_cast<std::uint32_t>(g.m_bricks.x) * g.m_bricks.y));
            for (int k = std::max(bz - 1, 0); k <= std::min(bz + 1, g.m_bricks.z - 1); ++k)
                for (int j = std::max(by - 1, 0); j <= std::min(by + 1, g.m_bricks.y - 1); ++j)
                    for (int i = std::max(bx - 1, 0); i <= std::min(bx + 1, g.m_bricks.x - 1); ++i)
                        near[g.brickIndex(i, j, k)] = 1;
        }
        now.clear();
        for (std::size_t b = 0; b < bricks; ++b)
            if (near[b])
                now.push_back(static_cast<std::uint32_t>(b));
    }
    for (const std::uint32_t b : g.m_liveList)
        g.m_live[b] = 0;
    for (const std::uint32_t b : now)
        g.m_live[b] = 1;
    for (const std::uint32_t b : g.m_liveList)
        if (!g.m_live[b])
            g.forNodesOf(b, [&](int, int, int, std::size_t n) {
                g.m_nodes[n] = Node{};
                g.m_hairDensity[n] = 0.0f;
                if (!g.m_sums.empty())
                    g.m_sums[n] = Sums{};
            });
    g.m_liveList = std::move(now);
    g.m_solidDensity = solidDensity;

    // What sample() reads, in three passes over the live nodes, a row of kBrick nodes along x at a
    // time (one vector each): the slots' sums (the slots emptied for the next splats), then the
    // smoothing (Kernel::NearestSmoothed) and the node's hair, then the density's gradient, which
    // takes the neighbours' density. Each pass is one wait for the pool: on a dense groom's small
    // grid (25,000 nodes) the waits, not the arithmetic, were most of finish().
    static_assert(sizeof(Sums) == 4 * sizeof(float) && sizeof(Accumulator) == 4 * sizeof(std::int64_t),
        "a row of kBrick nodes is read and written as one vector of each");
    const float perVolume = 1.0f / (g.m_cell * g.m_cell * g.m_cell);
    const double perWeight = 1.0 / static_cast<double>(g.m_weightUnits),
                 perMove = 1.0 / static_cast<double>(g.m_moveUnits);
    // A row's sums over the slots, as floats (weight, move x, y, z a node, as Sums), into `out`.
    auto sumRow = [&](std::size_t n0, int nodes, float* out) {
        if (nodes == kBrick) {
            Fixed16 total{};
            for (int c = 0; c < g.m_slots; ++c) { // integers: the same sum in any order
                Accumulator* const a = &g.m_accumulators[static_cast<std::size_t>(c) * count + n0];
                Fixed16 v;
                std::memcpy(&v, a, sizeof v);
                total += v;
                std::memset(static_cast<void*>(a), 0, sizeof v);
            }
            const Double16 units{ perWeight, perMove, perMove, perMove, perWeight, perMove, perMove, perMove, perWeight,
                perMove, perMove, perMove, perWeight, perMove, perMove, perMove };
            const Float16 sums = __builtin_convertvector(__builtin_convertvector(total, Double16) * units, Float16);
            std::memcpy(out, &sums, sizeof sums);
            return;
        }
        for (int i = 0; i < nodes; ++i) {
            Accumulator sum{};
            for (int c = 0; c < g.m_slots; ++c) {
                Accumulator& a = g.m_accumulators[static_cast<std::size_t>(c) * count + n0 + i];
                sum.weight += a.weight;
                sum.moveX += a.moveX;
                sum.moveY += a.moveY;
                sum.moveZ += a.moveZ;
                a = Accumulator{};
            }
            float* const s = out + 4 * i;
            s[0] = static_cast<float>(sum.weight * perWeight);
            s[1] = static_cast<float>(sum.moveX * perMove);
            s[2] = static_cast<float>(sum.moveY * perMove);
            s[3] = static_cast<float>(sum.moveZ * perMove);
        }
    };
    // [1 2 1]/4 of `from` along `axis` over a row, into `out` (as Sums); node n of the grid is
    // from[n - fromBase]. At the grid's faces the missing neighbour is the node itself, so the
    // smoothing keeps the total weight. Nodes outside the live bricks hold zeros (emptied above),
    // and no sum reaches them.
    const std::ptrdiff_t steps[3] = { 1, g.m_dims.x, static_cast<std::ptrdiff_t>(g.m_dims.x) * g.m_dims.y };
    auto smoothRow = [&](const Sums* grid, std::size_t fromBase, int axis, int i0, int j, int k, std::size_t n0,
                         int nodes, float* out) {
        const Sums* const from = grid - fromBase; // (only ever indexed at n >= fromBase)
        const std::ptrdiff_t step = steps[axis];
        const int size = g.m_dims[axis];
        if (nodes == kBrick && (axis != 0 || (i0 > 0 && i0 + kBrick < size))) {
            const int at = axis == 1 ? j : k;
            Float16 here, before, after;
            std::memcpy(&here, from + n0, sizeof here);
            if (axis != 0 && at == 0)
                before = here;
            else
                std::memcpy(&before, from + n0 - step, sizeof before);
            if (axis != 0 && at + 1 == size)
                after = here;
            else
                std::memcpy(&after, from + n0 + step, sizeof after);
            const Float16 smoothed = 0.25f * (before + after) + 0.5f * here;
            std::memcpy(out, &smoothed, sizeof smoothed);
            return;
        }
        for (int i = 0; i < nodes; ++i) {
            const std::size_t n = n0 + static_cast<std::size_t>(i);
            const int at = axis == 0 ? i0 + i : axis == 1 ? j : k;
            const Sums& here = from[n];
            const Sums& before = at > 0 ? from[n - static_cast<std::size_t>(step)] : here;
            const Sums& after = at + 1 < size ? from[n + static_cast<std::size_t>(step)] : here;
            float* const s = out + 4 * i;
            s[0] = 0.25f * (before.weight + after.weight) + 0.5f * here.weight;
            s[1] = 0.25f * (before.moveX + after.moveX) + 0.5f * here.moveX;
            s[2] = 0.25f * (before.moveY + after.moveY) + 0.5f * here.moveY;
            s[3] = 0.25f * (before.moveZ + after.moveZ) + 0.5f * here.moveZ;
        }
    };
    auto storeRow = [&](std::size_t n0, int nodes, const float* sums) { // what sample() reads of the hair
        if (nodes == kBrick) { // a shuffle and a 16-byte store a node (GCC stored the row float by float)
            Float16 all;
            std::memcpy(&all, sums, sizeof all);
            for (int i = 0; i < kBrick; ++i) {
                const Float4 sum = { all[4 * i], all[4 * i + 1], all[4 * i + 2], all[4 * i + 3] };
                const Float4 hair = __builtin_shufflevector(sum, sum, 1, 2, 3, 0); // Node's moveX, moveY, moveZ, weight
                std::memcpy(&g.m_nodes[n0 + static_cast<std::size_t>(i)].moveX, &hair, sizeof hair);
            }
            const Float4 weight = { all[0], all[4], all[8], all[12] };
            const Float4 density = weight * perVolume;
            std::memcpy(&g.m_hairDensity[n0], &density, sizeof density);
            return;
        }
        for (int i = 0; i < nodes; ++i) {
            Node& node = g.m_nodes[n0 + static_cast<std::size_t>(i)];
            const float* const s = sums + 4 * i;
            node.weight = s[0];
            node.moveX = s[1];
            node.moveY = s[2];
            node.moveZ = s[3];
            g.m_hairDensity[n0 + static_cast<std::size_t>(i)] = s[0] * perVolume;
        }
    };
    auto rowsOfLive = [&](std::size_t begin, std::size_t end, auto&& fn) {
        for (std::size_t l = begin; l < end; ++l)
            g.forRowsOf(g.m_liveList[l], fn);
    };
    if (g.m_kernel == Kernel::NearestSmoothed) {
        // The sums and the smoothing along x and y touch only nodes of one z plane: a layer of
        // bricks (those of one brick z, contiguous in g.m_liveList, which is in brick order) does
        // all three in one go. Along z it takes the layers beside: the next pass.
        std::vector<std::size_t> layers;
        for (std::size_t l = 0; l < g.m_liveList.size(); ++l)
            if (l == 0 || g.m_liveList[l] / g.brickLayerSize() != g.m_liveList[l - 1] / g.brickLayerSize())
                layers.push_back(l);
        layers.push_back(g.m_liveList.size());
        // The smoothing along x goes into a scratch of one layer's planes (zeros outside its live
        // bricks, as the grid's are), which the smoothing along y reads back into the sums: the
        // grid keeps no second array of sums (16 bytes a node).
        const std::size_t plane = static_cast<std::size_t>(steps[2]);
        forRange(pool, layers.size() - 1, 1, [&](std::size_t begin, std::size_t end) {
            std::vector<Sums> scratch(plane * kBrick);
            for (std::size_t layer = begin; layer < end; ++layer) {
                const std::size_t first = layers[layer], last = layers[layer + 1];
                const std::size_t base = g.m_liveList[first] / g.brickLayerSize() * kBrick * plane;
                std::fill(scratch.begin(), scratch.end(), Sums{});
                rowsOfLive(first, last,
                    [&](int, int, int, std::size_t n0, int nodes) { sumRow(n0, nodes, &g.m_sums[n0].weight); });
                rowsOfLive(first, last, [&](int i0, int j, int k, std::size_t n0, int nodes) {
                    smoothRow(g.m_sums.data(), 0, 0, i0, j, k, n0, nodes, &scratch[n0 - base].weight);
                });
                rowsOfLive(first, last, [&](int i0, int j, int k, std::size_t n0, int nodes) {
                    smoothRow(scratch.data(), base, 1, i0, j, k, n0, nodes, &g.m_sums[n0].weight);
                });
            }
        });
        forRange(pool, g.m_liveList.size(), 4, [&](std::size_t begin, std::size_t end) {
            rowsOfLive(begin, end, [&](int i0, int j, int k, std::size_t n0, int nodes) {
                alignas(64) float sums[4 * kBrick];
                smoothRow(g.m_sums.data(), 0, 2, i0, j, k, n0, nodes, sums);
                storeRow(n0, nodes, sums);
            });
        });
    } else {
        forRange(pool, g.m_liveList.size(), 4, [&](std::size_t begin, std::size_t end) {
            rowsOfLive(begin, end, [&](int, int, int, std::size_t n0, int nodes) {
                alignas(64) float sums[4 * kBrick];
                sumRow(n0, nodes, sums);
                storeRow(n0, nodes, sums);
            });
        });
    }
    const float inv2h = 0.5f / g.m_cell;
    forRange(pool, g.m_liveList.size(), 4, [&](std::size_t begin, std::size_t end) {
        rowsOfLive(begin, end, [&](int i0, int j, int k, std::size_t n0, int nodes) {
            if (nodes == kBrick && i0 > 0 && i0 + kBrick < g.m_dims.x && j > 0 && j + 1 < g.m_dims.y && k > 0
                && k + 1 < g.m_dims.z) {
                auto density = [&](std::size_t n) { // hair and head at four nodes from n
                    Float4 hair, solid;
                    std::memcpy(&hair, &g.m_hairDensity[n], sizeof hair);
                    std::memcpy(&solid, &g.m_solid[n], sizeof solid);
                    return hair + solid * g.m_solidDensity;
                };
                const std::size_t sy = static_cast<std::size_t>(steps[1]), sz = static_cast<std::size_t>(steps[2]);
                const Float4 here = density(n0), gx = (density(n0 + 1) - density(n0 - 1)) * inv2h,
                             gy = (density(n0 + sy) - density(n0 - sy)) * inv2h,
                             gz = (density(n0 + sz) - density(n0 - sz)) * inv2h;
                // Node i's (density, gradient) is column i of these four: a 4 x 4 transpose, then a
                // 16-byte store a node.
                const Float4 t0 = __builtin_shufflevector(here, gx, 0, 4, 1, 5),
                             t1 = __builtin_shufflevector(here, gx, 2, 6, 3, 7),
                             t2 = __builtin_shufflevector(gy, gz, 0, 4, 1, 5),
                             t3 = __builtin_shufflevector(gy, gz, 2, 6, 3, 7);
                const Float4 columns[kBrick]
                    = { __builtin_shufflevector(t0, t2, 0, 1, 4, 5), __builtin_shufflevector(t0, t2, 2, 3, 6, 7),
                          __builtin_shufflevector(t1, t3, 0, 1, 4, 5), __builtin_shufflevector(t1, t3, 2, 3, 6, 7) };
                for (int i = 0; i < kBrick; ++i)
                    std::memcpy(&g.m_nodes[n0 + static_cast<std::size_t>(i)].density, &columns[i], sizeof columns[i]);
                return;
            }
            for (int i = i0; i < i0 + nodes; ++i) {
                Node& node = g.m_nodes[n0 + static_cast<std::size_t>(i - i0)];
                const std::size_t n = n0 + static_cast<std::size_t>(i - i0);
                node.density = g.m_hairDensity[n] + g.m_solid[n] * g.m_solidDensity;
                node.gradX = (g.densityAt(i + 1, j, k) - g.densityAt(i - 1, j, k)) * inv2h;
                node.gradY = (g.densityAt(i, j + 1, k) - g.densityAt(i, j - 1, k)) * inv2h;
                node.gradZ = (g.densityAt(i, j, k + 1) - g.densityAt(i, j, k - 1)) * inv2h;
            }
        });
    });
}

void HairVolumeGridKernels<HWY_NAMESPACE::GridTarget>::cellsOf(
    const G& g, const float* x, const float* y, const float* z, int count, CellRow& out)
{
    // A whole row in a few vector instructions, a register's width at a time (on AVX2 a 16-lane
    // value is two registers, and GCC took this row's arithmetic lane by lane: 2,000 instructions,
    // a fifth of the small default-volume workloads' time at AVX2, perf); a shorter row is padded
    // with NaN (outside). The same arithmetic lane by lane either way.
    using V = HWY_NAMESPACE::kernel::Lane;
    using M = HWY_NAMESPACE::kernel::Mask;
    constexpr int kWidth = HWY_NAMESPACE::kernel::kVecLanes;
    alignas(64) float px[kRowLanes], py[kRowLanes], pz[kRowLanes];
    for (int l = 0; l < kRowLanes; ++l) {
        px[l] = l < count ? x[l] : NAN;
        py[l] = l < count ? y[l] : NAN;
        pz[l] = l < count ? z[l] : NAN;
    }
    for (int first = 0; first < kRowLanes; first += kWidth) {
        V vx, vy, vz;
        std::memcpy(&vx, px + first, sizeof vx);
        std::memcpy(&vy, py + first, sizeof vy);
        std::memcpy(&vz, pz + first, sizeof vz);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes" // (V's alignment: its size's anyway)
        const Nearest::CoordinatesOf<V> c = Nearest::coordinatesOf(g, vx, vy, vz);
#pragma GCC diagnostic pop
        const M ix = c.ix, iy = c.iy, iz = c.iz;
        const V zero{};
        const V fx = c.inside ? c.fx : zero, fy = c.inside ? c.fy : zero, fz = c.inside ? c.fz : zero;
        const M node = c.inside ? ix + g.m_dims.x * (iy + g.m_dims.y * iz) : M{} - 1;
        const M nearest = Nearest::nearestNodes(g, c);
        std::memcpy(out.nearest + first, &nearest, sizeof nearest);
        std::memcpy(out.ix + first, &ix, sizeof ix);
        std::memcpy(out.iy + first, &iy, sizeof iy);
        std::memcpy(out.iz + first, &iz, sizeof iz);
        std::memcpy(out.fx + first, &fx, sizeof fx);
        std::memcpy(out.fy + first, &fy, sizeof fy);
        std::memcpy(out.fz + first, &fz, sizeof fz);
        std::memcpy(out.node + first, &node, sizeof node);
    }
}

void HairVolumeGridKernels<HWY_NAMESPACE::GridTarget>::splatRow(G& g, int slot, const float* x, const float* y,
    const float* z, const float* weight, const float* moveX, const float* moveY, const float* moveZ, int count,
    int stride)
{
    stride = count == kRowLanes ? std::clamp(stride, 1, kRowLanes) : 1;
    if (g.m_kernel == Kernel::NearestSmoothed) { // a shorter row padded with lanes outside the grid
        Lane row[7];
        const float* const from[7] = { x, y, z, weight, moveX, moveY, moveZ };
        for (int i = 0; i < 7; ++i) {
            row[i] = Lane{} + (i < 3 ? NAN : 0.0f);
            std::memcpy(&row[i], from[i], static_cast<std::size_t>(count) * sizeof(float));
        }
        Nearest::splatNearestRow(g, slot, row[0], row[1], row[2], row[3], row[4], row[5], row[6], stride);
        return;
    }
    CellRow cells;
    cellsOf(g, x, y, z, count, cells);
    std::int64_t* const grid = &g.m_accumulators[static_cast<std::size_t>(slot) * g.m_nodes.size()].weight;
    const std::ptrdiff_t strideY = 4 * static_cast<std::ptrdiff_t>(g.m_dims.x),
                         strideZ = strideY * static_cast<std::ptrdiff_t>(g.m_dims.y);
    std::uint8_t* const touched = g.m_touched.data() + static_cast<std::size_t>(slot) * g.m_live.size();
    const Float8 units{ g.m_weightUnits, g.m_moveUnits, g.m_moveUnits, g.m_moveUnits, g.m_weightUnits, g.m_moveUnits,
        g.m_moveUnits, g.m_moveUnits };
    const std::size_t brickY = static_cast<std::size_t>(g.m_bricks.x),
                      brickZ = brickY * static_cast<std::size_t>(g.m_bricks.y);
    // Side-by-side particles (a row's neighbouring strands) often share a cell: their adds are
    // summed in registers and written once per run of one cell, so they do not wait on each other
    // through memory. Always in lane order: the same bits every time.
    int runNode = -1, ix = 0, iy = 0, iz = 0;
    Float8 run[4] = {};
    auto flush = [&] {
        if (runNode < 0)
            return;
        // The bricks of the eight nodes: one, unless the cell's far corner is in the next brick
        // along an axis. Eight stores, some to the same byte, and no branch: written as loops, GCC
        // made the innermost a call to memset, with every live register spilled around it (perf:
        // a tenth of the splat's time on paper-35x35x30).
        const int bx = ix / kBrick, by = iy / kBrick, bz = iz / kBrick;
        const std::size_t nx = static_cast<std::size_t>((ix + 1) / kBrick - bx),
                          ny = static_cast<std::size_t>((iy + 1) / kBrick - by) * brickY,
                          nz = static_cast<std::size_t>((iz + 1) / kBrick - bz) * brickZ;
        std::uint8_t* const brick = touched + g.brickIndex(bx, by, bz);
        brick[0] = brick[nx] = brick[ny] = brick[nx + ny] = 1;
        brick[nz] = brick[nx + nz] = brick[ny + nz] = brick[nx + ny + nz] = 1;
        // In fixed point, rounded half away from zero: the same integers wherever this row is
        // splatted, and no drift toward zero in the sums.
        std::int64_t* const base = grid + 4 * static_cast<std::ptrdiff_t>(runNode);
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy) {
                std::int64_t* const pair = base + dy * strideY + dz * strideZ;
                const Float8 value = run[2 * dz + dy] * units;
                Fixed8 sum;
                std::memcpy(&sum, pair, sizeof sum);
                sum += HWY_NAMESPACE::lanes::roundToInt64(value);
                std::memcpy(pair, &sum, sizeof sum);
            }
    };
    for (int l = 0; l < count; l += stride) {
        const float w = weight[l];
        if (cells.node[l] < 0 || !(w > 0.0f))
            continue;
        if (cells.node[l] != runNode) {
            flush();
            runNode = cells.node[l];
            ix = cells.ix[l];
            iy = cells.iy[l];
            iz = cells.iz[l];
            run[0] = run[1] = run[2] = run[3] = Float8{};
        }
        // (weight, weight x move) at the low and the high node along x, in one register.
        const float fx = cells.fx[l], fy = cells.fy[l], fz = cells.fz[l];
        const float mx = std::clamp(moveX[l], -kMaxMoveMetres, kMaxMoveMetres),
                    my = std::clamp(moveY[l], -kMaxMoveMetres, kMaxMoveMetres),
                    mz = std::clamp(moveZ[l], -kMaxMoveMetres, kMaxMoveMetres);
        const Float8 value = Float8{ 1.0f, mx, my, mz, 1.0f, mx, my, mz };
        const Float8 wx = Float8{ 1.0f - fx, 1.0f - fx, 1.0f - fx, 1.0f - fx, fx, fx, fx, fx };
        const float wz[2] = { w * (1.0f - fz), w * fz }, wy[2] = { 1.0f - fy, fy };
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy)
                run[2 * dz + dy] += (wz[dz] * wy[dy]) * wx * value;
    }
    flush();
}

void HairVolumeGridKernels<HWY_NAMESPACE::GridTarget>::sampleRow(
    const G& g, const float* x, const float* y, const float* z, SampleRow& out, int count, int stride)
{
    if (g.m_kernel == Kernel::NearestSmoothed && count == kRowLanes) { // the solver's read, in registers
        Lane px, py, pz, v[8];
        std::memcpy(&px, x, sizeof px);
        std::memcpy(&py, y, sizeof py);
        std::memcpy(&pz, z, sizeof pz);
        Nearest::readNearestRow(g, px, py, pz, stride, v);
        float* const fields[8] = { out.density, out.gradX, out.gradY, out.gradZ, out.momentumX, out.momentumY,
            out.momentumZ, out.hair }; // Node's order
        for (int f = 0; f < 8; ++f)
            std::memcpy(fields[f], &v[f], sizeof v[f]);
        return;
    }
    CellRow cells;
    cellsOf(g, x, y, z, count, cells);
    const std::ptrdiff_t strideY = g.m_dims.x, strideZ = strideY * g.m_dims.y;
    stride = count == kRowLanes ? std::clamp(stride, 1, kRowLanes) : 1;
    // Lane l's eight values (Node's order), from its eight nodes or its nearest.
    auto sampleLane = [&](int l) {
        Float8 sum{};
        if (g.m_kernel == Kernel::NearestSmoothed) {
            if (cells.nearest[l] >= 0)
                sum = load8(&g.m_nodes[static_cast<std::size_t>(cells.nearest[l])].density);
        } else if (cells.node[l] >= 0) {
            const float fx = cells.fx[l], fy = cells.fy[l], fz = cells.fz[l];
            const float wz[2] = { 1.0f - fz, fz }, wy[2] = { 1.0f - fy, fy }, wx[2] = { 1.0f - fx, fx };
            const Node* const base = g.m_nodes.data() + cells.node[l];
            for (int dz = 0; dz < 2; ++dz)
                for (int dy = 0; dy < 2; ++dy) {
                    const Node* const row = base + dy * strideY + dz * strideZ;
                    const float wyz = wz[dz] * wy[dy];
                    sum += load8(&row[0].density) * (wyz * wx[0]);
                    sum += load8(&row[1].density) * (wyz * wx[1]);
                }
        }
        return sum;
    };
    if (stride == 1 && count == kRowLanes) {
        // Eight lanes at a time, their values turned into the row's arrays by an 8 x 8 transpose
        // (Nearest::transpose8): taken out lane by lane instead, each lane's eight
        // values were seven extracts and eight scalar stores, where perf put a fifth of the read.
        float* const fields[8] = { out.density, out.gradX, out.gradY, out.gradZ, out.momentumX, out.momentumY,
            out.momentumZ, out.hair }; // Node's order
        for (int first = 0; first < kRowLanes; first += 8) {
            Float8 r[8], values[8];
            for (int i = 0; i < 8; ++i)
                r[i] = sampleLane(first + i);
            Nearest::transpose8(r, values);
            for (int f = 0; f < 8; ++f)
                std::memcpy(fields[f] + first, &values[f], sizeof values[f]);
        }
        return;
    }
    for (int l = 0; l < count; l = l + stride < count || l == count - 1 ? l + stride : count - 1) {
        const Float8 sum = sampleLane(l);
        out.density[l] = sum[0];
        out.gradX[l] = sum[1];
        out.gradY[l] = sum[2];
        out.gradZ[l] = sum[3];
        out.momentumX[l] = sum[4];
        out.momentumY[l] = sum[5];
        out.momentumZ[l] = sum[6];
        out.hair[l] = sum[7];
    }
    if (stride == 1)
        return;
    // The lanes between two samples: the linear blend of the two, in one vector pass per array.
    float* const fields[8]
        = { out.density, out.hair, out.momentumX, out.momentumY, out.momentumZ, out.gradX, out.gradY, out.gradZ };
    Lane v[8];
    for (int f = 0; f < 8; ++f)
        std::memcpy(&v[f], fields[f], sizeof v[f]);
    Nearest::blendBetweenSamples(stride, v, 8);
    for (int f = 0; f < 8; ++f)
        std::memcpy(fields[f], &v[f], sizeof v[f]);
}

namespace HWY_NAMESPACE {
using Kernels = HairVolumeGridKernels<GridTarget>;
using G = HairVolumeGrid;

// What the members dispatch to.
void splatRowOnTarget(G& g, int slot, const float* x, const float* y, const float* z, const float* weight,
    const float* moveX, const float* moveY, const float* moveZ, int count, int stride)
{
    Kernels::splatRow(g, slot, x, y, z, weight, moveX, moveY, moveZ, count, stride);
}
void sampleRowOnTarget(
    const G& g, const float* x, const float* y, const float* z, G::SampleRow& out, int count, int stride)
{
    Kernels::sampleRow(g, x, y, z, out, count, stride);
}
void finishOnTarget(G& g, ThreadPool* pool, float solidDensity)
{
    Kernels::finish(g, pool, solidDensity);
}

} // namespace HWY_NAMESPACE
} // namespace wisp
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

namespace wisp {

HWY_EXPORT(splatRowOnTarget);
HWY_EXPORT(sampleRowOnTarget);
HWY_EXPORT(finishOnTarget);

bool HairVolumeGrid::setBounds(const glm::vec3& lo, const glm::vec3& hi, int slots, std::size_t maxNodes, Kernel kernel)
{
    m_slots = std::clamp(slots, 1, kMaxSlots);
    m_kernel = kernel;
    m_sums.clear();
    m_nodes.clear();
    m_hairDensity.clear();
    m_solid.clear();
    m_accumulators.clear();
    m_touched.clear();
    m_live.clear();
    m_liveList.clear();
    m_dims = glm::ivec3(0);
    const glm::vec3 size = hi - lo;
    if (!(std::isfinite(size.x) && std::isfinite(size.y) && std::isfinite(size.z)) || !(size.x > 0.0f)
        || !(size.y > 0.0f) || !(size.z > 0.0f) || !(glm::length(size) < 1e3f))
        return false;
    // The finest cell whose nodes (one more than the cells each way) fit the memory bound.
    maxNodes = std::clamp<std::size_t>(maxNodes, 64, kernel == Kernel::Trilinear ? kMaxNodes : kMaxSmoothedNodes);
    float cell = std::max(kFinestCellMetres, std::cbrt(size.x * size.y * size.z / static_cast<float>(maxNodes)));
    glm::ivec3 dims;
    for (;;) {
        dims = glm::ivec3(glm::ceil(size / cell)) + 2; // and a node beyond each end
        if (static_cast<std::size_t>(dims.x) * dims.y * dims.z <= maxNodes)
            break;
        cell *= 1.02f;
    }
    m_cell = cell;
    m_dims = dims;
    // Centred on the box.
    m_origin = 0.5f * (lo + hi) - 0.5f * cell * glm::vec3(dims - 1);
    const std::size_t count = static_cast<std::size_t>(dims.x) * dims.y * dims.z;
    m_nodes.assign(count, Node{});
    m_hairDensity.assign(count, 0.0f);
    m_solid.assign(count, 0.0f);
    m_accumulators.assign(count * static_cast<std::size_t>(m_slots), Accumulator{});
    if (kernel == Kernel::NearestSmoothed) {
        m_sums.assign(count, Sums{});
    }
    m_bricks = (dims + kBrick - 1) / kBrick;
    const std::size_t bricks = static_cast<std::size_t>(m_bricks.x) * m_bricks.y * m_bricks.z;
    m_live.assign(bricks, 0);
    m_touched.assign(bricks * static_cast<std::size_t>(m_slots), 0);
    return true;
}

void HairVolumeGrid::setWeightBound(double totalWeight)
{
    // The largest powers of two that keep every sum below 2^61 (all the hair in one node, moving at
    // kMaxMoveMetres): exact scales, and headroom for each splat's rounding.
    auto units = [](double bound) {
        const int exponent = std::isfinite(bound) && bound > 0.0 ? std::ilogb(bound) + 1 : 0;
        return std::ldexp(1.0f, std::clamp(61 - exponent, -60, 100));
    };
    m_weightUnits = units(totalWeight);
    m_moveUnits = units(totalWeight * kMaxMoveMetres);
}

int HairVolumeGrid::claimSlot()
{
    const std::uint32_t all = (1u << m_slots) - 1u;
    for (;;) {
        const std::uint32_t held = m_claimed.load(std::memory_order_relaxed);
        if ((held & all) == all) {
            std::this_thread::yield(); // more threads than slots: wait for one
            continue;
        }
        const int slot = std::countr_one(held);
        if (!(m_claimed.fetch_or(1u << slot, std::memory_order_acquire) & (1u << slot)))
            return slot;
    }
}

void HairVolumeGrid::releaseSlot(int slot)
{
    m_claimed.fetch_and(~(1u << slot), std::memory_order_release);
}

std::size_t HairVolumeGrid::memoryBytes() const
{
    return m_nodes.capacity() * sizeof(Node) + (m_hairDensity.capacity() + m_solid.capacity()) * sizeof(float)
        + m_accumulators.capacity() * sizeof(Accumulator) + m_touched.capacity() + m_live.capacity()
        + m_liveList.capacity() * sizeof(std::uint32_t) + m_sums.capacity() * sizeof(Sums);
}

void HairVolumeGrid::setSolid(const std::function<float(const glm::vec3&)>& signedDistance)
{
    for (int k = 0; k < m_dims.z; ++k)
        for (int j = 0; j < m_dims.y; ++j)
            for (int i = 0; i < m_dims.x; ++i) {
                const float d = signedDistance(m_origin + m_cell * glm::vec3(i, j, k));
                m_solid[index(i, j, k)] = std::clamp(0.5f - d / m_cell, 0.0f, 1.0f);
            }
}

template <typename Fn> void HairVolumeGrid::forRowsOf(std::size_t brick, Fn&& fn) const
{
    const int bx = static_cast<int>(brick % static_cast<std::size_t>(m_bricks.x));
    const int by
        = static_cast<int>((brick / static_cast<std::size_t>(m_bricks.x)) % static_cast<std::size_t>(m_bricks.y));
    const int bz = static_cast<int>(brick / brickLayerSize());
    const int i0 = bx * kBrick, nodes = std::min(kBrick, m_dims.x - i0);
    for (int k = bz * kBrick; k < std::min((bz + 1) * kBrick, m_dims.z); ++k)
        for (int j = by * kBrick; j < std::min((by + 1) * kBrick, m_dims.y); ++j)
            fn(i0, j, k, index(i0, j, k), nodes);
}

template <typename Fn> void HairVolumeGrid::forNodesOf(std::size_t brick, Fn&& fn) const
{
    forRowsOf(brick, [&](int i0, int j, int k, std::size_t n0, int nodes) {
        for (int i = 0; i < nodes; ++i)
            fn(i0 + i, j, k, n0 + static_cast<std::size_t>(i));
    });
}

void HairVolumeGrid::clear(ThreadPool* pool)
{
    const std::size_t count = m_nodes.size(), bricks = m_live.size();
    forRange(pool, static_cast<std::size_t>(m_slots), 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t slot = begin; slot < end; ++slot) {
            Accumulator* a = m_accumulators.data() + slot * count;
            std::uint8_t* touched = m_touched.data() + slot * bricks;
            for (std::size_t b = 0; b < bricks; ++b)
                if (touched[b]) {
                    forNodesOf(b, [&](int, int, int, std::size_t n) { a[n] = Accumulator{}; });
                    touched[b] = 0;
                }
        }
    });
}

void HairVolumeGrid::finish(ThreadPool* pool, float solidDensity)
{
    HWY_DYNAMIC_DISPATCH(finishOnTarget)(*this, pool, solidDensity);
}

void HairVolumeGrid::splatRow(int slot, const float* x, const float* y, const float* z, const float* weight,
    const float* moveX, const float* moveY, const float* moveZ, int count, int stride)
{
    HWY_DYNAMIC_DISPATCH(splatRowOnTarget)(*this, slot, x, y, z, weight, moveX, moveY, moveZ, count, stride);
}

void HairVolumeGrid::sampleRow(
    const float* x, const float* y, const float* z, SampleRow& out, int count, int stride) const
{
    HWY_DYNAMIC_DISPATCH(sampleRowOnTarget)(*this, x, y, z, out, count, stride);
}

double HairVolumeGrid::totalWeight() const
{
    double sum = 0.0;
    for (const Node& n : m_nodes)
        sum += n.weight;
    return sum;
}

} // namespace wisp

#endif // HWY_ONCE
