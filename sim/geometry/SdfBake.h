#pragma once
// The passes of SignedDistanceField::bake, over a sample grid, each split into slabs of planes
// handed to a ThreadPool's threads. Used by SignedDistanceField.cpp; not part of sim/'s API.
//
// How the bake works, and why.
//
// 1. Exact narrow band. Every triangle visits the samples inside its box grown by B = kBandCells
//    cells and keeps the minimum exact point-triangle distance per sample (a register of samples
//    at a time on the SIMD target: SdfBandRow.h). A sample whose true
//    distance is <= B lies in the grown box of its nearest triangle, so every sample that ends
//    up <= B holds its exact distance (to float precision). Cost is proportional to the surface
//    area in cells, not to the volume, which is what makes a 20k-triangle head take milliseconds
//    where a closest-point query per sample would take seconds.
//
// 2. Sign: the generalized winding number (Jacobson et al. 2013) is the average over all
//    directions of the signed number of surface crossings along a ray from the sample. We take
//    that average over the six axis directions, counting crossings along the grid's own lines
//    (each triangle is rasterised onto the rows its projection covers, with Bridson's robust
//    point-in-triangle test so a row through a shared edge or vertex is counted exactly once).
//    A sample is inside when |sum of the six counts| > 3, i.e. winding number > 1/2.
//    Why this over the alternatives:
//    - for a closed mesh every single direction already gives the exact integer winding number,
//      so the sign is exact, including overlapping shells (eyeballs inside a head count 2, not
//      "outside" as ray parity would say);
//    - for open meshes (a neck, eye holes) a point inside sees the hole in only one or two of the
//      six directions and is still voted inside; points outside are not fooled by a hole unless
//      they look through it along three axes at once;
//    - it costs O(samples + crossings), far cheaper than a hierarchical winding number per sample,
//      and unlike pseudo-normal signs it needs no closest triangle far from the surface;
//    - |w| rather than w accepts a mesh whose triangles all face inward.
//    Weakness: a mesh with inconsistently oriented triangles can cancel crossings; such meshes
//    should be repaired on import.
//
// 3. Far field: beyond the band, the value is max(B, e + B - sqrt(3) h), where e is the exact
//    Euclidean distance to the nearest band sample (Felzenszwalb–Huttenlocher distance transform,
//    separable, O(samples)). That is a lower bound on the true distance: along the segment from a
//    far sample to its nearest surface point there is a point at distance B - sqrt(3)/2 h from the
//    surface, and the sample nearest to it is at most sqrt(3)/2 h away, so it is a band sample no
//    farther than d - B + sqrt(3) h. The true distance is also at most e + B, so the far field is
//    within sqrt(3) cells of exact, monotone, and never claims the surface is farther than it is.
//
// Every pass is split into slabs of planes handed to the threads of a ThreadPool (HairSimulation
// passes its solver's, so one pool serves the bake and the steps); each sample is written by exactly
// one slab per pass and combines its inputs with min or integer sums, so the result does not
// depend on the number of threads or on scheduling.

#include "sim/util/ThreadPool.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace wisp::sdf_detail {

inline constexpr float kFarMarker = 1.0e30f; // "no band sample on this row yet" in the distance transform

// Calls fn(i) once for every i in [0, count), on the pool's threads (the caller's included; on the
// caller alone when `pool` is null), one index at a time as a thread frees (ThreadPool's dynamic
// chunks, grain 1: slabs differ in cost). Returns false when fn ran out of memory somewhere; the
// exception never reaches the pool's threads (sim/ never throws across its API), and the other
// indices are skipped once one failed.
template <class Fn> bool parallelFor(ThreadPool* pool, int count, Fn&& fn)
{
    if (count <= 0)
        return true;
    std::atomic<bool> failed{ false };
    const std::function<void(std::size_t, std::size_t)> body = [&](std::size_t begin, std::size_t end) noexcept {
        try {
            for (std::size_t i = begin; i < end && !failed.load(std::memory_order_relaxed); ++i)
                fn(static_cast<int>(i));
        } catch (...) { // only std::bad_alloc from per-slab buffers can get here
            failed = true;
        }
    };
    forRange(pool, static_cast<std::size_t>(count), 1, body);
    return !failed;
}

struct BakeTriangle {
    glm::vec3 a, b, c;
    glm::vec3 unitNormal; // zero for zero-area triangles
    glm::vec3 lo, hi;
};

struct Grid {
    glm::ivec3 dims{ 0 };
    glm::vec3 origin{ 0.0f };
    float h = 0.0f;

    std::size_t index(int i, int j, int k) const
    {
        return static_cast<std::size_t>(i)
            + static_cast<std::size_t>(dims.x)
            * (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(k));
    }
    std::size_t index(const glm::ivec3& c) const { return index(c.x, c.y, c.z); }
    std::size_t size() const
    {
        return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
    }
    glm::vec3 position(int i, int j, int k) const
    {
        return origin + glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * h;
    }
    // First and last sample index along `axis` whose coordinate lies in [lo, hi], give or take a
    // thousandth of a cell so float rounding never loses one (callers test each sample exactly).
    // Empty (first > last) when outside the grid.
    void range(int axis, float lo, float hi, int& first, int& last) const
    {
        const double a = std::ceil((static_cast<double>(lo) - origin[axis]) / h - 1e-3);
        const double b = std::floor((static_cast<double>(hi) - origin[axis]) / h + 1e-3);
        first = static_cast<int>(std::clamp(a, 0.0, static_cast<double>(dims[axis])));
        last = static_cast<int>(std::clamp(b, -1.0, static_cast<double>(dims[axis] - 1)));
    }
};

// Pass 1: exact squared distances within the band (kFarMarker elsewhere).
bool bakeBand(ThreadPool* pool, const std::vector<BakeTriangle>& triangles, const Grid& grid, float band,
    std::vector<float>& dist2);

bool voteAlongAxis(ThreadPool* pool, const std::vector<BakeTriangle>& triangles, const Grid& grid, int axis,
    std::vector<std::int16_t>& votes);

bool distanceTransform(ThreadPool* pool, const Grid& grid, std::vector<float>& field);

} // namespace wisp::sdf_detail
