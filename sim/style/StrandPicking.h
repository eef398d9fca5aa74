#pragma once
// What the styling brushes touch: strands near the cursor's ray, strands crossed by a scissor
// stroke, and a strand dragged by the comb. Geometry only, on drawn strands (world space, metres).

#include "sim/geometry/HairCurves.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace wisp {

struct StrandPick {
    std::uint32_t strand = 0;
    float weight = 0.0f; // brush falloff at the strand's nearest point, 0..1
    float depth = 0.0f; // distance along the ray to that point, metres
};

// Strands (all of `curves`, or only those listed in `only`) with a point within `radiusMetres` of
// the ray origin + t direction, 0 < t < maxDepth (the head's surface under the cursor: hair behind
// the head is not touched). Weight by brushFalloff (ScalpBrush.h) of the nearest point's distance.
std::vector<StrandPick> strandsNearRay(const HairCurves& curves, std::span<const std::uint32_t> only,
    const glm::vec3& origin, const glm::vec3& direction, float radiusMetres, float falloff, float maxDepth);

struct StrandCut {
    std::uint32_t strand = 0;
    float lengthMetres = 0.0f; // arc length from the root to where the blade crosses it
};

// The scissors: the blade is the wedge swept from the eye between two view rays (one mouse move).
// Each strand that crosses it is cut at its first crossing from the root; `visible(point)` decides
// whether the artist can see the crossing (false: behind the head, not cut).
std::vector<StrandCut> strandsCutBy(const HairCurves& curves, const glm::vec3& eye, const glm::vec3& directionA,
    const glm::vec3& directionB, const std::function<bool(const glm::vec3&)>& visible);

// The comb: moves a strand's points by `delta` times `weight`, more toward the tip (the share of
// arc length from the root), then puts each segment back at its length (follow the leader), so the
// root stays and the strand does not stretch.
void combStrand(
    std::span<glm::vec3> positions, std::span<const float> segmentLengths, const glm::vec3& delta, float weight);

// The distance from p to the nearest point of the polyline (metres); huge for fewer than 2 points.
float distanceToPolyline(const glm::vec3& p, std::span<const glm::vec3> line);

// The ray mirrored across the plane x = planeX (the brushes' X symmetry).
glm::vec3 mirroredPoint(const glm::vec3& p, float planeX);
glm::vec3 mirroredDirection(const glm::vec3& d);

} // namespace wisp
