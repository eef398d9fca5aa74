// Member hairs from key hairs (sim/groom/WispMembers.h), the arc-length resampling the rest shapes
// use, and keeping a drawn member's shape out of the head and body (Groom.h: buildMembers).
#include "sim/groom/WispMembers.h"

#include "sim/geometry/ShortestArc.h"
#include "sim/geometry/SignedDistanceField.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace groom_detail {

float clumpAt(float u, float clumpDegree, float clumpRate)
{
    if (u <= clumpRate || clumpRate >= 1.0f)
        return 0.0f;
    const float x = (u - clumpRate) / (1.0f - clumpRate);
    return clumpDegree * x * x * (3.0f - 2.0f * x); // smoothstep: no kink where clumping starts
}

std::vector<std::vector<std::uint32_t>> membersOfWisps(const Groom& groom)
{
    std::vector<std::vector<std::uint32_t>> members(groom.wispCount());
    for (std::uint32_t i = 0; i < groom.strandCount(); ++i)
        members[groom.wispOf[i]].push_back(i);
    return members;
}

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

} // namespace groom_detail

using groom_detail::buildWispMembers;
using groom_detail::clumpAt;
using groom_detail::MemberFix;
using groom_detail::membersOfWisps;

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

HeadCurves keyRestCurves(const Groom& groom)
{
    HeadCurves keys;
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

} // namespace wisp
