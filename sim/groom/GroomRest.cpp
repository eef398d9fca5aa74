#include "sim/groom/GroomRest.h"
#include "sim/groom/PoreLayout.h"
#include "sim/groom/WispMembers.h"

#include "sim/geometry/ShortestArc.h"

#include "sim/geometry/SignedDistanceField.h"
#include "sim/util/Random.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>

namespace wisp::groom_detail {
namespace {

using enum Stream;

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

// The normal of the head at a surface point, interpolated from vertex normals.
glm::vec3 normalAt(const TriangleMesh& head, const std::vector<glm::vec3>& normals, const SurfacePoint& sp)
{
    const glm::uvec3 tri = head.triangles[sp.triangle];
    const float b0 = 1.0f - sp.barycentric.x - sp.barycentric.y;
    const glm::vec3 n = b0 * normals[tri.x] + sp.barycentric.x * normals[tri.y] + sp.barycentric.y * normals[tri.z];
    return glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0, 1, 0);
}

std::uint64_t styleHashOf(const Groom& groom, std::size_t strand)
{
    return strand < groom.styleHash.size() ? groom.styleHash[strand] : 0;
}

} // namespace

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

} // namespace wisp::groom_detail
