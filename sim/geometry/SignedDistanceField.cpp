#include "sim/geometry/SignedDistanceField.h"

#include "sim/geometry/MeshBvh.h" // closestPointOnTriangle
#include "sim/util/ThreadName.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <new>
#include <thread>

// How the bake works, and why.
//
// 1. Exact narrow band. Every triangle visits the samples inside its box grown by B = kBandCells
//    cells and keeps the minimum exact point-triangle distance per sample. A sample whose true
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
// Every pass is split into slabs of planes handed to threads; each sample is written by exactly
// one slab per pass and combines its inputs with min or integer sums, so the result does not
// depend on the number of threads or on scheduling.

namespace wisp {

namespace {

constexpr float kSqrt3 = 1.7320508f;
constexpr float kFarMarker = 1.0e30f; // "no band sample on this row yet" in the distance transform
constexpr int kSlabPlanes = 4;

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Calls fn(i) once for every i in [0, count) on `threadCount` threads (the caller's included).
// Returns false when fn ran out of memory somewhere.
template <class Fn> bool parallelFor(int threadCount, int count, Fn&& fn)
{
    if (count <= 0)
        return true;
    const int threads = std::min(threadCount, count);
    std::atomic<int> next{ 0 };
    std::atomic<bool> failed{ false };
    auto worker = [&]() noexcept {
        try {
            for (int i = next.fetch_add(1); i < count && !failed.load(std::memory_order_relaxed); i = next.fetch_add(1))
                fn(i);
        } catch (...) { // only std::bad_alloc from per-slab buffers can get here
            failed = true;
        }
    };
    std::vector<std::thread> pool;
    try {
        pool.reserve(static_cast<std::size_t>(threads - 1));
        for (int t = 1; t < threads; ++t)
            pool.emplace_back([&worker] {
                nameThisThread("wisp-sdf");
                worker();
            });
    } catch (...) {
        // No more threads to be had: the ones running (and this one) finish the work.
    }
    worker();
    for (std::thread& t : pool)
        t.join();
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

// Triangles bucketed by slabs of kSlabPlanes planes along one axis (compressed rows: slab s owns
// items[offsets[s] .. offsets[s+1])), in triangle order, so a slab's worker sees only its triangles.
struct SlabBins {
    std::vector<std::uint32_t> offsets;
    std::vector<std::uint32_t> items;
};

SlabBins binBySlab(const std::vector<BakeTriangle>& triangles, const Grid& grid, int axis, float grow)
{
    const int planes = grid.dims[axis];
    const int slabs = (planes + kSlabPlanes - 1) / kSlabPlanes;
    SlabBins bins;
    bins.offsets.assign(static_cast<std::size_t>(slabs) + 1, 0);
    auto slabRange = [&](const BakeTriangle& t, int& s0, int& s1) {
        int first, last;
        grid.range(axis, t.lo[axis] - grow, t.hi[axis] + grow, first, last);
        s0 = first / kSlabPlanes;
        s1 = last < first ? s0 - 1 : last / kSlabPlanes;
    };
    for (const BakeTriangle& t : triangles) {
        int s0, s1;
        slabRange(t, s0, s1);
        for (int s = s0; s <= s1; ++s)
            ++bins.offsets[static_cast<std::size_t>(s) + 1];
    }
    for (int s = 0; s < slabs; ++s)
        bins.offsets[static_cast<std::size_t>(s) + 1] += bins.offsets[static_cast<std::size_t>(s)];
    bins.items.resize(bins.offsets.back());
    std::vector<std::uint32_t> fill(bins.offsets.begin(), bins.offsets.end() - 1);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        int s0, s1;
        slabRange(triangles[i], s0, s1);
        for (int s = s0; s <= s1; ++s)
            bins.items[fill[static_cast<std::size_t>(s)]++] = static_cast<std::uint32_t>(i);
    }
    return bins;
}

// Robust 2D orientation with a simulation-of-simplicity tie-break (Bridson, makelevelset3):
// antisymmetric in its two points, so an edge shared by two triangles (traversed in opposite
// directions) puts a point lying exactly on it inside exactly one of them.
int orientation(double x1, double y1, double x2, double y2, double& twiceSignedArea)
{
    twiceSignedArea = y1 * x2 - x1 * y2;
    if (twiceSignedArea > 0)
        return 1;
    if (twiceSignedArea < 0)
        return -1;
    if (y2 > y1)
        return 1;
    if (y2 < y1)
        return -1;
    if (x1 > x2)
        return 1;
    if (x1 < x2)
        return -1;
    return 0; // only when both points coincide
}

// Is (x0, y0) inside triangle (1, 2, 3)? On success the barycentric weights of corners 1, 2, 3
// and the orientation sign (+1 clockwise in (x, y), -1 counter-clockwise).
bool pointInTriangle2d(double x0, double y0, double x1, double y1, double x2, double y2, double x3, double y3,
    double& a, double& b, double& c, int& sign)
{
    x1 -= x0;
    x2 -= x0;
    x3 -= x0;
    y1 -= y0;
    y2 -= y0;
    y3 -= y0;
    const int signA = orientation(x2, y2, x3, y3, a);
    if (signA == 0)
        return false;
    const int signB = orientation(x3, y3, x1, y1, b);
    if (signB != signA)
        return false;
    const int signC = orientation(x1, y1, x2, y2, c);
    if (signC != signA)
        return false;
    const double sum = a + b + c;
    if (sum == 0.0) // collinear projection: contributes no crossing
        return false;
    a /= sum;
    b /= sum;
    c /= sum;
    sign = signA;
    return true;
}

// Pass 1: exact squared distances within the band (kFarMarker elsewhere).
bool bakeBand(
    int threads, const std::vector<BakeTriangle>& triangles, const Grid& grid, float band, std::vector<float>& dist2)
{
    const SlabBins bins = binBySlab(triangles, grid, 2, band);
    const int slabs = static_cast<int>(bins.offsets.size()) - 1;
    // A hair of slack keeps float rounding from dropping a sample that is exactly `band` away.
    const double reach = static_cast<double>(band) * 1.0001 + 1e-7;
    const double h = grid.h;
    return parallelFor(threads, slabs, [&](int s) {
        const int k0 = s * kSlabPlanes, k1 = std::min(grid.dims.z - 1, k0 + kSlabPlanes - 1);
        for (std::uint32_t n = bins.offsets[static_cast<std::size_t>(s)];
             n < bins.offsets[static_cast<std::size_t>(s) + 1]; ++n) {
            const BakeTriangle& t = triangles[bins.items[n]];
            int i0, i1, j0, j1, kk0, kk1;
            grid.range(0, t.lo.x - band, t.hi.x + band, i0, i1);
            grid.range(1, t.lo.y - band, t.hi.y + band, j0, j1);
            grid.range(2, t.lo.z - band, t.hi.z + band, kk0, kk1);
            kk0 = std::max(kk0, k0);
            kk1 = std::min(kk1, k1);
            // Each row only visits the samples that can be within `band`: inside the sphere of
            // radius R + band around the triangle's box centre (R reaching its corners) and inside
            // the slab of half-width `band` around its plane. For triangles smaller than the band
            // that is about a quarter of the grown box, and the pass is most of the bake.
            const glm::dvec3 centre = 0.5 * (glm::dvec3(t.lo) + glm::dvec3(t.hi));
            const double radius = std::sqrt(std::max({ glm::dot(glm::dvec3(t.a) - centre, glm::dvec3(t.a) - centre),
                                      glm::dot(glm::dvec3(t.b) - centre, glm::dvec3(t.b) - centre),
                                      glm::dot(glm::dvec3(t.c) - centre, glm::dvec3(t.c) - centre) }))
                + reach;
            const glm::dvec3 normal(t.unitNormal);
            for (int k = kk0; k <= kk1; ++k)
                for (int j = j0; j <= j1; ++j) {
                    const glm::dvec3 rowStart(grid.origin.x, grid.origin.y + j * h, grid.origin.z + k * h);
                    const double dy = rowStart.y - centre.y, dz = rowStart.z - centre.z;
                    const double across2 = radius * radius - dy * dy - dz * dz;
                    if (across2 < 0.0)
                        continue;
                    const double across = std::sqrt(across2);
                    double lo = (centre.x - across - grid.origin.x) / h, hi = (centre.x + across - grid.origin.x) / h;
                    // Plane distance along the row: c0 + i * h * normal.x.
                    const double c0 = glm::dot(rowStart - glm::dvec3(t.a), normal);
                    const double slope = h * normal.x;
                    if (std::abs(slope) > 1e-12 * h) {
                        const double p = (-reach - c0) / slope, q = (reach - c0) / slope;
                        lo = std::max(lo, std::min(p, q));
                        hi = std::min(hi, std::max(p, q));
                    } else if (std::abs(c0) > reach) {
                        continue;
                    }
                    const int first = std::max(i0, static_cast<int>(std::clamp(std::ceil(lo - 1e-3), -1.0, 1e9)));
                    const int last = std::min(i1, static_cast<int>(std::clamp(std::floor(hi + 1e-3), -1.0, 1e9)));
                    float* row = &dist2[grid.index(0, j, k)];
                    for (int i = first; i <= last; ++i) {
                        const glm::vec3 p = grid.position(i, j, k);
                        const glm::vec3 d = closestPointOnTriangle(p, t.a, t.b, t.c).point - p;
                        const float d2 = glm::dot(d, d);
                        if (d2 < row[i])
                            row[i] = d2;
                    }
                }
        }
    });
}

// Pass 2, once per ray axis: adds to `votes` the signed crossings along +axis and -axis.
bool voteAlongAxis(int threads, const std::vector<BakeTriangle>& triangles, const Grid& grid, int axis,
    std::vector<std::int16_t>& votes)
{
    // (u, v) = the two other axes in cyclic order, so the 2D orientation of a projected triangle
    // has the sign of its normal's `axis` component.
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int n = grid.dims[axis], nu = grid.dims[u];
    const SlabBins bins = binBySlab(triangles, grid, v, 0.0f);
    const int slabs = static_cast<int>(bins.offsets.size()) - 1;
    const double h = grid.h;
    return parallelFor(threads, slabs, [&](int s) {
        const int v0 = s * kSlabPlanes, v1 = std::min(grid.dims[v] - 1, v0 + kSlabPlanes - 1);
        const std::size_t rowLength = static_cast<std::size_t>(n) + 1;
        // crossings[row][m] = signed crossings whose coordinate lies in (sample m-1, sample m].
        std::vector<std::int32_t> crossings(
            rowLength * static_cast<std::size_t>(nu) * static_cast<std::size_t>(v1 - v0 + 1), 0);
        for (std::uint32_t idx = bins.offsets[static_cast<std::size_t>(s)];
             idx < bins.offsets[static_cast<std::size_t>(s) + 1]; ++idx) {
            const BakeTriangle& t = triangles[bins.items[idx]];
            if (t.unitNormal == glm::vec3(0.0f))
                continue; // zero area: no solid angle, no crossing
            int ju0, ju1, jv0, jv1;
            grid.range(u, t.lo[u], t.hi[u], ju0, ju1);
            grid.range(v, t.lo[v], t.hi[v], jv0, jv1);
            jv0 = std::max(jv0, v0);
            jv1 = std::min(jv1, v1);
            for (int jv = jv0; jv <= jv1; ++jv) {
                const double pv = static_cast<double>(grid.origin[v]) + jv * h;
                for (int ju = ju0; ju <= ju1; ++ju) {
                    const double pu = static_cast<double>(grid.origin[u]) + ju * h;
                    double wa, wb, wc;
                    int sign;
                    if (!pointInTriangle2d(pu, pv, t.a[u], t.a[v], t.b[u], t.b[v], t.c[u], t.c[v], wa, wb, wc, sign))
                        continue;
                    const double x = wa * t.a[axis] + wb * t.b[axis] + wc * t.c[axis];
                    const double m = std::clamp(std::ceil((x - grid.origin[axis]) / h), 0.0, static_cast<double>(n));
                    // pointInTriangle2d's sign is minus the sign of normal[axis].
                    crossings[rowLength
                            * (static_cast<std::size_t>(jv - v0) * static_cast<std::size_t>(nu)
                                + static_cast<std::size_t>(ju))
                        + static_cast<std::size_t>(m)]
                        -= sign;
                }
            }
        }
        // Sample i sees, towards +axis, the crossings beyond it (sum over m > i) counted with the
        // normal's sign (leaving through an outward face counts +1), and towards -axis those before
        // it (m <= i) with the opposite sign: total - 2 * prefix(i).
        glm::ivec3 c;
        for (int jv = v0; jv <= v1; ++jv)
            for (int ju = 0; ju < nu; ++ju) {
                const std::int32_t* row = &crossings[rowLength
                    * (static_cast<std::size_t>(jv - v0) * static_cast<std::size_t>(nu)
                        + static_cast<std::size_t>(ju))];
                std::int32_t total = 0;
                for (std::size_t m = 0; m < rowLength; ++m)
                    total += row[m];
                std::int32_t prefix = 0;
                c[u] = ju;
                c[v] = jv;
                for (int i = 0; i < n; ++i) {
                    prefix += row[i];
                    c[axis] = i;
                    std::int16_t& slot = votes[grid.index(c)];
                    slot
                        = static_cast<std::int16_t>(std::clamp<std::int32_t>(slot + total - 2 * prefix, -30000, 30000));
                }
            }
    });
}

// One row of the Felzenszwalb–Huttenlocher squared distance transform, in cell units: out[q] =
// min_p ((q - p)^2 + f[p]) over the finite f. Rows without a finite input stay at kFarMarker.
void distanceTransformRow(const double* f, int n, double* out, int* sites, double* bounds)
{
    int k = -1;
    for (int q = 0; q < n; ++q) {
        if (f[q] >= kFarMarker)
            continue;
        double s = -std::numeric_limits<double>::infinity();
        while (k >= 0) {
            const int p = sites[k];
            s = ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) / (2.0 * (q - p));
            if (s > bounds[k])
                break;
            --k;
        }
        ++k;
        sites[k] = q;
        bounds[k] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
        bounds[k + 1] = std::numeric_limits<double>::infinity();
    }
    if (k < 0) {
        std::fill(out, out + n, static_cast<double>(kFarMarker));
        return;
    }
    int j = 0;
    for (int q = 0; q < n; ++q) {
        while (bounds[j + 1] < q)
            ++j;
        const double d = q - sites[j];
        out[q] = d * d + f[sites[j]];
    }
}

// Pass 3: squared distance (cells^2) from every sample to the nearest band sample, in place.
bool distanceTransform(int threads, const Grid& grid, std::vector<float>& field)
{
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int n = grid.dims[axis];
        const int planes = grid.dims[v];
        const bool ok = parallelFor(threads, planes, [&](int jv) {
            std::vector<double> in(static_cast<std::size_t>(n)), out(static_cast<std::size_t>(n)),
                bounds(static_cast<std::size_t>(n) + 1);
            std::vector<int> sites(static_cast<std::size_t>(n));
            glm::ivec3 c;
            c[v] = jv;
            for (int ju = 0; ju < grid.dims[u]; ++ju) {
                c[u] = ju;
                for (int i = 0; i < n; ++i) {
                    c[axis] = i;
                    in[static_cast<std::size_t>(i)] = field[grid.index(c)];
                }
                distanceTransformRow(in.data(), n, out.data(), sites.data(), bounds.data());
                for (int i = 0; i < n; ++i) {
                    c[axis] = i;
                    field[grid.index(c)] = static_cast<float>(
                        std::min(out[static_cast<std::size_t>(i)], static_cast<double>(kFarMarker)));
                }
            }
        });
        if (!ok)
            return false;
    }
    return true;
}

std::string describeFloat(float x)
{
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", static_cast<double>(x));
    return buffer;
}

} // namespace

