#pragma once
// Geometry of the viewport's scene guides, built on the CPU: the ground grid under the head, the
// wind arrow beside it and the paint brush's ring on the scalp. Pure C++ (no GL), so placement is
// tested without a context.
//
// Thread: any.

#include "sim/geometry/TriangleMesh.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <vector>

namespace wisp {

struct GuideVertex {
    glm::vec3 position; // world, metres
    glm::vec3 normal; // unit for solids, zero for lines
    glm::vec4 colour; // sRGB and alpha
};

struct GroundGrid {
    std::vector<GuideVertex> lines; // GL_LINES pairs
    glm::vec3 centre{ 0.0f }; // world, metres: on the floor under the head
    float fadeRadiusMetres = 0.0f; // the grid fades out toward this distance from the centre
};

// A grid on the plane y = head.min.y (the bottom of the head and neck), 5 cm squares with a
// brighter line every 25 cm, and the world's X and Z axes tinted red and blue where they cross it.
GroundGrid buildGroundGrid(const Aabb& head);

struct WindArrow {
    bool visible = false; // false for (nearly) still air or a non-finite wind
    glm::vec3 tail{ 0.0f }; // world, metres
    glm::vec3 tip{ 0.0f }; // the arrow points the way the wind blows
    std::vector<GuideVertex> triangles; // shaded solid: shaft and cone
};

// The arrow sits upwind of the head, pointing at it ("the wind comes from there"), at the height of
// the hair; its length grows with the speed (metres per m/s), up to a limit.
WindArrow buildWindArrow(const Aabb& head, const glm::vec3& windMetresPerSecond);

constexpr float kWindArrowMetresPerMps = 0.012f;
constexpr float kWindArrowMinMetres = 0.04f;
constexpr float kWindArrowMaxMetres = 0.30f;
constexpr float kStillAirMetresPerSecond = 1e-3f;

// The paint brush's footprint under the mouse, as the editor's paint tool found it on the head.
struct BrushCursor {
    glm::vec3 centre{ 0.0f }; // world, metres: where the cursor's ray meets the head
    glm::vec3 normal{ 0.0f, 1.0f, 0.0f }; // unit surface normal there
    float radiusMetres = 0.02f;
    bool erase = false; // the stroke removes weight: the ring is tinted red
    bool mirrored = false; // X-symmetric painting: a second, dimmer ring at mirrorCentre
    glm::vec3 mirrorCentre{ 0.0f };
    glm::vec3 mirrorNormal{ 0.0f, 1.0f, 0.0f };
    // The blow-dryer (sim/style/HairDryer.h): its cone of air from the nozzle (the apex) along the axis
    // to the ring, drawn translucent with its edges; the mirror dryer's is mirrored across the same
    // plane as the mirror ring (x), toward mirrorCentre.
    bool dryer = false;
    glm::vec3 dryerNozzle{ 0.0f }; // world, metres
    float dryerHalfAngleRadians = 0.35f;

    bool operator==(const BrushCursor&) const = default;
};

constexpr int kBrushRingSegments = 64;
// Lifted off the surface it lies on, so the head's own depth does not hide it.
constexpr float kBrushRingLiftMetres = 0.0005f;

// The brush ring(s) as GL_TRIANGLES: a band `bandMetres` wide centred on the circle of the brush's
// radius, in the plane perpendicular to the normal, lifted kBrushRingLiftMetres along it. The band
// width is the caller's, so it can keep the ring a constant width on screen (the mirror ring lies
// at another depth, hence its own width). White to add, red to erase; the mirror ring is dimmer
// (lower alpha). Empty for a non-finite cursor or a radius that is not positive.
std::vector<GuideVertex> buildBrushRings(const BrushCursor& cursor, float bandMetres, float mirrorBandMetres);

constexpr int kDryerConeSides = 32;
constexpr int kDryerConeEdges = 8; // lines from the nozzle to the rim, so the cone reads as one
// The dryer's cone as GL_TRIANGLES: a translucent surface from `nozzle` to the circle of the
// cone's radius at `aim` (perpendicular to nozzle -> aim), kDryerConeEdges edges `bandMetres`
// wide, and a small disc at the nozzle. Empty when nozzle and aim coincide or are not finite.
std::vector<GuideVertex> buildDryerCone(
    const glm::vec3& nozzle, const glm::vec3& aim, float halfAngleRadians, float bandMetres, float alpha);

} // namespace wisp
