#pragma once
// A head (or any collider) as an indexed triangle mesh in metres, +Y up.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace wisp {

struct TriangleMesh {
    std::vector<glm::vec3> positions; // metres
    std::vector<glm::uvec3> triangles; // indices into positions, counter-clockwise seen from outside

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return triangles.size(); }
};

struct Aabb {
    glm::vec3 min{ 0.0f };
    glm::vec3 max{ 0.0f };
    glm::vec3 size() const { return max - min; }
    glm::vec3 center() const { return 0.5f * (min + max); }
};

// A point on the mesh surface: a triangle and barycentric weights (b1, b2) of its 2nd and 3rd vertex.
// The point is (1 - b1 - b2) * v0 + b1 * v1 + b2 * v2, so it follows the mesh when the mesh moves.
struct SurfacePoint {
    std::uint32_t triangle = 0;
    glm::vec2 barycentric{ 0.0f };
};

// Empty string when the mesh is usable for grooming and collision; otherwise what is wrong with it
// (no triangles, an index out of range, a non-finite coordinate).
[[nodiscard]] std::string validateMesh(const TriangleMesh& mesh);

Aabb boundsOf(const TriangleMesh& mesh);

// Area-weighted vertex normals (unit length; zero-area neighbourhoods get +Y).
std::vector<glm::vec3> vertexNormals(const TriangleMesh& mesh);

glm::vec3 pointOn(const TriangleMesh& mesh, const SurfacePoint& p);
glm::vec3 faceNormal(const TriangleMesh& mesh, std::uint32_t triangle); // unit, or zero if degenerate
float triangleArea(const TriangleMesh& mesh, std::uint32_t triangle); // square metres

// Interpolates a per-vertex scalar (a painted weight) at a surface point.
float interpolate(const TriangleMesh& mesh, const std::vector<float>& perVertex, const SurfacePoint& p);

} // namespace wisp