SignedDistanceField SignedDistanceField::bake(
    const TriangleMesh& mesh, float cellSize, float margin, std::string* error, int threadCount)
{
    const int threads = threadCount > 0 ? std::min(threadCount, 64)
                                        : static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 64u));
    auto fail = [&](std::string message) {
        if (error)
            *error = std::move(message);
        return SignedDistanceField{};
    };
    if (error)
        error->clear();
    if (std::string problem = validateMesh(mesh); !problem.empty())
        return fail(problem);
    if (!std::isfinite(cellSize) || !(cellSize > 0.0f))
        return fail("the cell size must be a positive number of metres, not " + describeFloat(cellSize));
    if (cellSize > kMaxExtentMetres)
        return fail("a cell size of " + describeFloat(cellSize) + " m is absurd for a collider (at most "
            + describeFloat(kMaxExtentMetres) + " m)");
    if (!std::isfinite(margin) || margin < 0.0f)
        return fail("the margin must be zero or a positive number of metres, not " + describeFloat(margin));

    const Aabb meshBox = boundsOf(mesh);
    const glm::dvec3 lo = glm::dvec3(meshBox.min) - static_cast<double>(margin);
    const glm::dvec3 extent = glm::dvec3(meshBox.size()) + 2.0 * static_cast<double>(margin);
    for (int a = 0; a < 3; ++a)
        if (!std::isfinite(extent[a]) || extent[a] > kMaxExtentMetres)
            return fail("the collider's box is " + describeFloat(static_cast<float>(extent[a]))
                + " m across, more than " + describeFloat(kMaxExtentMetres) + " m: are the mesh's units metres?");

    // Enough samples to cover the box; coarser cells while the grid would be too large.
    double h = cellSize;
    glm::ivec3 dims(2);
    for (int attempt = 0;; ++attempt) {
        double total = 1.0;
        glm::dvec3 n;
        for (int a = 0; a < 3; ++a) {
            n[a] = std::max(2.0, std::ceil(extent[a] / h - 1e-9) + 1.0);
            total *= n[a];
        }
        if (total <= static_cast<double>(kMaxSamples) || attempt > 60) {
            if (total > static_cast<double>(kMaxSamples))
                return fail("could not fit the grid in memory"); // unreachable in practice
            dims = glm::ivec3(n);
            break;
        }
        h *= std::cbrt(total / static_cast<double>(kMaxSamples)) * 1.0001;
    }

    Grid grid;
    grid.dims = dims;
    grid.origin = glm::vec3(lo);
    grid.h = static_cast<float>(h);
    const float band = static_cast<float>(kBandCells) * grid.h;

    try {
        std::vector<BakeTriangle> triangles;
        triangles.reserve(mesh.triangles.size());
        for (const glm::uvec3& tri : mesh.triangles) {
            BakeTriangle t;
            t.a = mesh.positions[tri.x];
            t.b = mesh.positions[tri.y];
            t.c = mesh.positions[tri.z];
            const glm::vec3 n = glm::cross(t.b - t.a, t.c - t.a);
            const float len = glm::length(n);
            t.unitNormal = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f);
            t.lo = glm::min(t.a, glm::min(t.b, t.c));
            t.hi = glm::max(t.a, glm::max(t.b, t.c));
            triangles.push_back(t);
        }

        std::vector<float> values(grid.size(), kFarMarker); // squared band distances, then the result
        if (!bakeBand(threads, triangles, grid, band, values))
            return fail("not enough memory to bake the collider");

        std::vector<std::int16_t> votes(grid.size(), 0);
        for (int axis = 0; axis < 3; ++axis)
            if (!voteAlongAxis(threads, triangles, grid, axis, votes))
                return fail("not enough memory to bake the collider");

        // Band samples are the sources of the distance transform.
        const float band2 = band * band;
        std::vector<float> nearestBand2(grid.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            nearestBand2[i] = values[i] <= band2 ? 0.0f : kFarMarker;
        if (!distanceTransform(threads, grid, nearestBand2))
            return fail("not enough memory to bake the collider");

        const float slack = kSqrt3 * grid.h;
        const bool ok = parallelFor(threads, grid.dims.z, [&](int k) {
            const std::size_t begin = grid.index(0, 0, k),
                              end
                = begin + static_cast<std::size_t>(grid.dims.x) * static_cast<std::size_t>(grid.dims.y);
            for (std::size_t i = begin; i < end; ++i) {
                float d;
                if (values[i] <= band2)
                    d = std::sqrt(values[i]);
                else
                    d = std::max(band, grid.h * std::sqrt(nearestBand2[i]) + band - slack);
                values[i] = std::abs(static_cast<int>(votes[i])) > 3 ? -d : d;
            }
        });
        if (!ok)
            return fail("not enough memory to bake the collider");

        SignedDistanceField field;
        field.m_values = std::move(values);
        field.m_dims = grid.dims;
        field.m_origin = grid.origin;
        field.m_cellSize = grid.h;
        field.m_normalCache = std::make_shared<NormalCache>();
        return field;
    } catch (const std::bad_alloc&) {
        return fail("not enough memory for a " + std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x "
            + std::to_string(dims.z) + " collider grid");
    }
}

