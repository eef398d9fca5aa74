#pragma once
// The head as every part of Wisp reads it: the mesh (metres, head space, +Y up), its BVH (picking,
// the cut's line of sight, the groom's roots) and its vertex grid with one-ring adjacency (the
// growth brush, the X-mirror plane). Built once per head and then only read, so one
// shared_ptr<const HeadModel> is shared by the document, the brushes and the simulation, on any
// thread, several at once.

#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/ScalpBrush.h"

#include <glm/vec3.hpp>

#include <memory>
#include <optional>

namespace wisp {

class HeadModel {
public:
    // Builds the BVH and the brush grid: O(n log n), tens of ms for a 270k-triangle head.
    // Thread: any (the editor builds it where the head is replaced).
    explicit HeadModel(TriangleMesh mesh);
    HeadModel(const HeadModel&) = delete; // the BVH and grid are built for this mesh; share the pointer
    HeadModel& operator=(const HeadModel&) = delete;

    const TriangleMesh& mesh() const { return m_mesh; }
    const MeshBvh& bvh() const { return m_bvh; }
    const ScalpBrush& scalp() const { return m_scalp; }
    float mirrorPlaneX() const { return m_scalp.mirrorPlaneX(); } // metres: the brushes' X symmetry

    // Where a ray (head space, `direction` unit) first meets the head, and the face's unit normal
    // turned toward the ray's origin; nullopt when it misses within `maxDistanceMetres`.
    struct SurfaceHit {
        glm::vec3 point{ 0.0f };
        glm::vec3 normal{ 0.0f, 0.0f, 1.0f };
        float distanceMetres = 0.0f;
    };
    std::optional<SurfaceHit> hitAlong(
        const glm::vec3& origin, const glm::vec3& direction, float maxDistanceMetres = 1.0e4f) const;

private:
    TriangleMesh m_mesh;
    MeshBvh m_bvh;
    ScalpBrush m_scalp;
};

using HeadModelPtr = std::shared_ptr<const HeadModel>;

} // namespace wisp
