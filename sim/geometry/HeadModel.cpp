#include "sim/geometry/HeadModel.h"

#include <glm/geometric.hpp>

namespace wisp {

HeadModel::HeadModel(TriangleMesh mesh)
    : m_mesh(std::move(mesh))
    , m_bvh(m_mesh)
    , m_scalp(m_mesh)
{
}

std::optional<HeadModel::SurfaceHit> HeadModel::hitAlong(
    const glm::vec3& origin, const glm::vec3& direction, float maxDistanceMetres) const
{
    const auto hit = m_bvh.raycast(origin, direction, maxDistanceMetres);
    if (!hit)
        return std::nullopt;
    const glm::uvec3 tri = m_mesh.triangles[hit->surface.triangle];
    const glm::vec3& a = m_mesh.positions[tri.x];
    glm::vec3 n = glm::cross(m_mesh.positions[tri.y] - a, m_mesh.positions[tri.z] - a);
    n = glm::length(n) > 0.0f ? glm::normalize(n) : -glm::normalize(direction);
    if (glm::dot(n, direction) > 0.0f) // the face seen from the origin
        n = -n;
    return SurfaceHit{ hit->point, n, hit->t * glm::length(direction) };
}

} // namespace wisp
