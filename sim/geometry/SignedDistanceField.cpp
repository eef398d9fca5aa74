#include "sim/geometry/SignedDistanceField.h"

#include "sim/geometry/SdfBake.h"
#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <mutex>
#include <new>
#include <thread>

// How the bake works, and why: sim/geometry/SdfBake.h, whose passes bake() runs.

namespace wisp {

namespace {

using namespace sdf_detail;

constexpr float kSqrt3 = 1.7320508f;

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
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
    if (threads == 1)
        return bake(mesh, cellSize, margin, error, nullptr);
    ThreadPool pool(threads);
    return bake(mesh, cellSize, margin, error, &pool);
}

SignedDistanceField SignedDistanceField::bake(
    const TriangleMesh& mesh, float cellSize, float margin, std::string* error, ThreadPool* pool)
{
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
        if (!bakeBand(pool, triangles, grid, band, values))
            return fail("not enough memory to bake the collider");

        std::vector<std::int16_t> votes(grid.size(), 0);
        for (int axis = 0; axis < 3; ++axis)
            if (!voteAlongAxis(pool, triangles, grid, axis, votes))
                return fail("not enough memory to bake the collider");

        // Band samples are the sources of the distance transform.
        const float band2 = band * band;
        std::vector<float> nearestBand2(grid.size());
        for (std::size_t i = 0; i < values.size(); ++i)
            nearestBand2[i] = values[i] <= band2 ? 0.0f : kFarMarker;
        if (!distanceTransform(pool, grid, nearestBand2))
            return fail("not enough memory to bake the collider");

        const float slack = kSqrt3 * grid.h;
        const bool ok = parallelFor(pool, grid.dims.z, [&](int k) {
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
