#pragma once
// Painting a per-vertex mask (a growth region's weights) with a spherical brush on the head.
//
// ScalpBrush is prepared once per head and then only read: every method is const, allocates nothing
// proportional to the mesh, and may run on any thread, several at once. A dab visits only the grid
// cells its sphere overlaps, so its cost follows the brush's footprint, not the head's vertex count.

#include "sim/geometry/TriangleMesh.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace wisp {

enum class BrushMode { Add, Erase, Smooth };

// The accepted ranges; validateBrush and the brush panel read them from here.
constexpr float kBrushRadiusMinMetres = 0.0005f;
constexpr float kBrushRadiusMaxMetres = 0.5f;

struct BrushSettings {
    float radiusMetres = 0.02f; // sphere of influence around the dab centre
    float strength = 0.5f; // 0..1: share of the way to the target per dab at the centre
    float falloff = 0.5f; // 0: full strength to the rim .. 1: smooth fall from the centre to 0 at the rim
    BrushMode mode = BrushMode::Add;
    bool mirrorX = true; // also dab at the centre mirrored across the plane x = mirrorPlaneX()
};

// Empty when usable; otherwise names the field and the problem
// ("brush radius: 0 is outside 0.0005..0.5 m", "brush strength: nan is not a finite number").
[[nodiscard]] std::string validateBrush(const BrushSettings& settings);

// The brush's weight at distance `distanceOverRadius` (0 at the centre, 1 at the rim) from the
// centre, 0..1. The inner (1 - falloff) of the radius gets full weight, the rest falls to 0 at the
// rim along a smoothstep; outside the sphere it is 0.
float brushFalloff(float distanceOverRadius, float falloff);

class ScalpBrush {
public:
    ScalpBrush() = default; // knows no vertices: every dab changes nothing
    // Builds the vertex grid and the one-ring adjacency: O(n log n), a few ms for 135k vertices.
    // Vertices with a non-finite position are left out of the grid (never painted); triangles with
    // an index out of range add no adjacency. The mirror plane is the x centre of the bounds of the
    // finite vertices.
    explicit ScalpBrush(const TriangleMesh& head);

    std::size_t vertexCount() const { return m_vertexCount; }
    float mirrorPlaneX() const { return m_mirrorPlaneX; } // metres

    // Applies one dab centred at `centre` (metres, a point on the surface) to `weights` (one per
    // vertex) and returns the indices of the vertices whose weight changed, sorted and unique, so
    // callers can regroom locally and record undo diffs.
    //
    // Each vertex within the radius moves toward its target (Add: 1, Erase: 0, Smooth: the mean of
    // its one-ring's weights before this dab) by strength * brushFalloff(distance / radius), and the
    // result is clamped to 0..1 (a non-finite weight counts as 0). With mirrorX the same dab is also
    // applied at the centre mirrored across x = mirrorPlaneX(); a vertex inside both spheres is moved
    // once, by the larger of the two influences.
    //
    // Refuses, changing nothing and returning an empty vector: settings that validateBrush rejects,
    // weights.size() != vertexCount(), a non-finite centre. Callers validate first to tell why.
    std::vector<std::uint32_t> dab(
        const glm::vec3& centre, const BrushSettings& settings, std::span<float> weights) const;

    // Vertices within radiusMetres of centre (distance <= radius), sorted; empty for a non-finite
    // centre or a negative radius. For tests and overlays.
    std::vector<std::uint32_t> verticesNear(const glm::vec3& centre, float radiusMetres) const;

private:
    // One grid entry: a vertex's position beside its index, stored in cell order so that scanning a
    // cell reads one contiguous run of 16-byte entries.
    struct GridVertex {
        glm::vec3 position{ 0.0f }; // metres
        std::uint32_t vertex = 0;
    };
    // An inclusive range of cell coordinates; empty when min > max on some axis.
    struct CellBox {
        glm::ivec3 min{ 0 };
        glm::ivec3 max{ -1 };
        bool contains(const glm::ivec3& c) const;
    };
    CellBox cellsAround(const glm::vec3& centre, float radiusMetres) const;
    template <typename Visit> void forEachVertexIn(const CellBox& box, const CellBox* skip, Visit&& visit) const;

    std::size_t m_vertexCount = 0;
    float m_mirrorPlaneX = 0.0f;

    // Uniform grid over the finite vertices' bounds: cell (x, y, z) holds
    // m_grid[m_cellStart[i] .. m_cellStart[i + 1]) with i = x + dims.x * (y + dims.y * z).
    glm::vec3 m_gridMin{ 0.0f }; // metres
    float m_cellMetres = 1.0f;
    glm::ivec3 m_gridDims{ 0 };
    std::vector<std::uint32_t> m_cellStart;
    std::vector<GridVertex> m_grid;

    // One-ring adjacency: vertex v's neighbours are m_ring[m_ringStart[v] .. m_ringStart[v + 1]).
    std::vector<std::uint32_t> m_ringStart;
    std::vector<std::uint32_t> m_ring;
};

} // namespace wisp
