#include "sim/geometry/SdfBake.h"

#include "sim/geometry/MeshBvh.h" // closestPointOnTriangle
#include "sim/geometry/SdfBandRow.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>

namespace wisp::sdf_detail {

namespace {

constexpr int kSlabPlanes = 4;

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

} // namespace

// Pass 1: exact squared distances within the band (kFarMarker elsewhere).
bool bakeBand(ThreadPool* pool, const std::vector<BakeTriangle>& triangles, const Grid& grid, float band,
    std::vector<float>& dist2)
{
    const SlabBins bins = binBySlab(triangles, grid, 2, band);
    const int slabs = static_cast<int>(bins.offsets.size()) - 1;
    // A hair of slack keeps float rounding from dropping a sample that is exactly `band` away.
    const double reach = static_cast<double>(band) * 1.0001 + 1e-7;
    const double h = grid.h, inverseH = 1.0 / h;
    return parallelFor(pool, slabs, [&](int s) {
        const int k0 = s * kSlabPlanes, k1 = std::min(grid.dims.z - 1, k0 + kSlabPlanes - 1);
        std::vector<float> xs, ys, zs; // one triangle's samples in this slab (BandSamples)
        std::vector<std::uint32_t> indices;
        for (std::uint32_t n = bins.offsets[static_cast<std::size_t>(s)];
             n < bins.offsets[static_cast<std::size_t>(s) + 1]; ++n) {
            const BakeTriangle& t = triangles[bins.items[n]];
            xs.clear();
            ys.clear();
            zs.clear();
            indices.clear();
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
            // (Reciprocals once a triangle: the rows' bounds are rounded outward by a thousandth of
            // a cell, so the last bits these change move no bound.)
            const double slope = h * normal.x;
            const bool steep = std::abs(slope) > 1e-12 * h;
            const double inverseSlope = steep ? 1.0 / slope : 0.0;
            for (int k = kk0; k <= kk1; ++k)
                for (int j = j0; j <= j1; ++j) {
                    const glm::dvec3 rowStart(grid.origin.x, grid.origin.y + j * h, grid.origin.z + k * h);
                    const double dy = rowStart.y - centre.y, dz = rowStart.z - centre.z;
                    const double across2 = radius * radius - dy * dy - dz * dz;
                    if (across2 < 0.0)
                        continue;
                    const double across = std::sqrt(across2);
                    double lo = (centre.x - across - grid.origin.x) * inverseH,
                           hi = (centre.x + across - grid.origin.x) * inverseH;
                    // Plane distance along the row: c0 + i * h * normal.x.
                    const double c0 = glm::dot(rowStart - glm::dvec3(t.a), normal);
                    if (steep) {
                        const double p = (-reach - c0) * inverseSlope, q = (reach - c0) * inverseSlope;
                        lo = std::max(lo, std::min(p, q));
                        hi = std::min(hi, std::max(p, q));
                    } else if (std::abs(c0) > reach) {
                        continue;
                    }
                    const int first = std::max(i0, static_cast<int>(std::clamp(std::ceil(lo - 1e-3), -1.0, 1e9)));
                    const int last = std::min(i1, static_cast<int>(std::clamp(std::floor(hi + 1e-3), -1.0, 1e9)));
                    // The row's samples join the triangle's list, at their positions as
                    // Grid::position computes them.
                    for (int i = first; i <= last; ++i) {
                        const glm::vec3 p = grid.position(i, j, k);
                        xs.push_back(p.x);
                        ys.push_back(p.y);
                        zs.push_back(p.z);
                        indices.push_back(static_cast<std::uint32_t>(grid.index(i, j, k)));
                    }
                }
            // Their exact distances, a register of samples at a time across the rows (SdfBandRow.h).
            const std::size_t count = xs.size();
            const std::size_t padded = (count + kBandSamplePadding - 1) / kBandSamplePadding * kBandSamplePadding;
            xs.resize(padded, 0.0f);
            ys.resize(padded, 0.0f);
            zs.resize(padded, 0.0f);
            bandSamples(t, BandSamples{ xs.data(), ys.data(), zs.data(), indices.data(), count }, dist2.data());
        }
    });
}

// Pass 2, once per ray axis: adds to `votes` the signed crossings along +axis and -axis.
bool voteAlongAxis(ThreadPool* pool, const std::vector<BakeTriangle>& triangles, const Grid& grid, int axis,
    std::vector<std::int16_t>& votes)
{
    // (u, v) = the two other axes in cyclic order, so the 2D orientation of a projected triangle
    // has the sign of its normal's `axis` component.
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int n = grid.dims[axis], nu = grid.dims[u];
    const SlabBins bins = binBySlab(triangles, grid, v, 0.0f);
    const int slabs = static_cast<int>(bins.offsets.size()) - 1;
    const double h = grid.h;
    return parallelFor(pool, slabs, [&](int s) {
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

bool distanceTransform(ThreadPool* pool, const Grid& grid, std::vector<float>& field)
{
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int n = grid.dims[axis];
        const int planes = grid.dims[v];
        const bool ok = parallelFor(pool, planes, [&](int jv) {
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

} // namespace wisp::sdf_detail
