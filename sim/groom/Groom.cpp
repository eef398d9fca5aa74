#include "sim/groom/Groom.h"

#include "sim/geometry/ShortestArc.h"

#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/util/Random.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <numeric>
#include <tuple>
#include <unordered_map>

namespace wisp {
namespace {

// Keys of the independent random streams, so that e.g. lengths never correlate with positions.
enum Stream : std::uint64_t { CandidateCount = 1, CandidatePoint, Priority, Keep, LengthJitter, CurlPhase };

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

struct Pore {
    SurfacePoint surface;
    glm::vec3 position;
    float priority;
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
struct PoreSetStats {
    std::size_t candidates = 0;
    double wantedCandidates = 0.0; // before the cap
    bool capped = false;
};

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

// Pushes p out of the collider to `offset` above the skin (Lee et al. 3.4: nodes inside the head move out).
glm::vec3 pushOut(const SignedDistanceField* collider, glm::vec3 p, float offset)
{
    if (!collider)
        return p;
    for (int i = 0; i < 3; ++i) {
        const float d = collider->distance(p);
        if (d >= offset)
            break;
        p += (offset - d) * collider->gradient(p);
    }
    return p;
}

// Rest shape of one key hair: it leaves the scalp along the normal, turns toward "down" along the
// head as a combed strand does, drapes over the head (pushed out where it would go inside) and,
// with curl, winds as a helix around that centreline (curlHelix: turns per metre of hair). Every
// segment is length / segments long, so the polyline's arc length is the strand's length.
void buildKeyRest(const glm::vec3& root, const glm::vec3& normal, float partX, float length, int segments,
    float curlRadius, float curlTurnsPerMetre, float curlPhase, float offset, const SignedDistanceField* collider,
    std::span<glm::vec3> out)
{
    const bool curly = curlRadius > 0.0f && curlTurnsPerMetre > 0.0f;
    const CurlHelix helix = curlHelix(length, segments, curlRadius, curlTurnsPerMetre);
    const float segmentLength = length / static_cast<float>(segments);
    // The curl's radius ramps up over the first 2 cm of hair so the root stays on the scalp.
    constexpr float kRampMetres = 0.02f;
    auto radiusAt = [&](std::size_t j) {
        return curlRadius * std::min(1.0f, segmentLength * static_cast<float>(j) / kRampMetres);
    };
    // Centreline advance of each segment: what is left of the segment's length once the helix has
    // gone around by its angle (exact for a straight centreline; the ramp makes the first ones longer).
    std::vector<float> step(out.size(), segmentLength);
    if (curly)
        for (std::size_t j = 1; j < out.size(); ++j) {
            const float r0 = radiusAt(j - 1), r1 = radiusAt(j);
            const float across = r0 * r0 + r1 * r1 - 2.0f * r0 * r1 * std::cos(helix.anglePerSegment);
            step[j]
                = std::sqrt(std::max(segmentLength * segmentLength - across, 0.01f * segmentLength * segmentLength));
        }
    const float axisLength = std::accumulate(step.begin() + 1, step.end(), 0.0f);

    // Centreline.
    std::vector<glm::vec3> centre(out.size());
    std::vector<glm::vec3> tangent(out.size());
    centre[0] = root;
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    // Combed with a centre part: down, away from the part line and a little toward the back, so
    // the front hair frames the face instead of falling over it.
    const float side = std::clamp((root.x - partX) / 0.02f, -1.0f, 1.0f);
    const glm::vec3 comb = glm::normalize(glm::vec3(0.8f * side, -1.0f, -0.6f));
    glm::vec3 flow = comb - normal * glm::dot(comb, normal);
    if (glm::length(flow) < 0.2f) // the comb direction is along the normal: comb toward the back
        flow += glm::vec3(0.0f, 0.0f, -0.5f);
    flow = glm::normalize(flow);
    glm::vec3 direction = normal;
    constexpr float kTurnDistance = 0.03f; // metres over which the strand turns from the normal to the flow
    float s = 0.0f; // along the centreline
    for (std::size_t j = 1; j < out.size(); ++j) {
        s += step[j];
        const float blend = std::min(1.0f, s / kTurnDistance);
        glm::vec3 want = glm::normalize(glm::mix(normal, flow, blend));
        // Far from the head the strand hangs toward gravity.
        want = glm::normalize(glm::mix(want, down, std::min(1.0f, s / (4.0f * kTurnDistance + axisLength)) * 0.6f));
        direction = glm::normalize(glm::mix(direction, want, 0.7f));
        glm::vec3 p = centre[j - 1] + step[j] * direction;
        if (j > 1) {
            p = pushOut(collider, p, offset + curlRadius);
            p = centre[j - 1] + step[j] * glm::normalize(p - centre[j - 1]);
        }
        direction = glm::normalize(p - centre[j - 1]);
        centre[j] = p;
    }
    if (!curly) {
        std::copy(centre.begin(), centre.end(), out.begin());
        return;
    }
    for (std::size_t j = 0; j < out.size(); ++j) {
        const std::size_t a = j == 0 ? 0 : j - 1;
        const std::size_t b = std::min(j + 1, out.size() - 1);
        tangent[j] = glm::normalize(centre[b] - centre[a]);
    }
    // Helix around the centreline in a parallel-transported frame.
    glm::vec3 u = anyPerpendicular(tangent[0]);
    for (std::size_t j = 0; j < out.size(); ++j) {
        if (j > 0)
            u = glm::normalize(rotateShortestArc(tangent[j - 1], tangent[j], u));
        const glm::vec3 v = glm::cross(tangent[j], u);
        const float angle = helix.anglePerSegment * static_cast<float>(j) + curlPhase;
        out[j] = centre[j] + radiusAt(j) * (std::cos(angle) * u + std::sin(angle) * v);
    }
    // Where the centreline bends, a segment is a little longer or shorter than planned: keep each
    // segment's direction and give it its length again, so the arc length is the strand's length.
    glm::vec3 previous = out[0];
    for (std::size_t j = 1; j < out.size(); ++j) {
        const glm::vec3 d = out[j] - previous;
        const float l = glm::length(d);
        previous = out[j];
        out[j] = out[j - 1] + (l > 1e-9f ? d * (segmentLength / l) : segmentLength * tangent[j]);
    }
}

// Lee et al.: members start to clump at clump-rate along the strand and reach clump-degree at the tip.
float clumpAt(float u, float clumpDegree, float clumpRate)
{
    if (u <= clumpRate || clumpRate >= 1.0f)
        return 0.0f;
    const float x = (u - clumpRate) / (1.0f - clumpRate);
    return clumpDegree * x * x * (3.0f - 2.0f * x); // smoothstep: no kink where clumping starts
}

// The normal of the head at a surface point, interpolated from vertex normals.
glm::vec3 normalAt(const TriangleMesh& head, const std::vector<glm::vec3>& normals, const SurfacePoint& sp)
{
    const glm::uvec3 tri = head.triangles[sp.triangle];
    const float b0 = 1.0f - sp.barycentric.x - sp.barycentric.y;
    const glm::vec3 n = b0 * normals[tri.x] + sp.barycentric.x * normals[tri.y] + sp.barycentric.y * normals[tri.z];
    return glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0, 1, 0);
}

// The strands of each wisp, in strand order.
std::vector<std::vector<std::uint32_t>> membersOfWisps(const Groom& groom)
{
    std::vector<std::vector<std::uint32_t>> members(groom.wispCount());
    for (std::uint32_t i = 0; i < groom.strandCount(); ++i)
        members[groom.wispOf[i]].push_back(i);
    return members;
}

using MemberFix = std::function<void(std::uint32_t strand, std::span<glm::vec3> points)>;
void buildWispMembers(const Groom& groom, std::size_t w, std::span<const std::uint32_t> members,
    std::span<const glm::vec3> key, const glm::mat3& headRotation, HairCurves& out, float wetClump = 0.0f,
    const MemberFix& keepShape = {});

// Everything of a groom the layout of its pores cannot tell: what the head looks like there and
// the rest shapes. Rest shapes of wisps equal to one of `previous` (same region, site, members and
// settings) are copied from it instead of being built again.
struct RestContext {
    const TriangleMesh& head;
    const std::vector<glm::vec3>& normals;
    float partX;
    const SignedDistanceField* collider;
    // Rest shapes that are given, not built (imported strands), by strand index.
    const std::unordered_map<std::uint32_t, std::vector<glm::vec3>>* givenRest = nullptr;
    const StyleEdits* style = nullptr; // salon edits by strand identity
};

std::uint64_t styleHashOf(const Groom& groom, std::size_t strand)
{
    return strand < groom.styleHash.size() ? groom.styleHash[strand] : 0;
}

std::size_t buildRest(Groom& groom, const RestContext& context, const Groom* previous)
{
    const auto points = static_cast<std::uint32_t>(groom.settings.segments + 1);
    groom.rest.clear();
    groom.rest.offsets.reserve(groom.roots.size() + 1);
    groom.rest.positions.reserve(groom.roots.size() * points);
    for (std::size_t i = 0; i < groom.roots.size(); ++i)
        groom.rest.addStrand(points);
    const std::vector<std::vector<std::uint32_t>> members = membersOfWisps(groom);

    // Previous wisps by (region id, site).
    std::unordered_map<std::uint64_t, std::uint32_t> previousWisp;
    std::vector<std::vector<std::uint32_t>> previousMembers;
    if (previous && previous->settings.segments == groom.settings.segments
        && previous->settings.hairOffsetMetres == groom.settings.hairOffsetMetres && previous->wispCount() > 0) {
        previousMembers = membersOfWisps(*previous);
        for (std::uint32_t w = 0; w < previous->wispCount(); ++w) {
            const std::uint64_t region = previous->regionIds[previous->regionOfStrand[previous->keyStrand[w]]];
            previousWisp.emplace((region << 32) | previous->siteOfWisp[w], w);
        }
    }
    auto sameSettings = [](const GroomSettings& a, const GroomSettings& b) {
        return a.densityPerCm2 == b.densityPerCm2 && a.wispSize == b.wispSize && a.clumpDegree == b.clumpDegree
            && a.clumpRate == b.clumpRate && a.lengthMetres == b.lengthMetres && a.lengthVariation == b.lengthVariation
            && a.curlRadiusMetres == b.curlRadiusMetres && a.curlTurnsPerMetre == b.curlTurnsPerMetre
            && a.seed == b.seed;
    };
    // A wisp is reusable when it has the same members with the same identities.
    auto reusable = [&](std::size_t w) -> std::int64_t {
        if (previousWisp.empty())
            return -1;
        const std::uint64_t region = groom.regionIds[groom.regionOfStrand[groom.keyStrand[w]]];
        const auto it = previousWisp.find((region << 32) | groom.siteOfWisp[w]);
        if (it == previousWisp.end())
            return -1;
        const std::uint32_t pw = it->second;
        if (!sameSettings(groom.settingsOfWisp(w), previous->settingsOfWisp(pw)))
            return -1;
        const std::vector<std::uint32_t>& now = members[w];
        const std::vector<std::uint32_t>& before = previousMembers[pw];
        if (now.size() != before.size())
            return -1;
        for (std::size_t m = 0; m < now.size(); ++m)
            if (groom.rootIds[now[m]] != previous->rootIds[before[m]]
                || styleHashOf(groom, now[m]) != styleHashOf(*previous, before[m])
                || (groom.keyStrand[w] == now[m]) != (previous->keyStrand[pw] == before[m]))
                return -1;
        return pw;
    };

    std::size_t reused = 0;
    for (std::size_t w = 0; w < groom.wispCount(); ++w) {
        if (const std::int64_t pw = reusable(w); pw >= 0) {
            const std::vector<std::uint32_t>& before = previousMembers[static_cast<std::size_t>(pw)];
            for (std::size_t m = 0; m < members[w].size(); ++m) {
                const std::span<const glm::vec3> src = previous->rest.strand(before[m]);
                std::copy(src.begin(), src.end(), groom.rest.strandForWrite(members[w][m]).begin());
            }
            ++reused;
            continue;
        }
        const std::uint32_t k = groom.keyStrand[w];
        const StrandStyle* style = nullptr;
        if (context.style && styleHashOf(groom, k) != 0)
            if (const auto found = context.style->find(groom.strandIdentity(k)); found != context.style->end())
                style = &found->second;
        if (style && style->shape.size() >= 2) { // combed: the comb's shape is the rest shape
            const std::vector<glm::vec3> shape = resampleByArcLength(style->shape, points);
            if (!shape.empty()) {
                std::span<glm::vec3> key = groom.rest.strandForWrite(k);
                std::copy(shape.begin(), shape.end(), key.begin());
                key[0] = groom.rootPositions[k];
                buildWispMembers(groom, w, members[w], key, glm::mat3(1.0f), groom.rest);
                continue;
            }
        }
        if (context.givenRest) {
            if (const auto given = context.givenRest->find(k); given != context.givenRest->end()) {
                std::vector<glm::vec3> rest = given->second;
                if (style && style->lengthMetres > 0.0f) // an imported strand cut or grown
                    rest = resampleByArcLength(shapeWithLength(rest, style->lengthMetres), points);
                if (rest.size() != points)
                    rest = given->second;
                std::copy(rest.begin(), rest.end(), groom.rest.strandForWrite(k).begin());
                continue; // an imported strand is a wisp of its own
            }
        }
        const GroomSettings& s = groom.settingsOfWisp(w);
        const glm::vec3 n = normalAt(context.head, context.normals, groom.roots[k]);
        const float phase = glm::two_pi<float>() * randomUnit(s.seed, CurlPhase, groom.rootIds[k]);
        std::span<glm::vec3> key = groom.rest.strandForWrite(k);
        // A perm gives the key hair (and so its wisp) its own curl.
        const float curlRadius
            = style && style->curlRadiusMetres >= 0.0f ? style->curlRadiusMetres : s.curlRadiusMetres;
        const float curlTurns
            = style && style->curlTurnsPerMetre >= 0.0f ? style->curlTurnsPerMetre : s.curlTurnsPerMetre;
        buildKeyRest(groom.rootPositions[k], n, context.partX, groom.lengths[k], s.segments, curlRadius, curlTurns,
            phase, s.hairOffsetMetres, context.collider, key);
        buildWispMembers(groom, w, members[w], key, glm::mat3(1.0f), groom.rest);
    }
    return reused;
}

// What of a region's groom does not depend on its painted weights: the pores, the wisp sites (a
// coarser blue-noise subset, so a wisp's neighbourhood does not shift when an artist paints
// elsewhere) and each pore's nearest site.
struct PoreLayout {
    PoreSetStats stats;
    std::vector<Pore> pores;
    std::vector<std::uint32_t> sites; // pore index of each site
    std::vector<std::uint32_t> siteOfPore; // nearest site of each pore
};

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

// One region's strands and wisps, appended to `groom`: a pore grows a strand when its painted
// weight beats its own random threshold, so the local density follows the weight and a weight-0
// area has no strand at all. The strands sharing a site form a wisp whose key hair is the member
// nearest the site.
void growRegion(Groom& groom, const TriangleMesh& head, const PoreLayout& layout, std::span<const float> weights,
    const GroomSettings& settings, std::uint16_t region)
{
    std::unordered_map<std::uint32_t, std::uint32_t> wispOfSite;
    std::vector<float> keyDistance;
    const std::size_t firstWisp = groom.keyStrand.size();
    for (std::uint32_t id = 0; id < layout.pores.size(); ++id) {
        const Pore& pore = layout.pores[id];
        const glm::uvec3 tri = head.triangles[pore.surface.triangle];
        const float b0 = 1.0f - pore.surface.barycentric.x - pore.surface.barycentric.y;
        const float weight = b0 * weights[tri.x] + pore.surface.barycentric.x * weights[tri.y]
            + pore.surface.barycentric.y * weights[tri.z];
        if (!(weight > randomUnit(settings.seed, Keep, id)))
            continue;
        const auto strand = static_cast<std::uint32_t>(groom.roots.size());
        groom.roots.push_back(pore.surface);
        groom.rootIds.push_back(id);
        groom.rootPositions.push_back(pore.position);
        groom.regionOfStrand.push_back(region);
        const float jitter = 2.0f * randomUnit(settings.seed, LengthJitter, id) - 1.0f;
        groom.lengths.push_back(settings.lengthMetres * (1.0f + settings.lengthVariation * jitter));

        const std::uint32_t site = layout.siteOfPore[id];
        const float d = glm::distance(pore.position, layout.pores[layout.sites[site]].position);
        auto [it, added] = wispOfSite.emplace(site, static_cast<std::uint32_t>(groom.keyStrand.size()));
        if (added) {
            groom.keyStrand.push_back(strand);
            groom.siteOfWisp.push_back(site);
            keyDistance.push_back(d);
        }
        const std::uint32_t w = it->second;
        groom.wispOf.push_back(w);
        if (d < keyDistance[w - firstWisp]) {
            keyDistance[w - firstWisp] = d;
            groom.keyStrand[w] = strand;
        }
    }
}

// A region of imported strands: each strand, resampled to the shared segment count, becomes a
// wisp of its own, moved so that its root sits on the nearest point of the head (the file's
// roots lie on its own scalp, a little off ours). Strands of fewer than two distinct points
// are skipped. The strand's index in the file is its identity across regrooms.
void growImported(Groom& groom, const MeshBvh& bvh, const HairCurves& strands, const GroomSettings& settings,
    std::uint16_t region, std::unordered_map<std::uint32_t, std::vector<glm::vec3>>& givenRest)
{
    const std::size_t points = static_cast<std::size_t>(settings.segments) + 1;
    for (std::uint32_t i = 0; i < strands.strandCount(); ++i) {
        const std::span<const glm::vec3> s = strands.strand(i);
        std::vector<glm::vec3> rest = resampleByArcLength(s, points);
        if (rest.empty())
            continue;
        const MeshBvh::ClosestPoint root = bvh.closestPoint(rest.front());
        const glm::vec3 shift = root.point - rest.front();
        float length = 0.0f;
        for (std::size_t j = 0; j < rest.size(); ++j) {
            rest[j] += shift;
            if (j > 0)
                length += glm::distance(rest[j], rest[j - 1]);
        }
        const auto strand = static_cast<std::uint32_t>(groom.roots.size());
        groom.roots.push_back(root.surface);
        groom.rootIds.push_back(i);
        groom.rootPositions.push_back(root.point);
        groom.regionOfStrand.push_back(region);
        groom.lengths.push_back(length);
        groom.wispOf.push_back(static_cast<std::uint32_t>(groom.keyStrand.size()));
        groom.keyStrand.push_back(strand);
        groom.siteOfWisp.push_back(i);
        givenRest.emplace(strand, std::move(rest));
    }
}

// Salon edits that change a strand's length (cut, grow, shrink, comb) and the hash by which a
// rebuild tells an edited strand's rest shape from the one it had.
void applyStyleLengths(Groom& groom, const StyleEdits* style)
{
    groom.styleHash.assign(groom.strandCount(), 0);
    if (!style || style->empty())
        return;
    const std::vector<float> groomed = groom.lengths; // before the edits
    for (std::size_t i = 0; i < groom.strandCount(); ++i) {
        const auto found = style->find(groom.strandIdentity(i));
        if (found == style->end())
            continue;
        const StrandStyle& s = found->second;
        groom.styleHash[i] = restShapeHash(s);
        if (s.shape.size() >= 2)
            groom.lengths[i] = strandLength(s.shape);
        else if (s.lengthMetres > 0.0f)
            groom.lengths[i] = s.lengthMetres;
    }
    // A member rides beside its key hair point for point (buildWispMembers); past the key's tip it
    // can only go on straight along the tip's direction, which for a key cut near the scalp points
    // straight out of it. So no member is longer than its key by more than their groomed lengths'
    // ratio: where the key is shorter, its members are cut with it, as the cut tool does. Edits
    // made on another groom reach this one with a key shorter than its members whenever the wisps
    // were regrouped since (a preset or a slider changed the density or the wisp size).
    for (std::size_t i = 0; i < groom.strandCount(); ++i) {
        const std::uint32_t k = groom.keyStrand[groom.wispOf[i]];
        if (k == i || !(groomed[k] > 0.0f))
            continue;
        const float longest = groom.lengths[k] * std::max(1.0f, groomed[i] / groomed[k]);
        groom.lengths[i] = std::min(groom.lengths[i], longest);
    }
}

// A region's seed: the shared seed, mixed with the region's identity so regions do not repeat
// each other's pores (region 0 keeps the shared seed).
std::uint32_t regionSeed(std::uint32_t seed, std::uint32_t regionId)
{
    return regionId == 0 ? seed : static_cast<std::uint32_t>(hashKeys(seed, 0x5e9105u, regionId));
}

GroomSettings mergedSettings(const GroomSettings& region, const GroomSettings& shared, std::uint32_t regionId)
{
    GroomSettings s = region;
    s.segments = shared.segments;
    s.seed = regionSeed(shared.seed, regionId);
    s.hairOffsetMetres = shared.hairOffsetMetres;
    return s;
}

} // namespace

GroomSettings groomSettingsFrom(const ParameterValues& v)
{
    GroomSettings s;
    s.densityPerCm2 = v.getFloat(Param::Density);
    s.wispSize = v.getInt(Param::WispSize);
    s.clumpDegree = v.getFloat(Param::ClumpDegree);
    s.clumpRate = v.getFloat(Param::ClumpRate);
    s.lengthMetres = v.getFloat(Param::Length);
    s.lengthVariation = v.getFloat(Param::LengthVariation);
    s.segments = v.getInt(Param::Segments);
    s.curlRadiusMetres = v.getFloat(Param::CurlRadius);
    s.curlTurnsPerMetre = v.getFloat(Param::CurlTurns);
    s.seed = static_cast<std::uint32_t>(v.get(Param::Seed));
    s.hairOffsetMetres = v.getFloat(Param::HairOffset);
    return s;
}

CurlHelix curlHelix(float lengthMetres, int segments, float radiusMetres, float turnsPerMetreOfHair)
{
    CurlHelix h;
    if (!(radiusMetres > 0.0f) || !(turnsPerMetreOfHair > 0.0f) || !(lengthMetres > 0.0f) || segments < 1)
        return h;
    // Hair wound around a helix of radius r goes at most 1 / (2 pi r) times around per metre (a
    // flat ring); kMaxCurlWrap keeps the coil from closing on itself.
    const float tightest = kMaxCurlWrap / (glm::two_pi<float>() * radiusMetres);
    h.radiusMetres = radiusMetres;
    h.turnsPerMetre = std::min(turnsPerMetreOfHair, tightest);
    h.clamped = turnsPerMetreOfHair > tightest;
    h.anglePerSegment = glm::two_pi<float>() * h.turnsPerMetre * lengthMetres / static_cast<float>(segments);
    // Along the smooth helix, the hair per turn is sqrt((2 pi r)^2 + p^2) = 1 / T.
    const float perTurn = 1.0f / h.turnsPerMetre, around = glm::two_pi<float>() * radiusMetres;
    h.pitchMetres = std::sqrt(std::max(perTurn * perTurn - around * around, 0.0f));
    return h;
}

std::string validateGroomSettings(const GroomSettings& s)
{
    return checkParameterValues({
        { Param::Density, s.densityPerCm2 },
        { Param::WispSize, s.wispSize },
        { Param::ClumpDegree, s.clumpDegree },
        { Param::ClumpRate, s.clumpRate },
        { Param::Length, s.lengthMetres },
        { Param::LengthVariation, s.lengthVariation },
        { Param::Segments, s.segments },
        { Param::CurlRadius, s.curlRadiusMetres },
        { Param::CurlTurns, s.curlTurnsPerMetre },
        { Param::HairOffset, s.hairOffsetMetres },
    });
}

// What a GroomBuilder keeps between builds on one head.
struct GroomBuilder::Cache {
    const TriangleMesh* head = nullptr; // identity check only; the caller keeps the head alive
    std::size_t vertices = 0, triangles = 0;
    std::vector<glm::vec3> normals;
    float partX = 0.0f; // the head's mid-plane, where the part runs
    double areaM2 = 0.0;
    struct Key {
        float density;
        int wispSize;
        std::uint32_t seed;
        bool operator<(const Key& o) const
        {
            return std::tie(density, wispSize, seed) < std::tie(o.density, o.wispSize, o.seed);
        }
    };
    std::map<Key, std::shared_ptr<const PoreLayout>> layouts;
};

GroomBuilder::GroomBuilder()
    : m_cache(std::make_unique<Cache>())
{
}
GroomBuilder::~GroomBuilder() = default;
GroomBuilder::GroomBuilder(GroomBuilder&&) noexcept = default;
GroomBuilder& GroomBuilder::operator=(GroomBuilder&&) noexcept = default;

void GroomBuilder::forgetHead()
{
    *m_cache = Cache{};
}

void GroomBuilder::setMaxPoreCandidates(std::size_t cap)
{
    m_maxPoreCandidates = cap;
    forgetHead();
}

GroomResult GroomBuilder::build(const TriangleMesh& head, std::span<const GroomRegionInput> regions,
    const GroomSettings& shared, const SignedDistanceField* collider, const Groom* previous, const MeshBvh* bvh,
    const StyleEdits* style)
{
    m_reused = m_built = 0;
    m_poreCandidates = 0;
    Cache& cache = *m_cache;
    if (cache.head != &head || cache.vertices != head.positions.size() || cache.triangles != head.triangles.size()) {
        if (std::string error = validateMesh(head); !error.empty())
            return { {}, "head: " + error };
        forgetHead();
        cache.head = &head;
        cache.vertices = head.positions.size();
        cache.triangles = head.triangles.size();
        cache.normals = vertexNormals(head);
        cache.partX = boundsOf(head).center().x;
        for (std::uint32_t t = 0; t < head.triangles.size(); ++t)
            cache.areaM2 += triangleArea(head, t);
    }
    if (std::string error = checkParameterValues(
            { { Param::Segments, shared.segments }, { Param::HairOffset, shared.hairOffsetMetres } });
        !error.empty())
        return { {}, error };
    if (regions.size() > 0xffff)
        return { {}, "regions: " + std::to_string(regions.size()) + " is more than 65535" };

    GroomResult result;
    Groom& groom = result.groom;
    groom.settings = shared;
    std::map<Cache::Key, std::shared_ptr<const PoreLayout>> used;
    std::unordered_map<std::uint32_t, std::vector<glm::vec3>> givenRest;
    for (std::size_t r = 0; r < regions.size(); ++r) {
        const GroomRegionInput& region = regions[r];
        const GroomSettings settings = mergedSettings(region.settings, shared, region.id);
        if (std::string error = validateGroomSettings(settings); !error.empty())
            return { {}, "region " + std::to_string(r + 1) + ": " + error };
        if (region.importedStrands) {
            if (!bvh)
                return { {},
                    "region " + std::to_string(r + 1) + ": imported strands need the head's BVH to be rooted" };
            groom.regionIds.push_back(region.id);
            groom.regionSettings.push_back(settings);
            groom.regionStiffnessScale.push_back(region.stiffnessScale);
            growImported(groom, *bvh, *region.importedStrands, settings, static_cast<std::uint16_t>(r), givenRest);
            continue;
        }
        if (region.weights.size() != head.positions.size())
            return { {},
                "region " + std::to_string(r + 1) + ": growth map has " + std::to_string(region.weights.size())
                    + " weights for " + std::to_string(head.positions.size()) + " vertices" };
        bool anyGrowth = false;
        for (std::size_t i = 0; i < region.weights.size(); ++i) {
            if (!std::isfinite(region.weights[i]))
                return { {},
                    "region " + std::to_string(r + 1) + ": growth map: weight " + std::to_string(i)
                        + " is not a finite number" };
            anyGrowth = anyGrowth || region.weights[i] > 0.0f;
        }
        // Bounded work: refuse densities that would place more than ~4 million strands.
        if (cache.areaM2 * settings.densityPerCm2 * 1e4 > 4.0e6)
            return { {},
                "density: " + std::to_string(settings.densityPerCm2) + " strands/cm² on "
                    + std::to_string(cache.areaM2 * 1e4) + " cm² would place more than 4 million strands" };
        groom.regionIds.push_back(region.id);
        groom.regionSettings.push_back(settings);
        groom.regionStiffnessScale.push_back(region.stiffnessScale);
        if (!anyGrowth)
            continue;
        const Cache::Key key{ settings.densityPerCm2, settings.wispSize, settings.seed };
        std::shared_ptr<const PoreLayout>& layout = used[key];
        if (!layout) {
            const auto found = cache.layouts.find(key);
            layout = found != cache.layouts.end()
                ? found->second
                : std::make_shared<const PoreLayout>(makePoreLayout(head, settings, m_maxPoreCandidates));
        }
        m_poreCandidates += layout->stats.candidates;
        if (layout->stats.capped) {
            char text[320];
            std::snprintf(text, sizeof text,
                "region %zu: density %g strands/cm² on the head's %.0f cm² needs %.0f pore candidates; capped "
                "at %zu, so the hair is sparser than asked",
                r + 1, static_cast<double>(settings.densityPerCm2), cache.areaM2 * 1e4, layout->stats.wantedCandidates,
                m_maxPoreCandidates);
            result.warnings.emplace_back(text);
        }
        growRegion(groom, head, *layout, region.weights, settings, static_cast<std::uint16_t>(r));
    }
    cache.layouts = std::move(used); // keep the layouts in use, drop the rest
    if (regions.size() == 1)
        groom.settings = groom.regionSettings.front();
    applyStyleLengths(groom, style);
    m_reused = buildRest(groom, { head, cache.normals, cache.partX, collider, &givenRest, style }, previous);
    m_built = groom.wispCount() - m_reused;
    return result;
}

GroomResult buildGroom(const TriangleMesh& head, std::span<const float> growthWeights, const GroomSettings& settings,
    const SignedDistanceField* collider)
{
    if (std::string error = validateMesh(head); !error.empty())
        return { {}, "head: " + error };
    if (std::string error = validateGroomSettings(settings); !error.empty())
        return { {}, error };
    if (growthWeights.size() != head.positions.size())
        return { {},
            "growth map: " + std::to_string(growthWeights.size()) + " weights for "
                + std::to_string(head.positions.size()) + " vertices" };
    bool anyGrowth = false;
    for (std::size_t i = 0; i < growthWeights.size(); ++i) {
        if (!std::isfinite(growthWeights[i]))
            return { {}, "growth map: weight " + std::to_string(i) + " is not a finite number" };
        anyGrowth = anyGrowth || growthWeights[i] > 0.0f;
    }
    if (!anyGrowth)
        return { {}, "growth map: every weight is 0, so no hair grows; paint where hair should grow" };
    const GroomRegionInput region{ 0, growthWeights, settings, 1.0f };
    GroomBuilder builder;
    GroomResult result = builder.build(head, std::span(&region, 1), settings, collider);
    if (result.ok() && result.groom.roots.empty())
        return { {}, "growth map: the painted area is too small or too faint for any strand at this density" };
    return result;
}

GroomResult buildGridGroom(const TriangleMesh& head, const MeshBvh& bvh, int width, int height, int particlesPerStrand,
    float lengthMetres, const SignedDistanceField* collider)
{
    if (std::string error = validateMesh(head); !error.empty())
        return { {}, "head: " + error };
    if (width < 1 || height < 1 || width * static_cast<long long>(height) > 4'000'000)
        return { {},
            "grid: " + std::to_string(width) + " x " + std::to_string(height) + " strands is not 1 .. 4 million" };
    if (std::string error = checkParameterValue(Param::Segments, particlesPerStrand - 1); !error.empty())
        return { {}, "grid: particles per strand: " + std::to_string(particlesPerStrand) + " is outside 3..128" };
    if (std::string error = checkParameterValue(Param::Length, lengthMetres); !error.empty())
        return { {}, error };

    GroomResult result;
    Groom& groom = result.groom;
    ParameterValues defaults;
    groom.settings = groomSettingsFrom(defaults);
    groom.settings.wispSize = 1;
    groom.settings.lengthMetres = lengthMetres;
    groom.settings.lengthVariation = 0.0f;
    groom.settings.segments = particlesPerStrand - 1;
    groom.settings.curlRadiusMetres = 0.0f;
    groom.settings.curlTurnsPerMetre = 0.0f;

    const Aabb box = boundsOf(head);
    // The cranium's centre: the upper part of the box, where a ray outward always crosses the scalp.
    const glm::vec3 centre(box.center().x, box.min.y + 0.6f * box.size().y, box.center().z);
    std::vector<glm::vec3> rootPositions;
    for (int j = 0; j < height; ++j) {
        // Polar angle from +Y: the top cap down to about 70 degrees, as a scalp grid.
        const float polar = glm::radians(8.0f + 62.0f * (static_cast<float>(j) + 0.5f) / static_cast<float>(height));
        for (int i = 0; i < width; ++i) {
            const float azimuth = glm::two_pi<float>() * (static_cast<float>(i) + 0.5f) / static_cast<float>(width);
            const glm::vec3 dir(
                std::sin(polar) * std::cos(azimuth), std::cos(polar), std::sin(polar) * std::sin(azimuth));
            const float far = 2.0f * glm::length(box.size());
            // Cast inward from outside so the outermost surface (the scalp) is found even when the
            // centre guess is not inside a closed mesh.
            const auto hit = bvh.raycast(centre + far * dir, -dir, far);
            const SurfacePoint sp = hit ? hit->surface : bvh.closestPoint(centre + 0.5f * box.size().y * dir).surface;
            groom.roots.push_back(sp);
            groom.rootIds.push_back(static_cast<std::uint32_t>(groom.roots.size() - 1));
            rootPositions.push_back(pointOn(head, sp));
            groom.lengths.push_back(lengthMetres);
            groom.wispOf.push_back(static_cast<std::uint32_t>(groom.keyStrand.size()));
            groom.siteOfWisp.push_back(static_cast<std::uint32_t>(groom.keyStrand.size()));
            groom.keyStrand.push_back(static_cast<std::uint32_t>(groom.roots.size() - 1));
            groom.regionOfStrand.push_back(0);
        }
    }
    groom.rootPositions = std::move(rootPositions);
    groom.regionIds = { 0 };
    groom.regionSettings = { groom.settings };
    groom.regionStiffnessScale = { 1.0f };
    const std::vector<glm::vec3> normals = vertexNormals(head);
    buildRest(groom, { head, normals, boundsOf(head).center().x, collider }, nullptr);
    return result;
}

std::vector<glm::vec3> resampleByArcLength(std::span<const glm::vec3> strand, std::size_t points)
{
    if (strand.size() < 2 || points < 2)
        return {};
    std::vector<float> along(strand.size(), 0.0f);
    for (std::size_t j = 1; j < strand.size(); ++j)
        along[j] = along[j - 1] + glm::distance(strand[j], strand[j - 1]);
    const float total = along.back();
    if (!(total > 1e-7f) || !std::isfinite(total))
        return {};
    std::vector<glm::vec3> out(points);
    std::size_t segment = 1;
    for (std::size_t i = 0; i < points; ++i) {
        const float target = total * static_cast<float>(i) / static_cast<float>(points - 1);
        while (segment + 1 < strand.size() && along[segment] < target)
            ++segment;
        const float span = along[segment] - along[segment - 1];
        const float t = span > 0.0f ? std::clamp((target - along[segment - 1]) / span, 0.0f, 1.0f) : 0.0f;
        out[i] = glm::mix(strand[segment - 1], strand[segment], t);
    }
    out.front() = strand.front();
    out.back() = strand.back();
    return out;
}

HairCurves keyRestCurves(const Groom& groom)
{
    HairCurves keys;
    keys.offsets.reserve(groom.wispCount() + 1);
    for (std::uint32_t k : groom.keyStrand) {
        const std::span<const glm::vec3> src = groom.rest.strand(k);
        const std::size_t index = keys.addStrand(static_cast<std::uint32_t>(src.size()));
        std::copy(src.begin(), src.end(), keys.strandForWrite(index).begin());
    }
    return keys;
}

void buildMembers(const Groom& groom, std::span<const glm::vec3> keyPositions, const glm::mat3& headRotation,
    HairCurves& out, std::span<const float> wetClumpOfWisp, const MemberContact* contact)
{
    const std::size_t points = static_cast<std::size_t>(groom.settings.segments) + 1;
    const std::vector<std::vector<std::uint32_t>> members = membersOfWisps(groom);
    MemberFix fix;
    if (contact)
        fix = [&](std::uint32_t strand, std::span<glm::vec3> p) {
            keepMemberShape(groom.rest.strand(strand), *contact, p);
        };
    for (std::size_t w = 0; w < groom.wispCount(); ++w)
        buildWispMembers(groom, w, members[w], keyPositions.subspan(w * points, points), headRotation, out,
            w < wetClumpOfWisp.size() ? wetClumpOfWisp[w] : 0.0f, fix);
}

namespace {

// Point p, `depth` inside a surface of outward unit normal n, turned about `parent` onto the
// surface's tangent plane keeping its distance `length` from the parent (as the solver's contact
// does); with `push`, whatever the turn cannot reach is pushed out along n, less `slack`.
glm::vec3 turnedOut(
    const glm::vec3& parent, const glm::vec3& p, const glm::vec3& n, float depth, float length, bool push, float slack)
{
    const glm::vec3 u = (p - parent) / glm::max(glm::distance(p, parent), 1e-9f);
    const float along = glm::dot(n, u);
    const float reach = std::min(depth / length + along, 1.0f);
    glm::vec3 side = u - n * along;
    const float sl = glm::length(side);
    side = sl > 1e-9f ? side / sl : glm::vec3(0.0f);
    const glm::vec3 turned = parent + (n * reach + side * std::sqrt(std::max(1.0f - reach * reach, 0.0f))) * length;
    return turned + n * (push ? std::max(depth - slack - glm::dot(turned - p, n), 0.0f) : 0.0f);
}

} // namespace

void keepMemberShape(std::span<const glm::vec3> rest, const MemberContact& contact, std::span<glm::vec3> points)
{
    constexpr int kMemberContactPasses = 4;
    constexpr int kArcBisections = 6;
    // Signed distance above the kept offset (negative: too close or inside) and the outward unit
    // normal, both in frame space.
    auto clearanceAt = [&](const glm::vec3& p) {
        const glm::vec3 local = glm::transpose(contact.headRotation) * (p - contact.headTranslation);
        return contact.head->distance(local) - contact.offsetMetres;
    };
    auto normalAt = [&](const glm::vec3& p) {
        const glm::vec3 local = glm::transpose(contact.headRotation) * (p - contact.headTranslation);
        const glm::vec3 n = contact.headRotation * contact.head->gradient(local);
        const float nl = glm::length(n);
        return nl > 1e-9f ? n / nl : glm::vec3(0, 1, 0);
    };
    // Follow the leader along the member's own guide (Müller et al. 2012): each point at its rest
    // length from the one before, toward where the key put it; then out of the head and the body,
    // turned about the point before so the length holds.
    for (std::size_t j = 1; j < points.size() && j < rest.size(); ++j) {
        const float length = glm::distance(rest[j], rest[j - 1]);
        const float slack = length < 2.0f * contact.offsetMetres ? contact.offsetMetres : 0.0f;
        const glm::vec3 parent = points[j - 1];
        const glm::vec3 d = points[j] - parent;
        const float dl = glm::length(d);
        glm::vec3 p = parent + (dl > 1e-9f ? d / dl : glm::normalize(rest[j] - rest[j - 1])) * length;
        if (contact.head) {
            // Newton on the sphere of radius `length` about the parent: turn onto the tangent plane,
            // look again from there (a nose, an ear is not its tangent plane), a few times.
            float clearance = clearanceAt(p);
            for (int pass = 0; clearance < 0.0f && pass < kMemberContactPasses; ++pass) {
                p = turnedOut(parent, p, normalAt(p), -clearance, length, false, 0.0f);
                clearance = clearanceAt(p);
            }
            // Where that does not converge (a crevice between an ear and the skull, where the
            // normal flips from wall to wall), turn along the great circle from where the point
            // is toward the parent's own outward normal, and take the first clear point on that
            // arc (bisection): the length still holds. Only a point that no turn gets out of the
            // skin itself (its parent is too deep) is pushed out and the segment gives way.
            if (clearance < -slack) {
                const glm::vec3 from = (p - parent) / length;
                const glm::vec3 to = normalAt(parent);
                auto onArc = [&](float t) {
                    const glm::vec3 v = glm::mix(from, to, t);
                    const float vl = glm::length(v);
                    return parent + (vl > 1e-6f ? v / vl : to) * length;
                };
                const glm::vec3 end = onArc(1.0f);
                const float endClearance = clearanceAt(end);
                if (endClearance >= -slack) {
                    float lo = 0.0f, hi = 1.0f;
                    for (int b = 0; b < kArcBisections; ++b) {
                        const float mid = 0.5f * (lo + hi);
                        (clearanceAt(onArc(mid)) >= -slack ? hi : lo) = mid;
                    }
                    p = onArc(hi);
                } else {
                    if (endClearance > clearance) {
                        p = end;
                        clearance = endClearance;
                    }
                    if (clearance < -contact.offsetMetres)
                        p += normalAt(p) * (-contact.offsetMetres - clearance);
                }
            }
        }
        // The body's capsules are exact: one look each.
        for (const Capsule& capsule : contact.body) {
            const glm::vec3 ab = capsule.b - capsule.a;
            const float ab2 = glm::dot(ab, ab);
            const float t = ab2 > 0.0f ? std::clamp(glm::dot(p - capsule.a, ab) / ab2, 0.0f, 1.0f) : 0.0f;
            const glm::vec3 away = p - (capsule.a + ab * t);
            const float distance = glm::length(away);
            const float depth = capsule.radiusMetres + contact.offsetMetres - distance;
            if (depth > 0.0f && distance > 1e-9f)
                p = turnedOut(parent, p, away / distance, depth, length, true, slack);
        }
        points[j] = p;
    }
}

namespace {

// Writes wisp w's key (from `key`) and its members into `out` (Lee et al.: members follow their key
// hair, clumping toward it by clump-degree from clump-rate on).
void buildWispMembers(const Groom& groom, std::size_t w, std::span<const std::uint32_t> members,
    std::span<const glm::vec3> key, const glm::mat3& headRotation, HairCurves& out, float wetClump,
    const MemberFix& keepShape)
{
    const GroomSettings& s = groom.settingsOfWisp(w);
    // Wet hair clumps: the clump degree moves toward 1 and clumping starts nearer the root.
    const float clumpDegree = s.clumpDegree + (1.0f - s.clumpDegree) * wetClump;
    const float clumpRate = s.clumpRate * (1.0f - wetClump);
    const std::size_t points = key.size();
    const std::uint32_t k = groom.keyStrand[w];
    std::span<glm::vec3> keyOut = out.strandForWrite(k);
    if (keyOut.data() != key.data())
        std::copy(key.begin(), key.end(), keyOut.begin());
    if (members.size() < 2)
        return;
    // Parallel transport along the key: a member's root offset turns with the key's tangent, so
    // members stay beside their key wherever the key bends. Offsets are measured between rest roots
    // in head space.
    thread_local std::vector<glm::mat3> transport;
    thread_local std::vector<glm::vec3> tangent;
    transport.resize(points);
    tangent.resize(points);
    for (std::size_t j = 0; j < points; ++j) {
        const std::size_t a = j == 0 ? 0 : j - 1;
        const std::size_t b = std::min(j + 1, points - 1);
        const glm::vec3 d = key[b] - key[a];
        const float len = glm::length(d);
        tangent[j] = len > 1e-9f ? d / len : (j > 0 ? tangent[j - 1] : glm::vec3(0, 1, 0));
        transport[j] = j == 0 ? headRotation : shortestArcMatrix(tangent[j - 1], tangent[j]) * transport[j - 1];
    }
    const float keyLength = groom.lengths[k];
    const glm::vec3 keyRoot = groom.rootPositions[k];
    for (std::uint32_t m : members) {
        if (m == k)
            continue;
        const glm::vec3 rootOffset = groom.rootPositions[m] - keyRoot;
        std::span<glm::vec3> dst = out.strandForWrite(m);
        const float scale = groom.lengths[m] / keyLength;
        for (std::size_t j = 0; j < points; ++j) {
            const float u = static_cast<float>(j) / static_cast<float>(points - 1);
            const float f = u * scale * static_cast<float>(points - 1);
            glm::vec3 onKey;
            glm::mat3 frame;
            if (f >= static_cast<float>(points - 1)) { // longer than its key: continue along the tip
                const float beyond
                    = (f - static_cast<float>(points - 1)) * glm::distance(key[points - 1], key[points - 2]);
                onKey = key[points - 1] + beyond * tangent[points - 1];
                frame = transport[points - 1];
            } else {
                const auto j0 = static_cast<std::size_t>(f);
                const float t = f - static_cast<float>(j0);
                onKey = glm::mix(key[j0], key[j0 + 1], t);
                frame = t < 0.5f ? transport[j0] : transport[j0 + 1];
            }
            dst[j] = onKey + (1.0f - clumpAt(u, clumpDegree, clumpRate)) * (frame * rootOffset);
        }
        if (keepShape)
            keepShape(m, dst);
    }
}

} // namespace

} // namespace wisp
