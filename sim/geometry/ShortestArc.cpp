#include "sim/geometry/ShortestArc.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

glm::vec3 anyPerpendicular(const glm::vec3& n)
{
    const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(n, helper));
}

glm::vec3 rotateShortestArc(const glm::vec3& a, const glm::vec3& b, const glm::vec3& v)
{
    const glm::vec3 k = glm::cross(a, b);
    const float c = glm::dot(a, b);
    if (c < -0.9999f) { // opposite: a half-turn about any axis across a
        const glm::vec3 axis = anyPerpendicular(a);
        return 2.0f * glm::dot(v, axis) * axis - v;
    }
    return v * c + glm::cross(k, v) + k * (glm::dot(k, v) / (1.0f + c));
}

glm::mat3 shortestArcMatrix(const glm::vec3& a, const glm::vec3& b)
{
    return glm::mat3(rotateShortestArc(a, b, { 1, 0, 0 }), rotateShortestArc(a, b, { 0, 1, 0 }),
        rotateShortestArc(a, b, { 0, 0, 1 }));
}

glm::vec3 turnShortestArc(const glm::vec3& a, const glm::vec3& b, const glm::vec3& v, float share, float maxRadians)
{
    const glm::vec3 axis = glm::cross(a, b);
    const float sine = glm::length(axis);
    if (sine < 1e-7f)
        return v;
    const glm::vec3 k = axis / sine;
    const float angle = std::min(share * std::atan2(sine, glm::dot(a, b)), maxRadians);
    const float c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0f - c));
}

} // namespace wisp
