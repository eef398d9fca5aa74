#pragma once
// Collects vertices and polygons from any of the mesh readers and triangulates polygons as fans
// from their first corner (fine for the convex polygons modellers export; a concave one may fold).

#include "sim/geometry/TriangleMesh.h"

#include <cstddef>
#include <cstdint>

namespace wisp::io::mesh {

class MeshBuilder {
public:
    TriangleMesh mesh;
    std::size_t skippedFaces = 0; // faces that gave no triangle: fewer than 3 distinct corners

    // Corners must already be checked against the vertex count.
    void addPolygon(const std::uint32_t* corners, std::size_t count)
    {
        bool any = false;
        for (std::size_t i = 1; i + 1 < count; ++i)
            any |= addTriangle(corners[0], corners[i], corners[i + 1]);
        if (!any)
            ++skippedFaces;
    }

    // A triangle that repeats a vertex has no area and no normal: dropped. Strips use such
    // triangles on purpose to turn corners, so their caller does not count them as problems.
    bool addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c)
    {
        if (a == b || b == c || a == c)
            return false;
        mesh.triangles.emplace_back(a, b, c);
        return true;
    }
};

} // namespace wisp::io::mesh
