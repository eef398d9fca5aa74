#include "sim/geometry/TriangleMesh.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace wisp {

std::string validateMesh(const TriangleMesh& mesh)
{
    if (mesh.triangles.empty())
        return "the mesh has no triangles";
    if (mesh.positions.size() < 3)
        return "the mesh has fewer than 3 vertices";
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return "vertex " + std::to_string(i) + " has a non-finite coordinate";
    }
    const auto n = static_cast<std::uint32_t>(mesh.positions.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        if (tri.x >= n || tri.y >= n || tri.z >= n)
            return "triangle " + std::to_string(t) + " refers to a vertex past the last one (" + std::to_string(n)
                + " vertices)";
    }
    double area = 0.0;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
        area += triangleArea(mesh, t);
    if (!(area > 0.0))
        return "every triangle of the mesh has zero area";
    return {};
}

Aabb boundsOf(const TriangleMesh& mesh)
{
    if (mesh.positions.empty())
        return {};
    Aabb box{ mesh.positions.front(), mesh.positions.front() };
    for (const glm::vec3& p : mesh.positions) {
        box.min = glm::min(box.min, p);
        box.max = glm::max(box.max, p);
    }
    return box;
}

std::vector<glm::vec3> vertexNormals(const TriangleMesh& mesh)
{
    std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        const glm::vec3 n = glm::cross(b - a, c - a); // length = 2 * area: area weighting for free
        normals[t.x] += n;
        normals[t.y] += n;
        normals[t.z] += n;
    }
    for (glm::vec3& n : normals) {
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
}

glm::vec3 pointOn(const TriangleMesh& mesh, const SurfacePoint& p)
{
    const glm::uvec3 t = mesh.triangles[p.triangle];
    const float b0 = 1.0f - p.barycentric.x - p.barycentric.y;
    return b0 * mesh.positions[t.x] + p.barycentric.x * mesh.positions[t.y] + p.barycentric.y * mesh.positions[t.z];
}

glm::vec3 faceNormal(const TriangleMesh& mesh, std::uint32_t triangle)
{
    const glm::uvec3 t = mesh.triangles[triangle];
    const glm::vec3 n
        = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
    const float len = glm::length(n);
    return len > 0.0f ? n / len : glm::vec3(0.0f);
}

float triangleArea(const TriangleMesh& mesh, std::uint32_t triangle)
{
    const glm::uvec3 t = mesh.triangles[triangle];
    return 0.5f
        * glm::length(glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]));
}

float interpolate(const TriangleMesh& mesh, const std::vector<float>& perVertex, const SurfacePoint& p)
{
    const glm::uvec3 t = mesh.triangles[p.triangle];
    const float b0 = 1.0f - p.barycentric.x - p.barycentric.y;
    return b0 * perVertex[t.x] + p.barycentric.x * perVertex[t.y] + p.barycentric.y * perVertex[t.z];
}

} // namespace wisp