struct SignedDistanceField::NormalCache {
    std::once_flag built;
    std::vector<glm::vec4> samples;
};

const std::vector<glm::vec4>& SignedDistanceField::samplesWithNormals() const
{
    static const std::vector<glm::vec4> kNone;
    if (!m_normalCache)
        return kNone;
    std::call_once(m_normalCache->built, [this] {
        std::vector<glm::vec4>& out = m_normalCache->samples;
        out.resize(m_values.size());
        const glm::ivec3 dims = m_dims;
        auto at = [&](int x, int y, int z) {
            return sample(std::clamp(x, 0, dims.x - 1), std::clamp(y, 0, dims.y - 1), std::clamp(z, 0, dims.z - 1));
        };
        for (int k = 0; k < dims.z; ++k)
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i) {
                    glm::vec3 g(at(i + 1, j, k) - at(i - 1, j, k), at(i, j + 1, k) - at(i, j - 1, k),
                        at(i, j, k + 1) - at(i, j, k - 1));
                    const float len = glm::length(g);
                    g = len > 1e-12f ? g / len : glm::vec3(0.0f, 1.0f, 0.0f);
                    out[static_cast<std::size_t>(i)
                        + static_cast<std::size_t>(dims.x) * (j + static_cast<std::size_t>(dims.y) * k)]
                        = glm::vec4(at(i, j, k), g);
                }
    });
    return m_normalCache->samples;
}

