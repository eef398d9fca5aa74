#pragma once
// The viewport's camera, as in DCC tools: it orbits a pivot at some distance, +Y up. Pure math and
// no Qt or GL, so the viewport's mouse handling and the tests share one definition of the view.
//
// Angles are radians, distances metres, screen quantities pixels.
//
// Thread: GUI (owned by the viewport).

#include "sim/geometry/TriangleMesh.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace wisp {

class OrbitCamera {
public:
    // A pleasant 3/4 view of a face that looks toward +Z: from front-left-above.
    static constexpr float kDefaultYawRadians = 0.61f; // ~35° around +Y, from +Z toward +X
    static constexpr float kDefaultPitchRadians = 0.21f; // ~12° above the pivot
    static constexpr float kDefaultFovYDegrees = 35.0f; // a portrait lens: little distortion of the face
    static constexpr float kMaxPitchRadians = 1.55f; // just short of the poles, where yaw degenerates

    glm::vec3 pivot() const { return m_pivot; }
    float yaw() const { return m_yaw; }
    float pitch() const { return m_pitch; }
    float distance() const { return m_distance; }
    float fovYDegrees() const { return m_fovYDegrees; }

    void setPivot(const glm::vec3& pivotMetres) { m_pivot = pivotMetres; }
    void setOrientation(float yawRadians, float pitchRadians);
    void setDistance(float metres);
    void setFovYDegrees(float degrees);

    glm::vec3 eye() const; // world space, metres
    glm::vec3 forward() const; // unit, from the eye toward the pivot
    glm::vec3 right() const; // unit, screen right
    glm::vec3 up() const; // unit, screen up

    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const; // aspect = width / height
    glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }
    float nearPlane() const; // metres; follow the distance so zooming keeps depth precision
    float farPlane() const;

    // World point -> widget pixel (origin top-left, y down) in a viewport of `size` pixels. Also
    // reports whether the point is in front of the camera.
    glm::vec2 project(const glm::vec3& worldMetres, const glm::vec2& viewportSizePixels, bool* inFront = nullptr) const;

    // Mouse gestures. Orbit: dragging right turns the view as if grabbing the scene and spinning it
    // to the right; dragging up looks from further below.
    void orbit(float dxPixels, float dyPixels);
    // Moves the pivot in the view plane so the point under the cursor at the pivot's depth follows it.
    void pan(float dxPixels, float dyPixels, float viewportHeightPixels);
    // Wheel: positive steps move toward the pivot (one step = one notch, 120 eighths of a degree).
    void zoom(float steps);
    // Dolly by a vertical drag: up moves closer.
    void dolly(float dyPixels);

    // Looks at `bounds` from the current direction, at the distance where its bounding sphere fits
    // the narrower of the two fields of view with a small margin.
    void frame(const Aabb& bounds, float aspect);
    // The start-up view: default orientation and field of view, then frame(bounds).
    void reset(const Aabb& bounds, float aspect);

    static constexpr float kOrbitRadiansPerPixel = 0.008f;
    static constexpr float kZoomPerStep = 0.85f; // distance factor per wheel notch
    static constexpr float kMinDistance = 0.02f; // metres: close enough to see single strands
    static constexpr float kMaxDistance = 50.0f;

private:
    glm::vec3 m_pivot{ 0.0f };
    float m_yaw = kDefaultYawRadians;
    float m_pitch = kDefaultPitchRadians;
    float m_distance = 1.0f;
    float m_fovYDegrees = kDefaultFovYDegrees;
};

} // namespace wisp
