#pragma once
// The head as the solver sees it: a regular grid of signed distances in metres (negative inside),
// read with trilinear interpolation. Baked once per head; immutable afterwards, so any number of
// threads may read it at once.

#include "sim/geometry/TriangleMesh.h"

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <memory>
#include <string>
#include <vector>

namespace wisp {

class ThreadPool;

class SignedDistanceField {
public:
    SignedDistanceField() = default;

    // Samples every `cellSize` metres over the mesh's bounds grown by `margin` metres on each side.
    // An empty field and a message in *error for an unusable mesh (see validateMesh), a cell size
    // or margin that is not a positive (non-negative) finite number, or a box larger than
    // kMaxExtentMetres. Grids past kMaxSamples samples are made coarser (the cell size grows)
    // without complaint, so memory stays bounded whatever is asked.
    // Runs on the calling thread and the pool's threads (the calling thread alone when `pool` is
    // null); the pool must not be running other work (ThreadPool::parallelFor is not reentrant).
    // The result is bit-identical whatever the number of threads.
    static SignedDistanceField bake(
        const TriangleMesh& mesh, float cellSize, float margin, std::string* error, ThreadPool* pool);
    // The same on a pool of `threadCount` threads made for this bake (0: one per hardware thread,
    // at most 64), for callers that have no pool of their own (tests, tools).
    static SignedDistanceField bake(
        const TriangleMesh& mesh, float cellSize, float margin, std::string* error = nullptr, int threadCount = 0);

    static constexpr std::size_t kMaxSamples = 256u * 256u * 256u;
    static constexpr float kMaxExtentMetres = 1.0e4f;
    // Samples within kBandCells cells of the surface hold exact distances (to float precision).
    // Farther samples hold a lower bound on |distance|, at most sqrt(3) cells short, that keeps
    // growing away from the surface and always has the right sign (the .cpp says why).
    static constexpr int kBandCells = 3;

    bool empty() const { return m_values.empty(); }

    // Trilinear signed distance, metres. Outside the grid: the distance to the grid's box plus the
    // nearest border sample, so it keeps growing away from the head. +infinity for an empty field
    // or a non-finite point (nothing to collide with).
    float distance(const glm::vec3& p) const;
    // Unit outward direction: central differences (half a cell apart) of the trilinear field.
    // Never NaN: where the field is flat it falls back to the direction from the grid's centre,
    // then to +Y.
    glm::vec3 gradient(const glm::vec3& p) const;

    // Raw access for the solver's vectorised lookups: sample (i, j, k) sits at
    // origin() + (i, j, k) * cellSize() and is data()[i + dims.x * (j + dims.y * k)].
    // Every dimension is at least 2 in a non-empty field.
    const float* data() const { return m_values.data(); }
    glm::ivec3 dims() const { return m_dims; }
    glm::vec3 origin() const { return m_origin; }
    float cellSize() const { return m_cellSize; }
    Aabb bounds() const; // the box the samples span

    // Sample (i, j, k) without interpolation; indices must be inside dims().
    float sample(int i, int j, int k) const
    {
        return m_values[static_cast<std::size_t>(i)
            + static_cast<std::size_t>(m_dims.x)
                * (static_cast<std::size_t>(j) + static_cast<std::size_t>(m_dims.y) * static_cast<std::size_t>(k))];
    }

    // Every sample's distance and unit outward normal, (distance, normal), laid out as data(): the
    // solver's nearest-sample lookups (Solver.cpp). The normal is the central difference of the
    // neighbouring samples (clamped at the grid's faces), +Y where that is flat. Built on first use
    // and kept with the field (copies share it), so every solver that collides with this head
    // reuses one table instead of building its own. Safe to call from any number of threads.
    const std::vector<glm::vec4>& samplesWithNormals() const;

private:
    struct NormalCache;
    std::vector<float> m_values;
    std::shared_ptr<NormalCache> m_normalCache; // made by bake; empty fields have none
    glm::ivec3 m_dims{ 0 };
    glm::vec3 m_origin{ 0.0f };
    float m_cellSize = 0.0f;
};

} // namespace wisp
