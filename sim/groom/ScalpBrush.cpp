#include "sim/groom/ScalpBrush.h"
#include "sim/util/NumberText.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace wisp {
namespace {

// About half the default radius: a 2 cm dab then scans at most 5 x 5 x 5 cells, few of them
// empty near the surface, and a cell of a dense (135k-vertex) head holds around a hundred vertices.
constexpr float kCellMetres = 0.01f;
// Keeps the grid's memory bounded when a mesh is huge (say, in millimetres): cells grow instead.
constexpr std::size_t kMaxCells = std::size_t(1) << 20;

bool isFinite(const glm::vec3& p)
{
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::string checkRange(const char* field, float value, float minimum, float maximum, const char* unit)
{
    if (!std::isfinite(value))
        return std::string(field) + ": " + formatNumber(value) + " is not a finite number";
    if (value < minimum || value > maximum)
        return std::string(field) + ": " + formatNumber(value) + " is outside " + formatNumber(minimum) + ".."
            + formatNumber(maximum) + unit;
    return {};
}

} // namespace

std::string validateBrush(const BrushSettings& settings)
{
    if (auto e = checkRange("brush radius", settings.radiusMetres, kBrushRadiusMinMetres, kBrushRadiusMaxMetres, " m");
        !e.empty())
        return e;
    if (auto e = checkRange("brush strength", settings.strength, 0.0f, 1.0f, ""); !e.empty())
        return e;
    if (auto e = checkRange("brush falloff", settings.falloff, 0.0f, 1.0f, ""); !e.empty())
        return e;
    // A mode read from a file or a cast may hold any integer.
    if (const int mode = static_cast<int>(settings.mode); mode < 0 || mode > static_cast<int>(BrushMode::Smooth))
        return "brush mode: " + std::to_string(mode) + " is not add, erase or smooth";
    return {};
}

float brushFalloff(float distanceOverRadius, float falloff)
{
    if (!(distanceOverRadius <= 1.0f)) // also NaN
        return 0.0f;
    const float inner = 1.0f - falloff; // full strength up to here
    if (distanceOverRadius <= inner)
        return 1.0f;
    const float u = (distanceOverRadius - inner) / falloff; // falloff > 0 here, since t > inner = 1 - falloff
    return 1.0f - u * u * (3.0f - 2.0f * u);
}

ScalpBrush::ScalpBrush(const TriangleMesh& head)
    : m_vertexCount(head.positions.size())
{
    const std::vector<glm::vec3>& positions = head.positions;

    // Bounds of the finite vertices only: one NaN must not spoil the grid or the mirror plane.
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const glm::vec3& p : positions)
        if (isFinite(p)) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    if (lo.x <= hi.x)
        m_mirrorPlaneX = 0.5f * (lo.x + hi.x);
    // Cell counts in double: extents of up to 1e38 m must neither overflow nor loop forever. A mesh
    // whose extent overflows float gets no grid at all (nothing on it can be painted).
    if (lo.x <= hi.x && isFinite(hi - lo)) {
        const glm::dvec3 extent(hi - lo);
        double cell = kCellMetres;
        glm::dvec3 dims = glm::floor(extent / cell) + 1.0;
        while (dims.x * dims.y * dims.z > double(kMaxCells)) {
            cell *= 1.25;
            dims = glm::floor(extent / cell) + 1.0;
        }
        m_gridMin = lo;
        m_cellMetres = float(cell);
        m_gridDims = glm::ivec3(dims);
    }

