#include "widgets/HairChildren.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace wisp {

namespace {

// A counter-based random number in [0, 1) (splitmix64), so a child keeps its place in every frame.
float unitRandom(std::uint64_t key)
{
    std::uint64_t z = key + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<float>(z >> 40) / static_cast<float>(1ull << 24);
}

struct CellKey {
    std::int64_t operator()(const glm::ivec3& c) const
    {
        return (static_cast<std::int64_t>(c.x) * 73856093) ^ (static_cast<std::int64_t>(c.y) * 19349663)
            ^ (static_cast<std::int64_t>(c.z) * 83492791);
    }
};

} // namespace

std::size_t HairChildren::prepare(const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand, float density)
{
    density = std::clamp(std::isfinite(density) ? density : 1.0f, kMinDensity, kMaxDensity);
    const std::vector<std::uint16_t> looks(lookOfStrand.begin(), lookOfStrand.end());
    if (strands.offsets == m_offsets && looks == m_looks && density == m_density)
        return m_children.size();
    m_offsets = strands.offsets;
    m_looks = looks;
    m_density = density;
    m_children.clear();
    const std::size_t n = strands.strandCount();
    if (density <= 1.0f || n < 3)
        return 0;

    // Roots, and a typical spacing between neighbouring roots from the roots' spread over an area.
    std::vector<glm::vec3> roots(n);
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (std::size_t s = 0; s < n; ++s) {
        roots[s] = strands.pointsIn(s) > 0 ? strands.positions[strands.offsets[s]] : glm::vec3(0.0f);
        if (!std::isfinite(roots[s].x + roots[s].y + roots[s].z))
            roots[s] = glm::vec3(std::numeric_limits<float>::max());
        else {
            lo = glm::min(lo, roots[s]);
            hi = glm::max(hi, roots[s]);
        }
    }
    const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-4f));
    // The roots cover (roughly) a surface: the two largest extents' area over the strand count.
    std::array<float, 3> e{ extent.x, extent.y, extent.z };
    std::sort(e.begin(), e.end());
    const float spacing = std::sqrt(e[1] * e[2] / static_cast<float>(n));
    const float cell = std::max(spacing * 2.0f, 1e-5f);
    std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
    const auto cellOf = [&](const glm::vec3& p) { return glm::ivec3(glm::floor((p - lo) / cell)); };
    for (std::uint32_t s = 0; s < n; ++s)
        if (roots[s].x != std::numeric_limits<float>::max())
            grid[CellKey{}(cellOf(roots[s]))].push_back(s);

    // Each strand's two nearest neighbours that may share its children.
    const float maxDistance = kMaxNeighbourSpacings * spacing;
    const int reach = static_cast<int>(std::ceil(maxDistance / cell));
    std::vector<std::array<std::uint32_t, 2>> neighbours(n);
    for (std::uint32_t s = 0; s < n; ++s) {
        std::array<std::uint32_t, 2> best{ s, s };
        std::array<float, 2> bestDistance{ maxDistance * maxDistance, maxDistance * maxDistance };
        if (roots[s].x != std::numeric_limits<float>::max()) {
            const glm::ivec3 c = cellOf(roots[s]);
            for (int dz = -reach; dz <= reach; ++dz)
                for (int dy = -reach; dy <= reach; ++dy)
                    for (int dx = -reach; dx <= reach; ++dx) {
                        const auto it = grid.find(CellKey{}(c + glm::ivec3(dx, dy, dz)));
                        if (it == grid.end())
                            continue;
                        for (std::uint32_t t : it->second) {
                            if (t == s || strands.pointsIn(t) != strands.pointsIn(s))
                                continue;
                            if (!looks.empty() && looks.size() == n && looks[t] != looks[s])
                                continue;
                            const glm::vec3 d = roots[t] - roots[s];
                            const float d2 = glm::dot(d, d);
                            if (d2 < bestDistance[0]) {
                                best = { t, best[0] };
                                bestDistance = { d2, bestDistance[0] };
                            } else if (d2 < bestDistance[1] && t != best[0]) {
                                best[1] = t;
                                bestDistance[1] = d2;
                            }
                        }
                    }
        }
        neighbours[s] = best; // s itself where none qualifies: its weight stays with the parent
    }

    // (density - 1) children per strand, spread evenly over the parents, each at a random point of
    // the triangle of its parent and the parent's neighbours (uniform: u + v > 1 is folded back).
    const auto children = static_cast<std::size_t>(std::lround((density - 1.0f) * static_cast<float>(n)));
    m_children.resize(children);
    for (std::size_t c = 0; c < children; ++c) {
        const auto parent = static_cast<std::uint32_t>(c % n);
        float u = unitRandom(2 * c);
        float v = unitRandom(2 * c + 1);
        if (u + v > 1.0f) {
            u = 1.0f - u;
            v = 1.0f - v;
        }
        // Nearer the parent than the far corners (a child is its parent's): at most half the way.
        u *= 0.5f;
        v *= 0.5f;
        m_children[c] = Child{ { parent, neighbours[parent][0], neighbours[parent][1] }, { 1.0f - u - v, u, v } };
    }
    return m_children.size();
}

void HairChildren::interpolate(const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand,
    std::span<const float> wetness, HairCurves& out, std::vector<std::uint16_t>& outLooks,
    std::vector<float>& outWetness) const
{
    const std::size_t n = strands.strandCount();
    std::size_t childPoints = 0;
    for (const Child& c : m_children)
        childPoints += strands.pointsIn(c.strands[0]);
    out.offsets.resize(n + 1 + m_children.size());
    out.positions.resize(strands.positions.size() + childPoints);
    std::copy(strands.offsets.begin(), strands.offsets.end(), out.offsets.begin());
    std::copy(strands.positions.begin(), strands.positions.end(), out.positions.begin());
    std::size_t at = strands.positions.size();
    for (std::size_t k = 0; k < m_children.size(); ++k) {
        const Child& c = m_children[k];
        const std::uint32_t points = strands.pointsIn(c.strands[0]);
        const glm::vec3* p0 = strands.positions.data() + strands.offsets[c.strands[0]];
        const glm::vec3* p1 = strands.positions.data() + strands.offsets[c.strands[1]];
        const glm::vec3* p2 = strands.positions.data() + strands.offsets[c.strands[2]];
        glm::vec3* o = out.positions.data() + at;
        for (std::uint32_t j = 0; j < points; ++j)
            o[j] = c.weights[0] * p0[j] + c.weights[1] * p1[j] + c.weights[2] * p2[j];
        at += points;
        out.offsets[n + 1 + k] = static_cast<std::uint32_t>(at);
    }
    outLooks.clear();
    if (lookOfStrand.size() == n) {
        outLooks.assign(lookOfStrand.begin(), lookOfStrand.end());
        for (const Child& c : m_children)
            outLooks.push_back(lookOfStrand[c.strands[0]]);
    }
    outWetness.clear();
    if (wetness.size() == n) {
        outWetness.assign(wetness.begin(), wetness.end());
        for (const Child& c : m_children)
            outWetness.push_back(wetness[c.strands[0]]);
    }
}

} // namespace wisp
