#pragma once
// Where a box falls on screen: the part of the viewport that a full-screen pass needs to cover when
// what it works on lies inside the box (the hair's half-resolution target: HairLowResTarget).
//
// Pure C++ (no GL): tested without a context. Thread: any.

#include "sim/geometry/TriangleMesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace wisp {

// A rectangle in clip-space x and y: (x0, y0) bottom left, (x1, y1) top right, within -1..1.
using ClipRect = glm::vec4;
inline constexpr ClipRect kWholeViewport{ -1.0f, -1.0f, 1.0f, 1.0f };

// The viewport rectangle that holds the projection of `box` (world space, projected by
// `viewProjection`), widened by `marginPixels` of a viewport `viewportPixels` big on every side and
// clipped to the viewport. The whole viewport when a corner lies at or behind the camera's plane
// (its projection has no bound there) or anything is not finite; an empty rectangle (x0 >= x1 or
// y0 >= y1) when the box lies wholly outside the view.
ClipRect clipRectOfBox(const Aabb& box, const glm::mat4& viewProjection, glm::vec2 viewportPixels, float marginPixels);

// `rect` widened by `pixels` on every side (of a viewport `viewportPixels` big), within -1..1.
ClipRect widenClipRect(ClipRect rect, glm::vec2 viewportPixels, float pixels);

inline bool clipRectEmpty(const ClipRect& rect)
{
    return !(rect.x < rect.z && rect.y < rect.w);
}

} // namespace wisp