    // Counting sort of the vertices into their cells (CSR layout).
    const std::size_t cellCount = std::size_t(m_gridDims.x) * std::size_t(m_gridDims.y) * std::size_t(m_gridDims.z);
    m_cellStart.assign(cellCount + 1, 0);
    std::vector<std::uint32_t> cellOf(positions.size(), 0xffffffffu);
    for (std::size_t v = 0; v < positions.size() && cellCount > 0; ++v) {
        if (!isFinite(positions[v]))
            continue;
        const glm::ivec3 c = glm::min(glm::ivec3((positions[v] - m_gridMin) / m_cellMetres), m_gridDims - 1);
        cellOf[v] = std::uint32_t(c.x + m_gridDims.x * (c.y + m_gridDims.y * c.z));
        ++m_cellStart[cellOf[v] + 1];
    }
    for (std::size_t i = 0; i < cellCount; ++i)
        m_cellStart[i + 1] += m_cellStart[i];
    m_grid.resize(cellCount > 0 ? m_cellStart[cellCount] : 0);
    {
        std::vector<std::uint32_t> fill(m_cellStart.begin(), m_cellStart.end() - 1);
        for (std::size_t v = 0; v < positions.size(); ++v)
            if (cellOf[v] != 0xffffffffu)
                m_grid[fill[cellOf[v]]++] = { positions[v], std::uint32_t(v) };
    }

    // One-ring: each triangle makes its corners neighbours of each other. Count with repeats, fill,
    // then sort and deduplicate each vertex's run and close the gaps.
    const std::size_t n = positions.size();
    auto valid = [n](const glm::uvec3& t) { return t.x < n && t.y < n && t.z < n; };
    std::vector<std::uint32_t> start(n + 1, 0);
    for (const glm::uvec3& t : head.triangles)
        if (valid(t))
            for (int k = 0; k < 3; ++k)
                start[t[k] + 1] += 2;
    for (std::size_t v = 0; v < n; ++v)
        start[v + 1] += start[v];
    std::vector<std::uint32_t> ring(start[n]);
    {
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (const glm::uvec3& t : head.triangles)
            if (valid(t))
                for (int k = 0; k < 3; ++k) {
                    ring[fill[t[k]]++] = t[(k + 1) % 3];
                    ring[fill[t[k]]++] = t[(k + 2) % 3];
                }
    }
    m_ringStart.assign(n + 1, 0);
    m_ring.reserve(ring.size() / 2); // closed manifolds share each edge between two triangles
    for (std::size_t v = 0; v < n; ++v) {
        const auto first = ring.begin() + start[v], last = ring.begin() + start[v + 1];
        std::sort(first, last);
        for (auto it = first; it != last; ++it)
            if (*it != v && (it == first || *it != *(it - 1))) // degenerate triangles may name v itself
                m_ring.push_back(*it);
        m_ringStart[v + 1] = std::uint32_t(m_ring.size());
    }
}

bool ScalpBrush::CellBox::contains(const glm::ivec3& c) const
{
    return glm::all(glm::greaterThanEqual(c, min)) && glm::all(glm::lessThanEqual(c, max));
}

ScalpBrush::CellBox ScalpBrush::cellsAround(const glm::vec3& centre, float radiusMetres) const
{
    if (m_grid.empty())
        return {};
    // Clamp in float before converting: a far-away centre must not overflow the int conversion.
    const glm::vec3 limit = glm::vec3(m_gridDims);
    auto cellCoordinates = [&](const glm::vec3& p) {
        return glm::clamp(glm::floor((p - m_gridMin) / m_cellMetres), glm::vec3(-1.0f), limit);
    };
    const glm::vec3 lo = cellCoordinates(centre - radiusMetres), hi = cellCoordinates(centre + radiusMetres);
    // The last cell also holds the vertices on the grid's far face (see the constructor's min()).
    return { glm::max(glm::ivec3(lo), 0), glm::min(glm::ivec3(hi), m_gridDims - 1) };
}

template <typename Visit> void ScalpBrush::forEachVertexIn(const CellBox& box, const CellBox* skip, Visit&& visit) const
{
    for (int z = box.min.z; z <= box.max.z; ++z)
        for (int y = box.min.y; y <= box.max.y; ++y)
            for (int x = box.min.x; x <= box.max.x; ++x) {
                if (skip && skip->contains({ x, y, z }))
                    continue;
                const std::size_t cell
                    = std::size_t(x) + std::size_t(m_gridDims.x) * (std::size_t(y) + std::size_t(m_gridDims.y) * z);
                for (std::uint32_t i = m_cellStart[cell]; i < m_cellStart[cell + 1]; ++i)
                    visit(m_grid[i]);
            }
}

