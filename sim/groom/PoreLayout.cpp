#include "sim/groom/PoreLayout.h"

#include "sim/util/Random.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace wisp::groom_detail {

namespace {

// A hashed 3D grid for blue-noise thinning and nearest-site queries.
class PointGrid {
public:
    explicit PointGrid(float cellSize)
        : m_inverseCell(1.0f / cellSize)
    {
    }

    void insert(const glm::vec3& p, std::uint32_t id) { m_cells[keyOf(cellOf(p))].push_back(id); }

    template <typename Visit> void forNeighbours(const glm::vec3& p, Visit&& visit) const
    {
        const glm::ivec3 c = cellOf(p);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const auto it = m_cells.find(keyOf(c + glm::ivec3(dx, dy, dz)));
                    if (it == m_cells.end())
                        continue;
                    for (std::uint32_t id : it->second)
                        visit(id);
                }
    }

private:
    glm::ivec3 cellOf(const glm::vec3& p) const { return glm::ivec3(glm::floor(p * m_inverseCell)); }
    static std::uint64_t keyOf(const glm::ivec3& c)
    {
        return (static_cast<std::uint64_t>(c.x + (1 << 20)) << 42) | (static_cast<std::uint64_t>(c.y + (1 << 20)) << 21)
            | static_cast<std::uint64_t>(c.z + (1 << 20));
    }
    float m_inverseCell;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> m_cells;
};

// Greedy Poisson-disk thinning in priority order: a point survives when no surviving point lies
// within `radius`. The result is a maximal blue-noise subset; deterministic because the order is.
std::vector<std::uint32_t> thinToBlueNoise(
    const std::vector<Pore>& pores, std::span<const std::uint32_t> order, float radius)
{
    PointGrid grid(radius);
    std::vector<std::uint32_t> kept;
    const float radius2 = radius * radius;
    for (std::uint32_t id : order) {
        bool blocked = false;
        grid.forNeighbours(pores[id].position, [&](std::uint32_t other) {
            const glm::vec3 d = pores[other].position - pores[id].position;
            blocked = blocked || glm::dot(d, d) < radius2;
        });
        if (!blocked) {
            grid.insert(pores[id].position, id);
            kept.push_back(id);
        }
    }
    return kept;
}

// Greedy thinning reaches about this many points per r² (measured on the default head; random
// sequential adsorption saturates near 0.547 of the hexagonal packing 2/sqrt(3)/r²).
constexpr float kThinnedPointsPerRadiusSquared = 0.52f;

// The weight-independent pore set for a density: candidates per triangle from counter-based
// randomness keyed by the triangle, thinned to blue noise. Changing the growth weights never
// changes this set; the weights only decide which pores grow a strand.

std::vector<Pore> poreSet(const TriangleMesh& head, float densityPerM2, std::uint32_t seed, std::size_t maxCandidates,
    float* radiusOut, PoreSetStats* stats)
{
    constexpr float kOversample = 4.0f;
    // Candidates scale with the whole mesh's area, painted or not: bound them (and with them the
    // sort and the thinning) by maxCandidates (kMaxPoreCandidates). Past it every triangle gets proportionally
    // fewer, so the layout stays even but sparser than asked; the caller warns.
    double wanted = 0.0;
    for (std::uint32_t t = 0; t < head.triangles.size(); ++t)
        wanted += static_cast<double>(triangleArea(head, t)) * densityPerM2 * kOversample;
    const bool capped = !(wanted <= static_cast<double>(maxCandidates));
    // Each triangle rounds its count up by a random fraction: aim a little low so the total stays
    // under the cap.
    const double aim = static_cast<double>(maxCandidates) - static_cast<double>(head.triangles.size());
    const float share = capped ? static_cast<float>(std::max(aim, 0.0) / wanted) : 1.0f;
    if (!(share > 0.0f)) { // a cap below one candidate a triangle: no pores at all
        *stats = { 0, wanted, true };
        *radiusOut = std::sqrt(kThinnedPointsPerRadiusSquared / densityPerM2);
        return {};
    }
    std::vector<Pore> candidates;
    candidates.reserve(
        static_cast<std::size_t>(std::min(wanted, static_cast<double>(maxCandidates))) + head.triangles.size());
    for (std::uint32_t t = 0; t < head.triangles.size(); ++t) {
        const float expected = triangleArea(head, t) * densityPerM2 * kOversample * share;
        const auto count = static_cast<std::uint32_t>(expected + randomUnit(seed, CandidateCount, t));
        for (std::uint32_t i = 0; i < count; ++i) {
            float b1 = randomUnit(seed, CandidatePoint, t, 2 * i);
            float b2 = randomUnit(seed, CandidatePoint, t, 2 * i + 1);
            if (b1 + b2 > 1.0f) { // fold the square onto the triangle: uniform by area
                b1 = 1.0f - b1;
                b2 = 1.0f - b2;
            }
            const SurfacePoint sp{ t, { b1, b2 } };
            candidates.push_back({ sp, pointOn(head, sp), randomUnit(seed, Priority, t, i) });
        }
    }
    *stats = { candidates.size(), wanted, capped };
    std::vector<std::uint32_t> order(candidates.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
        [&](std::uint32_t a, std::uint32_t b) { return candidates[a].priority < candidates[b].priority; });
    const float radius = std::sqrt(kThinnedPointsPerRadiusSquared / (densityPerM2 * share));
    std::vector<std::uint32_t> kept = thinToBlueNoise(candidates, order, radius);
    std::sort(kept.begin(), kept.end()); // stable ids in triangle order
    std::vector<Pore> pores;
    pores.reserve(kept.size());
    for (std::uint32_t id : kept)
        pores.push_back(candidates[id]);
    *radiusOut = radius;
    return pores;
}

} // namespace

PoreLayout makePoreLayout(const TriangleMesh& head, const GroomSettings& settings, std::size_t maxCandidates)
{
    PoreLayout layout;
    float radius = 0.0f;
    layout.pores = poreSet(head, settings.densityPerCm2 * 1e4f, settings.seed, maxCandidates, &radius, &layout.stats);
    const std::vector<Pore>& pores = layout.pores;
    std::vector<std::uint32_t> order(pores.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
        [&](std::uint32_t a, std::uint32_t b) { return pores[a].priority < pores[b].priority; });
    const float wispRadius = radius * std::sqrt(static_cast<float>(settings.wispSize));
    layout.sites = thinToBlueNoise(pores, order, wispRadius);
    PointGrid siteGrid(wispRadius);
    for (std::uint32_t i = 0; i < layout.sites.size(); ++i)
        siteGrid.insert(pores[layout.sites[i]].position, i);
    layout.siteOfPore.resize(pores.size());
    for (std::uint32_t id = 0; id < pores.size(); ++id) {
        std::uint32_t nearest = 0;
        float best = INFINITY;
        siteGrid.forNeighbours(pores[id].position, [&](std::uint32_t site) {
            const glm::vec3 d = pores[layout.sites[site]].position - pores[id].position;
            const float d2 = glm::dot(d, d);
            if (d2 < best || (d2 == best && site < nearest)) {
                best = d2;
                nearest = site;
            }
        });
        layout.siteOfPore[id] = nearest;
    }
    return layout;
}
} // namespace wisp::groom_detail