Aabb SignedDistanceField::bounds() const
{
    if (empty())
        return {};
    return { m_origin, m_origin + glm::vec3(m_dims - 1) * m_cellSize };
}

float SignedDistanceField::distance(const glm::vec3& p) const
{
    if (empty() || !finite(p))
        return std::numeric_limits<float>::infinity();
    const glm::vec3 top = m_origin + glm::vec3(m_dims - 1) * m_cellSize;
    const glm::vec3 inside = glm::clamp(p, m_origin, top);
    const float outside = glm::length(p - inside);
    // Cell coordinates of the clamped point; the last cell is used for points on the far faces.
    const glm::vec3 g = (inside - m_origin) / m_cellSize;
    const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), m_dims - 2);
    const glm::vec3 f = glm::clamp(g - glm::vec3(cell), glm::vec3(0.0f), glm::vec3(1.0f));
    const std::size_t sx = 1, sy = static_cast<std::size_t>(m_dims.x), sz = sy * static_cast<std::size_t>(m_dims.y);
    const float* c = m_values.data() + static_cast<std::size_t>(cell.x) + sy * static_cast<std::size_t>(cell.y)
        + sz * static_cast<std::size_t>(cell.z);
    const float x00 = c[0] + (c[sx] - c[0]) * f.x;
    const float x10 = c[sy] + (c[sx + sy] - c[sy]) * f.x;
    const float x01 = c[sz] + (c[sx + sz] - c[sz]) * f.x;
    const float x11 = c[sy + sz] + (c[sx + sy + sz] - c[sy + sz]) * f.x;
    const float y0 = x00 + (x10 - x00) * f.y;
    const float y1 = x01 + (x11 - x01) * f.y;
    return y0 + (y1 - y0) * f.z + outside;
}

glm::vec3 SignedDistanceField::gradient(const glm::vec3& p) const
{
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    if (empty() || !finite(p))
        return up;
    const float e = 0.5f * m_cellSize;
    const glm::vec3 g(distance(p + glm::vec3(e, 0, 0)) - distance(p - glm::vec3(e, 0, 0)),
        distance(p + glm::vec3(0, e, 0)) - distance(p - glm::vec3(0, e, 0)),
        distance(p + glm::vec3(0, 0, e)) - distance(p - glm::vec3(0, 0, e)));
    const float len = glm::length(g);
    if (len > 1e-12f * m_cellSize && std::isfinite(len))
        return g / len;
    const glm::vec3 away = p - (m_origin + 0.5f * glm::vec3(m_dims - 1) * m_cellSize);
    const float awayLen = glm::length(away);
    if (awayLen > 0.0f && std::isfinite(awayLen))
        return away / awayLen;
    return up;
}

} // namespace wisp
