#include "sim/groom/Groom.h"
#include "sim/groom/GroomRest.h"
#include "sim/groom/PoreLayout.h"
#include "sim/groom/WispMembers.h"

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
#include <tuple>
#include <unordered_map>

namespace wisp {
namespace {

using groom_detail::buildRest;
using groom_detail::buildWispMembers;
using groom_detail::makePoreLayout;
using groom_detail::membersOfWisps;
using groom_detail::Pore;
using groom_detail::PoreLayout;
using groom_detail::RestContext;
using enum groom_detail::Stream;

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

} // namespace wisp
