#include "widgets/OrbitCamera.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {
namespace {

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

void OrbitCamera::setOrientation(float yawRadians, float pitchRadians)
{
    if (!std::isfinite(yawRadians) || !std::isfinite(pitchRadians))
        return;
    // Keep yaw in (-pi, pi] so it does not grow without bound over a long session.
    m_yaw = std::remainder(yawRadians, 2.0f * glm::pi<float>());
    m_pitch = std::clamp(pitchRadians, -kMaxPitchRadians, kMaxPitchRadians);
}

void OrbitCamera::setDistance(float metres)
{
    if (std::isfinite(metres))
        m_distance = std::clamp(metres, kMinDistance, kMaxDistance);
}

void OrbitCamera::setFovYDegrees(float degrees)
{
    if (std::isfinite(degrees))
        m_fovYDegrees = std::clamp(degrees, 5.0f, 120.0f);
}

glm::vec3 OrbitCamera::forward() const
{
    const float cp = std::cos(m_pitch);
    // The eye sits at pivot + distance * (cp sin(yaw), sin(pitch), cp cos(yaw)); forward points back.
    return -glm::vec3(cp * std::sin(m_yaw), std::sin(m_pitch), cp * std::cos(m_yaw));
}

glm::vec3 OrbitCamera::right() const
{
    return glm::vec3(std::cos(m_yaw), 0.0f, -std::sin(m_yaw));
}

glm::vec3 OrbitCamera::up() const
{
    return glm::cross(right(), forward());
}

glm::vec3 OrbitCamera::eye() const
{
    return m_pivot - m_distance * forward();
}

glm::mat4 OrbitCamera::view() const
{
    return glm::lookAt(eye(), m_pivot, up());
}

float OrbitCamera::nearPlane() const
{
    return std::max(m_distance * 0.01f, 0.001f);
}

float OrbitCamera::farPlane() const
{
    return m_distance * 100.0f + 10.0f;
}

glm::mat4 OrbitCamera::projection(float aspect) const
{
    const float safeAspect = (std::isfinite(aspect) && aspect > 1e-4f) ? aspect : 1.0f;
    return glm::perspective(glm::radians(m_fovYDegrees), safeAspect, nearPlane(), farPlane());
}

glm::vec2 OrbitCamera::project(const glm::vec3& worldMetres, const glm::vec2& viewportSizePixels, bool* inFront) const
{
    const float aspect = viewportSizePixels.y > 0.0f ? viewportSizePixels.x / viewportSizePixels.y : 1.0f;
    const glm::vec4 clip = viewProjection(aspect) * glm::vec4(worldMetres, 1.0f);
    if (inFront)
        *inFront = clip.w > 0.0f;
    const float w = std::abs(clip.w) > 1e-12f ? clip.w : 1e-12f;
    const glm::vec2 ndc = glm::vec2(clip.x, clip.y) / w;
    return { (ndc.x * 0.5f + 0.5f) * viewportSizePixels.x, (0.5f - ndc.y * 0.5f) * viewportSizePixels.y };
}

void OrbitCamera::orbit(float dxPixels, float dyPixels)
{
    setOrientation(m_yaw - dxPixels * kOrbitRadiansPerPixel, m_pitch + dyPixels * kOrbitRadiansPerPixel);
}

void OrbitCamera::pan(float dxPixels, float dyPixels, float viewportHeightPixels)
{
    if (!(viewportHeightPixels > 0.0f))
        return;
    // Size of one pixel at the pivot's depth: the view's height there is 2 d tan(fov/2).
    const float metresPerPixel
        = 2.0f * m_distance * std::tan(glm::radians(m_fovYDegrees) * 0.5f) / viewportHeightPixels;
    const glm::vec3 moved = m_pivot + (-dxPixels * right() + dyPixels * up()) * metresPerPixel;
    if (finite(moved))
        m_pivot = moved;
}

void OrbitCamera::zoom(float steps)
{
    setDistance(m_distance * std::pow(kZoomPerStep, steps));
}

void OrbitCamera::dolly(float dyPixels)
{
    zoom(-dyPixels / 40.0f);
}

void OrbitCamera::frame(const Aabb& bounds, float aspect)
{
    if (!finite(bounds.min) || !finite(bounds.max))
        return;
    const float radius = std::max(0.5f * glm::length(bounds.size()), 0.01f);
    const float safeAspect = (std::isfinite(aspect) && aspect > 1e-4f) ? aspect : 1.0f;
    const float halfFovY = glm::radians(m_fovYDegrees) * 0.5f;
    const float halfFovX = std::atan(std::tan(halfFovY) * safeAspect);
    const float halfFov = std::min(halfFovY, halfFovX);
    // A bounding-box sphere is generous for a head (its corners are air), so the margin is small.
    constexpr float kMargin = 0.92f;
    m_pivot = bounds.center();
    setDistance(kMargin * radius / std::sin(halfFov));
}

void OrbitCamera::reset(const Aabb& bounds, float aspect)
{
    m_yaw = kDefaultYawRadians;
    m_pitch = kDefaultPitchRadians;
    m_fovYDegrees = kDefaultFovYDegrees;
    frame(bounds, aspect);
}

} // namespace wisp
