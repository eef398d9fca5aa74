#pragma once
// A volumetric grid of hair around the head, for hair-hair interaction (Petrovic, Henne & Anderson
// 2005, "Volumetric Methods for Simulation and Rendering of Hair"; McAdams, Selle, Ward, Sifakis &
// Teran 2009, "Detail Preserving Continuum Simulation of Straight Hair"): particles splat their
// weight (metres of drawn hair they stand for) and their move over the last substep into the nodes
// around them (trilinear, cloud-in-cell); the solver then reads back, at each particle, the hair
// density, the hairs' mean move there and the density's gradient.
//
// Deterministic for any thread count without atomics: splats go into a fixed number of chunk grids
// (each chunk always gets the same particles, summed in the same order), reduced in chunk order.
//
// Lives in head space, so it follows the head. Its resolution adapts to the box it is given, cells
// no finer than kFinestCellMetres, within a bound of kMaxBytes for all its arrays.
//
// Thread: one owner; splat() may be called concurrently for different chunks.

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace wisp {

class ThreadPool;

class HairVolumeGrid {
public:
    static constexpr int kSplatChunks = 8;
    static constexpr std::size_t kMaxBytes = std::size_t{ 32 } << 20; // 32 MiB
    static constexpr float kFinestCellMetres = 0.008f;

    // Lays nodes over [lo, hi] (head space, metres), as fine as the memory bound allows. False (and
    // an empty grid) when the box is not finite or empty.
    bool setBounds(const glm::vec3& lo, const glm::vec3& hi);
    bool empty() const { return m_nodes.empty(); }

    // The head as a solid in the grid (Petrovic et al. treat the body as solid too): each node's
    // share inside it, from the signed distance (metres, negative inside) at the node, ramped over
    // one cell. finish() counts a node's solid share as `solidDensity` of hair, so hair lying on the
    // skin is pushed out as by more hair beneath it, and the gradient there points away from the head.
    void setSolid(const std::function<float(const glm::vec3&)>& signedDistance);

    // Chunks in use (1..kSplatChunks): splat() takes chunk < this; fewer chunks, less to clear and
    // sum. Choose it from the work, never from the thread count, to keep the same bits.
    void setChunks(int chunks) { m_activeChunks = chunks < 1 ? 1 : chunks > kSplatChunks ? kSplatChunks : chunks; }
    int chunks() const { return m_activeChunks; }

    // Forgets the last splats (all chunks). `pool` null: on the calling thread (for few particles,
    // waking the pool costs more than the work).
    void clear(ThreadPool* pool);
    // The same for one chunk, on the calling thread: the chunk's splatting thread clears it first.
    void clearChunk(int chunk);
    // Adds `weight` and `weight * move` at head-space `p` to chunk `chunk` (0..kSplatChunks-1).
    // Points outside the grid add nothing.
    inline void splat(int chunk, const glm::vec3& p, float weight, const glm::vec3& move);
    // Sums the chunks in order and derives the density (weight / m³), the mean move and the
    // density gradient (central differences at nodes) that sample() reads.
    void finish(ThreadPool* pool, float solidDensity = 0.0f);

    struct Sample {
        float density = 0.0f; // weight per m³ (the head's solid counted as solidDensity)
        float hair = 0.0f; // interpolated weight of the hair splatted at the nodes around (0: no hair, no move)
        glm::vec3 move{ 0.0f }; // weighted mean move of the hair here
        glm::vec3 gradient{ 0.0f }; // d density / d position, head space, weight per m⁴
    };
    // Trilinear at head-space `p` over the eight nodes around it, of what finish() left at each node
    // (density, its central-difference gradient, the hair's move weighted by its weight); zeros
    // outside the grid. Continuous in `p`: a particle crossing a cell feels no jump (a nearest-node
    // read made curls jitter, README "Hair volume").
    inline Sample sample(const glm::vec3& p) const;
    float cellMetres() const { return m_cell; }
    glm::ivec3 dims() const { return m_dims; }
    glm::vec3 origin() const { return m_origin; }
    std::size_t memoryBytes() const;
    // Total weight splatted (after finish), for tests: a splat conserves it.
    double totalWeight() const;

    static constexpr std::size_t kBytesPerNode = kSplatChunks * 4 * sizeof(float) + 10 * sizeof(float);

private:
    struct Accumulator {
        float weight, moveX, moveY, moveZ;
    };
    // What sample() reads, eight floats: one node of a pair (x even, x odd) shares a cache line.
    struct alignas(32) Node {
        float density; // hair and head, weight per m³
        float gradX, gradY, gradZ; // its central differences, weight per m⁴
        float moveX, moveY, moveZ; // the hair's summed weight x move (momentum; divided in sample())
        float weight; // the hair's summed weight
    };
    // Hair and head at a node (clamped into the grid), for the central differences.
    float densityAt(int i, int j, int k) const
    {
        const std::size_t n
            = index(std::clamp(i, 0, m_dims.x - 1), std::clamp(j, 0, m_dims.y - 1), std::clamp(k, 0, m_dims.z - 1));
        return m_hairDensity[n] + m_solid[n] * m_solidDensity;
    }
    float m_solidDensity = 0.0f;
    std::size_t index(int i, int j, int k) const
    {
        return static_cast<std::size_t>(i)
            + static_cast<std::size_t>(m_dims.x)
            * (static_cast<std::size_t>(j) + static_cast<std::size_t>(m_dims.y) * k);
    }

    glm::ivec3 m_dims{ 0 };
    glm::vec3 m_origin{ 0.0f };
    float m_cell = 0.0f;
    std::vector<Accumulator> m_chunks; // kSplatChunks grids, one after the other
    std::vector<Node> m_nodes;
    std::vector<float> m_hairDensity; // per node: the hair's weight per m³ (0 outside the live bricks)
    std::vector<float> m_solid; // per node: 0..1 inside the head
    // Bricks of kBrick³ nodes: only those a splat touched are cleared, summed and differenced, so a
    // pass costs what the hair occupies, not the whole grid (the editor's 7,600 particles would
    // otherwise pay for 200,000 nodes in eight chunks).
    static constexpr int kBrick = 4;
    std::size_t brickIndex(int bx, int by, int bz) const
    {
        return static_cast<std::size_t>(bx)
            + static_cast<std::size_t>(m_bricks.x)
            * (static_cast<std::size_t>(by) + static_cast<std::size_t>(m_bricks.y) * bz);
    }
    template <typename Fn> void forNodesOf(std::size_t brick, Fn&& fn) const;
    glm::ivec3 m_bricks{ 0 };
    int m_activeChunks = kSplatChunks;
    std::vector<std::uint8_t> m_touched; // per chunk and brick: a splat of the chunk wrote there
    std::vector<std::uint8_t> m_live; // per brick: its nodes hold the last finish's sums
    std::vector<std::uint32_t> m_liveList;
};

inline void HairVolumeGrid::splat(int chunk, const glm::vec3& p, float weight, const glm::vec3& move)
{
    const glm::vec3 g = (p - m_origin) * (1.0f / m_cell);
    if (!(g.x >= 0.0f && g.y >= 0.0f && g.z >= 0.0f && g.x < static_cast<float>(m_dims.x - 1)
            && g.y < static_cast<float>(m_dims.y - 1) && g.z < static_cast<float>(m_dims.z - 1)))
        return; // outside, or not finite
    const int ix = static_cast<int>(g.x), iy = static_cast<int>(g.y), iz = static_cast<int>(g.z);
    const float fx = g.x - static_cast<float>(ix), fy = g.y - static_cast<float>(iy), fz = g.z - static_cast<float>(iz);
    Accumulator* a = m_chunks.data() + static_cast<std::size_t>(chunk) * m_nodes.size() + index(ix, iy, iz);
    const std::size_t strideY = static_cast<std::size_t>(m_dims.x),
                      strideZ = strideY * static_cast<std::size_t>(m_dims.y);
    std::uint8_t* touched = m_touched.data() + static_cast<std::size_t>(chunk) * m_live.size();
    // The bricks of the eight nodes: one, unless the cell's far corner is in the next brick.
    const int bx = ix / kBrick, by = iy / kBrick, bz = iz / kBrick;
    const int nx = (ix + 1) / kBrick - bx, ny = (iy + 1) / kBrick - by, nz = (iz + 1) / kBrick - bz;
    std::uint8_t* brick = touched + brickIndex(bx, by, bz);
    const std::size_t brickY = static_cast<std::size_t>(m_bricks.x),
                      brickZ = brickY * static_cast<std::size_t>(m_bricks.y);
    if ((nx | ny | nz) == 0)
        *brick = 1;
    else
        for (int z = 0; z <= nz; ++z)
            for (int y = 0; y <= ny; ++y)
                for (int x = 0; x <= nx; ++x)
                    brick[x + y * brickY + z * brickZ] = 1;
    const float wz[2] = { weight * (1.0f - fz), weight * fz };
    const float wy[2] = { 1.0f - fy, fy };
    const float wx[2] = { 1.0f - fx, fx };
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy) {
            Accumulator* row = a + dy * strideY + dz * strideZ;
            const float wyz = wz[dz] * wy[dy];
            for (int dx = 0; dx < 2; ++dx) {
                const float w = wyz * wx[dx];
                row[dx].weight += w;
                row[dx].moveX += w * move.x;
                row[dx].moveY += w * move.y;
                row[dx].moveZ += w * move.z;
            }
        }
}