std::vector<std::uint32_t> ScalpBrush::verticesNear(const glm::vec3& centre, float radiusMetres) const
{
    std::vector<std::uint32_t> found;
    if (!isFinite(centre) || !(radiusMetres >= 0.0f))
        return found;
    const float radius2 = radiusMetres * radiusMetres;
    forEachVertexIn(cellsAround(centre, radiusMetres), nullptr, [&](const GridVertex& g) {
        const glm::vec3 d = g.position - centre;
        if (glm::dot(d, d) <= radius2)
            found.push_back(g.vertex);
    });
    std::sort(found.begin(), found.end());
    return found;
}

std::vector<std::uint32_t> ScalpBrush::dab(
    const glm::vec3& centre, const BrushSettings& settings, std::span<float> weights) const
{
    if (weights.size() != m_vertexCount || !isFinite(centre) || !validateBrush(settings).empty())
        return {};

    const float radius = settings.radiusMetres, radius2 = radius * radius;
    const glm::vec3 mirrored(2.0f * m_mirrorPlaneX - centre.x, centre.y, centre.z);
    const bool mirror = settings.mirrorX && mirrored != centre; // a dab on the plane is its own mirror

    // Every new weight is computed from the weights before the dab (Smooth reads neighbours that
    // may change too), so changes are gathered first and written afterwards.
    struct Change {
        std::uint32_t vertex;
        float weight;
    };
    std::vector<Change> changes;
    auto paint = [&](const GridVertex& g) {
        const glm::vec3 a = g.position - centre;
        float distance2 = glm::dot(a, a);
        if (mirror) {
            // The falloff only falls with distance, so the larger influence is the nearer centre's.
            const glm::vec3 b = g.position - mirrored;
            distance2 = std::min(distance2, glm::dot(b, b));
        }
        if (distance2 > radius2)
            return;
        // min(): sqrt and the division may round a vertex on the rim just past 1.
        const float distanceOverRadius = std::min(std::sqrt(distance2) / radius, 1.0f);
        const float influence = settings.strength * brushFalloff(distanceOverRadius, settings.falloff);
        if (influence <= 0.0f)
            return;
        auto clean = [](float w) { return std::isfinite(w) ? std::clamp(w, 0.0f, 1.0f) : 0.0f; };
        const float old = clean(weights[g.vertex]);
        // The way to the target. Smooth averages the neighbours' differences rather than their
        // weights, so an already even patch gives exactly 0 and stays bit-identical.
        float toTarget = (settings.mode == BrushMode::Add ? 1.0f : 0.0f) - old;
        if (settings.mode == BrushMode::Smooth) {
            const std::uint32_t first = m_ringStart[g.vertex], last = m_ringStart[g.vertex + 1];
            if (first == last)
                return; // no neighbours to average
            float sum = 0.0f;
            for (std::uint32_t i = first; i < last; ++i)
                sum += clean(weights[m_ring[i]]) - old;
            toTarget = sum / float(last - first);
        }
        // Add and Erase at full influence land exactly on 1 and 0 (old + (1 - old) may round short).
        const float next = influence >= 1.0f && settings.mode != BrushMode::Smooth
            ? (settings.mode == BrushMode::Add ? 1.0f : 0.0f)
            : std::clamp(old + influence * toTarget, 0.0f, 1.0f);
        if (!(next == weights[g.vertex])) // also replaces a NaN
            changes.push_back({ g.vertex, next });
    };

    // Each vertex lives in one cell; skipping the first box's cells in the second pass visits every
    // vertex at most once, so one inside both spheres is painted once.
    const CellBox box = cellsAround(centre, radius);
    forEachVertexIn(box, nullptr, paint);
    if (mirror)
        forEachVertexIn(cellsAround(mirrored, radius), &box, paint);

    std::sort(changes.begin(), changes.end(), [](const Change& a, const Change& b) { return a.vertex < b.vertex; });
    std::vector<std::uint32_t> changed(changes.size());
    for (std::size_t i = 0; i < changes.size(); ++i) {
        weights[changes[i].vertex] = changes[i].weight;
        changed[i] = changes[i].vertex;
    }
    return changed;
}

} // namespace wisp
