// A dense groom's row of 16 lanes on the hair volume grid (HairVolumeGrid::Kernel::NearestSmoothed),
// in registers: its splat and its read. The solver's per-substep read and its splat
// (SolverVolume.cpp) call them inline, with no trip through the grid's row arrays (CellRow,
// SampleRow) and no second dispatch; the grid's own splatRow and sampleRow (HairVolumeGrid.cpp) call
// the same functions: the same bits either way.
// Compiled once per SIMD target, as sim/solver/SolverLanes-inl.h.

#if defined(WISP_HAIR_VOLUME_GRID_NEAREST_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WISP_HAIR_VOLUME_GRID_NEAREST_INL_H_
#undef WISP_HAIR_VOLUME_GRID_NEAREST_INL_H_
#else
#define WISP_HAIR_VOLUME_GRID_NEAREST_INL_H_
#endif

#include "sim/solver/HairVolumeGrid.h"
#include "sim/solver/SolverLanes-inl.h"
#include "sim/util/ShuffleLanes-inl.h"

#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

HWY_BEFORE_NAMESPACE();
namespace wisp {
namespace HWY_NAMESPACE {

struct GridNearestTarget { }; // this target's HairVolumeGridKernels for a dense groom's rows

// For a row sampled every `Stride` lanes (a power of two) and at its last lane: per lane the
// sampled lanes before and after it (compile-time tables: constant shuffles on every target) and its
// share of the way from one to the other.
template <int Stride> constexpr std::array<int, kLanes> sampleBefore()
{
    std::array<int, kLanes> lanes{};
    for (int l = 0; l < kLanes; ++l)
        lanes[l] = l - l % Stride;
    return lanes;
}
template <int Stride> constexpr std::array<int, kLanes> sampleAfter()
{
    std::array<int, kLanes> lanes{};
    for (int l = 0; l < kLanes; ++l)
        lanes[l] = std::min(l - l % Stride + Stride, kLanes - 1);
    return lanes;
}
template <int Stride> struct LaneBlend {
    static constexpr std::array<int, kLanes> before = sampleBefore<Stride>(), after = sampleAfter<Stride>();
    static constexpr std::array<float, kLanes> share = [] {
        std::array<float, kLanes> s{};
        for (int l = 0; l < kLanes; ++l)
            s[l] = after[l] > before[l] ? static_cast<float>(l - before[l]) / static_cast<float>(after[l] - before[l])
                                        : 0.0f;
        return s;
    }();
    static void apply(Lane* values, int count)
    {
        Lane shares;
        std::memcpy(&shares, share.data(), sizeof shares);
        for (int i = 0; i < count; ++i) {
            const Lane from = shuffleLanesBy<before>(values[i]), to = shuffleLanesBy<after>(values[i]);
            values[i] = from + (to - from) * shares;
        }
    }
};

} // namespace HWY_NAMESPACE

static_assert(HairVolumeGrid::kRowLanes == kLanes, "a grid row is a solver lane");

template <> struct HairVolumeGridKernels<HWY_NAMESPACE::GridNearestTarget> {
    using G = HairVolumeGrid;
    using Float8 = float __attribute__((vector_size(8 * sizeof(float))));
    template <class L> using MaskOf = HWY_NAMESPACE::lanes::MaskOf<L>;

    // Each lane's grid coordinates: the cell's low node along each axis and the position in the
    // cell (0..1), for lanes inside the grid (`inside`); for the others, outside or not finite, the
    // node 0 and a position that means nothing. For a whole row (Lane) or one register's width of
    // it (kernel::Lane): the same arithmetic lane by lane.
    // `x`, `y`, `z` head space. (HairVolumeGrid::cellsOf takes its CellRow from these too.)
    template <class L> struct CoordinatesOf {
        using M = MaskOf<L>;
        M inside, ix, iy, iz;
        L fx, fy, fz;
    };
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes" // (Lane's alignment: its size's anyway)
    using Coordinates = CoordinatesOf<Lane>;
#pragma GCC diagnostic pop
    template <class L> static CoordinatesOf<L> coordinatesOf(const G& g, L x, L y, L z)
    {
        using M = MaskOf<L>;
        const float inverseCell = 1.0f / g.m_cell;
        const L gx = (x - g.m_origin.x) * inverseCell, gy = (y - g.m_origin.y) * inverseCell,
                gz = (z - g.m_origin.z) * inverseCell;
        CoordinatesOf<L> c;
        c.inside = (gx >= 0.0f) & (gy >= 0.0f) & (gz >= 0.0f) & (gx < static_cast<float>(g.m_dims.x - 1))
            & (gy < static_cast<float>(g.m_dims.y - 1)) & (gz < static_cast<float>(g.m_dims.z - 1));
        const L zero{};
        c.ix = __builtin_convertvector(c.inside ? gx : zero, M);
        c.iy = __builtin_convertvector(c.inside ? gy : zero, M);
        c.iz = __builtin_convertvector(c.inside ? gz : zero, M);
        c.fx = gx - __builtin_convertvector(c.ix, L);
        c.fy = gy - __builtin_convertvector(c.iy, L);
        c.fz = gz - __builtin_convertvector(c.iz, L);
        return c;
    }

    // The node each lane meets (Kernel::NearestSmoothed): the index of its nearest node, -1 outside
    // the grid or not finite; and when `brick` is given, the index of that node's brick there.
    template <class L> static MaskOf<L> nearestNodes(const G& g, const CoordinatesOf<L>& c, MaskOf<L>* brick = nullptr)
    {
        using M = MaskOf<L>;
        const M one = M{} + 1;
        const M nx = c.ix + ((c.fx >= 0.5f) & one), ny = c.iy + ((c.fy >= 0.5f) & one),
                nz = c.iz + ((c.fz >= 0.5f) & one);
        static_assert(G::kBrick == 4, "a node's brick is its coordinates shifted by two");
        if (brick)
            *brick = (nx >> 2) + g.m_bricks.x * ((ny >> 2) + g.m_bricks.y * (nz >> 2));
        return c.inside ? nx + g.m_dims.x * (ny + g.m_dims.y * nz) : M{} - 1;
    }

    // A row's nearest nodes and their bricks, lane by lane (nearestNodes), as the splat and the read
    // take them: the lanes' own work is done a register's width at a time (on AVX2 a 16-lane value
    // is two registers, and the row's arithmetic spilled), the nodes' work lane by lane.
    struct NearestRow {
        alignas(64) std::int32_t node[kLanes];
        alignas(64) std::int32_t brick[kLanes];
    };
    // Lanes `first` .. first + width - 1 of `row` from one register's width of head-space positions.
    template <class L> static void nearestInto(const G& g, L x, L y, L z, NearestRow& row, int first)
    {
        MaskOf<L> brick;
        const MaskOf<L> node = nearestNodes(g, coordinatesOf(g, x, y, z), &brick);
        std::memcpy(row.node + first, &node, sizeof node);
        std::memcpy(row.brick + first, &brick, sizeof brick);
    }

    // Adds a row's lanes 0, stride, 2 stride, ... (weight > 0, inside the grid) at their nearest
    // nodes into slot `slot`, marking the slot's bricks they touch: each lane its weight and its
    // weight x move (each component clamped to kMaxMoveMetres), in fixed point. Side-by-side
    // particles (a row's neighbouring strands) often share a node: a run of them is summed in
    // registers and written once, in lane order (the same bits every time).
    static void splatNearestRow(G& g, int slot, Lane x, Lane y, Lane z, const Lane& weight, const Lane& moveX,
        const Lane& moveY, const Lane& moveZ, int stride)
    {
        NearestRow nearest;
        nearestInto(g, x, y, z, nearest, 0);
        alignas(64) float lanes[4][kLanes];
        std::memcpy(lanes[0], &weight, sizeof weight);
        std::memcpy(lanes[1], &moveX, sizeof moveX);
        std::memcpy(lanes[2], &moveY, sizeof moveY);
        std::memcpy(lanes[3], &moveZ, sizeof moveZ);
        splatNearest(g, slot, nearest, lanes[0], lanes[1], lanes[2], lanes[3], stride);
    }
    // The same from the row's nodes (nearestInto) and its lanes' weights and moves.
    static void splatNearest(G& g, int slot, const NearestRow& nearest, const float* weight, const float* moveX,
        const float* moveY, const float* moveZ, int stride)
    {
        using Float4 = float __attribute__((vector_size(4 * sizeof(float))));
        using Fixed4 = std::int64_t __attribute__((vector_size(4 * sizeof(std::int64_t))));
        stride = std::clamp(stride, 1, kLanes);
        std::int64_t* const grid = &g.m_accumulators[static_cast<std::size_t>(slot) * g.m_nodes.size()].weight;
        std::uint8_t* const touched = g.m_touched.data() + static_cast<std::size_t>(slot) * g.m_live.size();
        const Float4 units{ g.m_weightUnits, g.m_moveUnits, g.m_moveUnits, g.m_moveUnits };
        int runNode = -1;
        Float4 run{};
        auto flush = [&] {
            if (runNode < 0)
                return;
            const Float4 value = run * units; // rounded half away from zero: no drift toward zero
            Fixed4 sum;
            std::int64_t* const at = grid + 4 * static_cast<std::ptrdiff_t>(runNode);
            std::memcpy(&sum, at, sizeof sum);
            sum += HWY_NAMESPACE::lanes::roundToInt64(value);
            std::memcpy(at, &sum, sizeof sum);
        };
        constexpr float kMax = G::kMaxMoveMetres;
        for (int l = 0; l < kLanes; l += stride) {
            const float w = weight[l];
            const int node = nearest.node[l];
            if (node < 0 || !(w > 0.0f))
                continue;
            if (node != runNode) {
                flush();
                runNode = node;
                run = Float4{};
                touched[nearest.brick[l]] = 1;
            }
            run += w
                * Float4{ 1.0f, std::clamp(moveX[l], -kMax, kMax), std::clamp(moveY[l], -kMax, kMax),
                      std::clamp(moveZ[l], -kMax, kMax) };
        }
        flush();
    }

    // Sixteen nodes' eight floats each (Node's order), transposed so that out[f] holds value f of
    // nodes 0..15, in three rounds of two-register shuffles, in place of eight scalar stores a node.
    static void transposeNodes(const float* const rows[kLanes], Lane out[8])
    {
        // v[k]: nodes k and k + 8. Each round swaps a bit of the register's number with a bit of the
        // position in it (the node's with the value's), until register f holds value f in order.
        Lane* const v = out;
        for (int k = 0; k < 8; ++k) {
            Float8 low, high;
            std::memcpy(&low, rows[k], sizeof low);
            std::memcpy(&high, rows[k + 8], sizeof high);
            v[k] = __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        }
        for (int k = 0; k < 4; ++k) {
            const Lane a = v[k], b = v[k + 4];
            v[k] = __builtin_shufflevector(a, b, 0, 1, 2, 3, 16, 17, 18, 19, 8, 9, 10, 11, 24, 25, 26, 27);
            v[k + 4] = __builtin_shufflevector(a, b, 4, 5, 6, 7, 20, 21, 22, 23, 12, 13, 14, 15, 28, 29, 30, 31);
        }
        for (int k : { 0, 1, 4, 5 }) {
            const Lane a = v[k], b = v[k + 2];
            v[k] = __builtin_shufflevector(a, b, 0, 1, 16, 17, 4, 5, 20, 21, 8, 9, 24, 25, 12, 13, 28, 29);
            v[k + 2] = __builtin_shufflevector(a, b, 2, 3, 18, 19, 6, 7, 22, 23, 10, 11, 26, 27, 14, 15, 30, 31);
        }
        for (int k : { 0, 2, 4, 6 }) {
            const Lane a = v[k], b = v[k + 1];
            v[k] = __builtin_shufflevector(a, b, 0, 16, 2, 18, 4, 20, 6, 22, 8, 24, 10, 26, 12, 28, 14, 30);
            v[k + 1] = __builtin_shufflevector(a, b, 1, 17, 3, 19, 5, 21, 7, 23, 9, 25, 11, 27, 13, 29, 15, 31);
        }
    }

    // The nodes at `nearest` read at lanes 0, stride, 2 stride, ... and 15 (a lane between, or
    // outside the grid, reads a node of zeros), transposed into out[8] (Node's order: density,
    // gradient x y z, momentum x y z, hair).
    static void readSampled(const G& g, const std::int32_t* nearest, int stride, Lane out[8])
    {
        const float* rows[kLanes];
        sampledRows(g, nearest, stride, rows);
        transposeNodes(rows, out);
    }
    // Where lanes 0, stride, 2 stride, ... and 15 read their node's eight floats (the others, and
    // lanes outside the grid, a node of zeros).
    static void sampledRows(const G& g, const std::int32_t* nearest, int stride, const float* rows[kLanes])
    {
        static const G::Node kEmpty{};
        const int between = stride - 1; // stride is a power of two: no division a lane
        for (int l = 0; l < kLanes; ++l)
            rows[l] = ((l & between) == 0 || l == kLanes - 1) && nearest[l] >= 0
                ? &g.m_nodes[static_cast<std::size_t>(nearest[l])].density
                : &kEmpty.density;
    }

    // The lanes between two samples (stride > 1, a power of two): the linear blend of the two around them.
    static void blendBetweenSamples(int stride, Lane* values, int count)
    {
        // (A switch, not a generic lambda: with the values captured by reference GCC kept the
        // eight fields on the stack, 40 more stores a read.)
        switch (stride) {
        case 2:
            HWY_NAMESPACE::LaneBlend<2>::apply(values, count);
            break;
        case 4:
            HWY_NAMESPACE::LaneBlend<4>::apply(values, count);
            break;
        case 8:
            HWY_NAMESPACE::LaneBlend<8>::apply(values, count);
            break;
        case 16:
            HWY_NAMESPACE::LaneBlend<16>::apply(values, count);
            break;
        default:
            break;
        }
    }

    // Eight nodes' eight floats (one AVX register each) transposed: out[f] holds value f of the
    // eight (the classic unpack, shuffle and 128-bit permute rounds, all within two registers).
    // Also the trilinear grid's full-row read (HairVolumeGrid.cpp, sampleRow).
    static void transpose8(const Float8 in[8], Float8 out[8])
    {
        Float8 t[8], u[8];
        for (int k = 0; k < 4; ++k) {
            t[2 * k] = __builtin_shufflevector(in[2 * k], in[2 * k + 1], 0, 8, 1, 9, 4, 12, 5, 13);
            t[2 * k + 1] = __builtin_shufflevector(in[2 * k], in[2 * k + 1], 2, 10, 3, 11, 6, 14, 7, 15);
        }
        for (int k : { 0, 1, 4, 5 }) { // t[k] with t[k + 2]
            const int o = k < 4 ? 2 * k : 2 * (k - 4) + 4;
            u[o] = __builtin_shufflevector(t[k], t[k + 2], 0, 1, 8, 9, 4, 5, 12, 13);
            u[o + 1] = __builtin_shufflevector(t[k], t[k + 2], 2, 3, 10, 11, 6, 7, 14, 15);
        }
        for (int f = 0; f < 4; ++f) {
            out[f] = __builtin_shufflevector(u[f], u[f + 4], 0, 1, 2, 3, 8, 9, 10, 11);
            out[f + 4] = __builtin_shufflevector(u[f], u[f + 4], 4, 5, 6, 7, 12, 13, 14, 15);
        }
    }

#if !WISP_LANES_AVX512
    // Each lane's eight floats blended between the samples around it (LaneBlend<Stride>): the same
    // arithmetic as blending the transposed fields, a node's eight floats in one register.
    template <int Stride> static void blendRows(const float* const rows[kLanes], Float8 out[kLanes])
    {
        using B = HWY_NAMESPACE::LaneBlend<Stride>;
        for (int l = 0; l < kLanes; ++l) {
            Float8 from, to;
            std::memcpy(&from, rows[B::before[l]], sizeof from);
            std::memcpy(&to, rows[B::after[l]], sizeof to);
            out[l] = from + (to - from) * B::share[l];
        }
    }
#endif

    // A full row's read, what HairVolumeGrid::sampleRow gives for it, into out[8] (Node's order).
    static void readNearestRow(const G& g, Lane x, Lane y, Lane z, int stride, Lane out[8])
    {
        NearestRow nearest;
        nearestInto(g, x, y, z, nearest, 0);
        readNearest(g, nearest, stride, out);
    }
    // The same from the row's nodes (nearestInto).
    static void readNearest(const G& g, const NearestRow& nearest, int stride, Lane out[8])
    {
        stride = static_cast<int>(std::bit_floor(static_cast<unsigned>(std::clamp(stride, 1, kLanes))));
#if WISP_LANES_AVX512
        // Sixteen nodes in a 16 x 8 transpose of 512-bit registers, then the blend: a permute a field.
        readSampled(g, nearest.node, stride, out);
        if (stride > 1)
            blendBetweenSamples(stride, out, 8);
#else
        // Two registers a lane: the blend first, a node's eight floats at a time, then two 8 x 8
        // transposes (16-lane shuffles across two registers go through memory on AVX2).
        const float* rows[kLanes];
        sampledRows(g, nearest.node, stride, rows);
        Float8 blended[kLanes];
        switch (stride) {
        case 2:
            blendRows<2>(rows, blended);
            break;
        case 4:
            blendRows<4>(rows, blended);
            break;
        case 8:
            blendRows<8>(rows, blended);
            break;
        case 16:
            blendRows<16>(rows, blended);
            break;
        default:
            for (int l = 0; l < kLanes; ++l)
                std::memcpy(&blended[l], rows[l], sizeof blended[l]);
            break;
        }
        Float8 low[8], high[8];
        transpose8(blended, low);
        transpose8(blended + 8, high);
        for (int f = 0; f < 8; ++f)
            out[f] = __builtin_shufflevector(low[f], high[f], 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
#endif
    }
};

} // namespace wisp
HWY_AFTER_NAMESPACE();

#endif // per-target include guard
