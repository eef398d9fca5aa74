#pragma once
// Geometry of the viewport's scene guides, built on the CPU: the ground grid under the head and the
// wind arrow beside it. Pure C++ (no GL), so placement is tested without a context.
//
// Thread: any.

#include "sim/TriangleMesh.h"

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

} // namespace wisp
