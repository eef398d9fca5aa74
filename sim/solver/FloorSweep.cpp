#include "sim/solver/FloorSweep.h"

#include <algorithm>
#include <cstring>

// The sweep is compiled once per SIMD target, as the solver's kernel (SolverBlockKernel.cpp), so the
// floor is measured on the target the solver runs on.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sim/solver/FloorSweep.cpp"
#include <hwy/foreach_target.h> // (before highway.h)

#include "sim/solver/SolverLanes-inl.h"

#include <hwy/highway.h>

#ifndef WISP_FLOOR_SWEEP_CONSTANTS_
#define WISP_FLOOR_SWEEP_CONSTANTS_
namespace wisp::floor_sweep {
constexpr std::size_t kFields = 6; // x, y, z, px, py, pz
constexpr float kStepSeconds = 1.0f / 60.0f;
constexpr float kKeep = 0.99f; // velocity kept per step: a little damping, so a push dies out
} // namespace wisp::floor_sweep
#endif

HWY_BEFORE_NAMESPACE();
namespace wisp::HWY_NAMESPACE {

using namespace floor_sweep;

// Blocks [begin, end) of one step, on this SIMD target. A block's 16 lanes are taken a register's
// width at a time (kernel::Lane, as the solver's kernel takes them), the slices of one particle side
// by side: their chains are independent, so a target with fewer lanes a register still has 16
// strands' worth of work in flight. (Written on the 16-lane Lane, two registers on AVX2 and four on
// SSE4, GCC moved every value through the stack: on a Zen 4, whose 512-bit operations are two
// 256-bit ones, the floor of 1M particles ran 1.9 ms a step at AVX2 and 1.7 at SSE4 where AVX-512's
// ran 0.64; now 0.85 and 1.14. The floor is what the machine allows: slower, it flattered every
// ratio measured against it.)
void sweepBlocks(float* rows, std::size_t begin, std::size_t end, std::uint32_t points, float segmentMetres)
{
    using namespace kernel;
    constexpr int kSlices = kLanes / kVecLanes;
    const std::size_t pointFloats = kFields * kLanes;
    const std::size_t blockFloats = points * pointFloats;
    const Lane gravityStep = splat(-9.81f * kStepSeconds * kStepSeconds);
    const Lane keep = splat(kKeep), length = splat(segmentMetres);
    auto load = [](const float* p) {
        Lane v;
        std::memcpy(&v, p, sizeof v);
        return v;
    };
    auto store = [](float* p, Lane v) { std::memcpy(p, &v, sizeof v); };
    for (std::size_t b = begin; b < end; ++b) {
        float* block = rows + b * blockFloats;
        V3 parent[kSlices]; // each slice's; the roots stay
        for (int s = 0; s < kSlices; ++s) {
            const float* root = block + s * kVecLanes;
            parent[s] = V3{ load(root), load(root + kLanes), load(root + 2 * kLanes) };
        }
        for (std::uint32_t j = 1; j < points; ++j) {
            for (int s = 0; s < kSlices; ++s) {
                float* row = block + j * pointFloats + s * kVecLanes;
                const V3 x{ load(row), load(row + kLanes), load(row + 2 * kLanes) };
                const V3 previous{ load(row + 3 * kLanes), load(row + 4 * kLanes), load(row + 5 * kLanes) };
                // Verlet: x' = x + keep (x - x_prev) + g dt².
                V3 moved = x + (x - previous) * keep;
                moved.y = moved.y + gravityStep;
                // Follow the leader: back onto the segment's length from the parent's new position.
                const V3 d = moved - parent[s];
                const V3 placed = parent[s] + d * (length * lrsqrt(lmax(dot(d, d), splat(1e-20f))));
                store(row, placed.x);
                store(row + kLanes, placed.y);
                store(row + 2 * kLanes, placed.z);
                store(row + 3 * kLanes, x.x);
                store(row + 4 * kLanes, x.y);
                store(row + 5 * kLanes, x.z);
                parent[s] = placed;
            }
        }
    }
}

} // namespace wisp::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

namespace wisp {

HWY_EXPORT(sweepBlocks);

using namespace floor_sweep;

FloorSweep::FloorSweep(std::size_t particles, std::uint32_t pointsPerStrand, int threadCount)
    : FloorSweep(particles, pointsPerStrand, std::make_unique<ThreadPool>(threadCount), nullptr)
{
}

FloorSweep::FloorSweep(std::size_t particles, std::uint32_t pointsPerStrand, ThreadPool& pool)
    : FloorSweep(particles, pointsPerStrand, nullptr, &pool)
{
}

FloorSweep::FloorSweep(
    std::size_t particles, std::uint32_t pointsPerStrand, std::unique_ptr<ThreadPool> ownPool, ThreadPool* pool)
    : m_ownPool(std::move(ownPool))
    , m_pool(pool ? pool : m_ownPool.get())
    , m_points(std::max<std::uint32_t>(pointsPerStrand, 2))
{
    m_strands = std::max<std::size_t>(1, (particles + m_points - 1) / m_points);
    m_blocks = (m_strands + kLanes - 1) / kLanes;
    m_particles = m_strands * m_points;
    m_segmentMetres = 0.3f / static_cast<float>(m_points - 1);
    m_rows.assign(m_blocks * m_points * kFields * kLanes, 0.0f);
    for (std::size_t b = 0; b < m_blocks; ++b)
        for (std::uint32_t j = 0; j < m_points; ++j)
            for (std::size_t l = 0; l < static_cast<std::size_t>(kLanes); ++l) {
                float* row = m_rows.data() + (b * m_points + j) * kFields * kLanes + l;
                const float x = 0.01f * static_cast<float>(b * kLanes + l);
                const float y = -m_segmentMetres * static_cast<float>(j);
                row[0 * kLanes] = row[3 * kLanes] = x;
                row[1 * kLanes] = row[4 * kLanes] = y;
            }
}

void FloorSweep::step()
{
    // A few blocks a chunk, as the solver splits its step; on the SIMD target the solver runs on.
    m_pool->parallelFor(m_blocks, 4, [&](std::size_t begin, std::size_t end) {
        HWY_DYNAMIC_DISPATCH(sweepBlocks)(m_rows.data(), begin, end, m_points, m_segmentMetres);
    });
}

void FloorSweep::displace(float dxMetres, float dzMetres)
{
    for (std::size_t b = 0; b < m_blocks; ++b)
        for (std::uint32_t j = 1; j < m_points; ++j)
            for (std::size_t l = 0; l < static_cast<std::size_t>(kLanes); ++l) {
                float* row = m_rows.data() + (b * m_points + j) * kFields * kLanes + l;
                const float share = static_cast<float>(j) / static_cast<float>(m_points - 1);
                row[0] += dxMetres * share;
                row[3 * kLanes] += dxMetres * share;
                row[2 * kLanes] += dzMetres * share;
                row[5 * kLanes] += dzMetres * share;
            }
}

float FloorSweep::at(std::size_t strand, std::uint32_t point, int field) const
{
    const std::size_t b = strand / kLanes, l = strand % kLanes;
    return m_rows[((b * m_points + point) * kFields + static_cast<std::size_t>(field)) * kLanes + l];
}

} // namespace wisp

#endif // HWY_ONCE