inline HairVolumeGrid::Sample HairVolumeGrid::sample(const glm::vec3& p) const
{
    Sample s;
    const glm::vec3 g = (p - m_origin) * (1.0f / m_cell);
    if (!(g.x >= 0.0f && g.y >= 0.0f && g.z >= 0.0f && g.x < static_cast<float>(m_dims.x - 1)
            && g.y < static_cast<float>(m_dims.y - 1) && g.z < static_cast<float>(m_dims.z - 1)))
        return s; // outside, not finite, or no grid
    const int ix = static_cast<int>(g.x), iy = static_cast<int>(g.y), iz = static_cast<int>(g.z);
    const float fx = g.x - static_cast<float>(ix), fy = g.y - static_cast<float>(iy), fz = g.z - static_cast<float>(iz);
    const Node* base = m_nodes.data() + index(ix, iy, iz);
    const std::size_t strideY = static_cast<std::size_t>(m_dims.x),
                      strideZ = strideY * static_cast<std::size_t>(m_dims.y);
    const float wz[2] = { 1.0f - fz, fz }, wy[2] = { 1.0f - fy, fy }, wx[2] = { 1.0f - fx, fx };
    float sum[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy) {
            const Node* row = base + dy * strideY + dz * strideZ;
            const float wyz = wz[dz] * wy[dy];
            for (int dx = 0; dx < 2; ++dx) {
                const float w = wyz * wx[dx];
                const float* n = &row[dx].density;
                for (int f = 0; f < 8; ++f)
                    sum[f] += w * n[f];
            }
        }
    s.density = sum[0];
    s.gradient = glm::vec3(sum[1], sum[2], sum[3]);
    s.hair = sum[7];
    if (sum[7] > 0.0f)
        s.move = glm::vec3(sum[4], sum[5], sum[6]) * (1.0f / sum[7]);
    return s;
}

} // namespace wisp
