#include "sim/HairVolumeGrid.h"

#include "sim/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace wisp {

bool HairVolumeGrid::setBounds(const glm::vec3& lo, const glm::vec3& hi)
{
    m_nodes.clear();
    m_chunks.clear();
    m_solid.clear();
    m_dims = glm::ivec3(0);
    const glm::vec3 size = hi - lo;
    if (!(std::isfinite(size.x) && std::isfinite(size.y) && std::isfinite(size.z)) || !(size.x > 0.0f) ||
        !(size.y > 0.0f) || !(size.z > 0.0f) || !(glm::length(size) < 1e3f))
        return false;
    // The finest cell whose nodes (one more than the cells each way) fit the memory bound.
    const std::size_t maxNodes = kMaxBytes / kBytesPerNode;
    float cell = std::max(kFinestCellMetres, std::cbrt(size.x * size.y * size.z / static_cast<float>(maxNodes)));
    glm::ivec3 dims;
    for (;;) {
        dims = glm::ivec3(glm::ceil(size / cell)) + 2;  // and a node beyond each end
        if (static_cast<std::size_t>(dims.x) * dims.y * dims.z <= maxNodes)
            break;
        cell *= 1.02f;
    }
    m_cell = cell;
    m_dims = dims;
    // Centred on the box.
    m_origin = 0.5f * (lo + hi) - 0.5f * cell * glm::vec3(dims - 1);
    const std::size_t count = static_cast<std::size_t>(dims.x) * dims.y * dims.z;
    m_nodes.assign(count, Node{});
    m_chunks.assign(count * kSplatChunks, Accumulator{});
    return true;
}

std::size_t HairVolumeGrid::memoryBytes() const
{
    return m_nodes.capacity() * sizeof(Node) + m_chunks.capacity() * sizeof(Accumulator) + m_solid.capacity() * sizeof(float);
}

void HairVolumeGrid::setSolid(const std::function<float(const glm::vec3&)>& signedDistance)
{
    m_solid.assign(m_nodes.size(), 0.0f);
    for (int k = 0; k < m_dims.z; ++k)
        for (int j = 0; j < m_dims.y; ++j)
            for (int i = 0; i < m_dims.x; ++i) {
                const float d = signedDistance(m_origin + m_cell * glm::vec3(i, j, k));
                m_solid[index(i, j, k)] = std::clamp(0.5f - d / m_cell, 0.0f, 1.0f);
            }
}

void HairVolumeGrid::clear(ThreadPool& pool)
{
    const std::size_t count = m_nodes.size();
    pool.parallelFor(kSplatChunks, 1, [&](std::size_t begin, std::size_t end) {
        std::memset(static_cast<void*>(m_chunks.data() + begin * count), 0, (end - begin) * count * sizeof(Accumulator));
    });
}

void HairVolumeGrid::finish(ThreadPool& pool, float solidDensity)
{
    const bool solid = !m_solid.empty() && solidDensity > 0.0f;
    const std::size_t count = m_nodes.size();
    const float perVolume = 1.0f / (m_cell * m_cell * m_cell);
    pool.parallelFor(count, 4096, [&](std::size_t begin, std::size_t end) {
        for (std::size_t n = begin; n < end; ++n) {
            Accumulator sum{0.0f, 0.0f, 0.0f, 0.0f};
            for (int c = 0; c < kSplatChunks; ++c) {  // always in chunk order: the same bits on any thread count
                const Accumulator& a = m_chunks[static_cast<std::size_t>(c) * count + n];
                sum.weight += a.weight;
                sum.moveX += a.moveX;
                sum.moveY += a.moveY;
                sum.moveZ += a.moveZ;
            }
            Node& node = m_nodes[n];
            node.weight = sum.weight;
            node.density = sum.weight * perVolume + (solid ? m_solid[n] * solidDensity : 0.0f);
            const float inv = sum.weight > 0.0f ? 1.0f / sum.weight : 0.0f;
            node.moveX = sum.moveX * inv;
            node.moveY = sum.moveY * inv;
            node.moveZ = sum.moveZ * inv;
        }
    });
    // Central differences of the density at every node (one-sided at the border).
    const float inv2h = 0.5f / m_cell;
    pool.parallelFor(static_cast<std::size_t>(m_dims.z), 1, [&](std::size_t begin, std::size_t end) {
        for (int k = static_cast<int>(begin); k < static_cast<int>(end); ++k)
            for (int j = 0; j < m_dims.y; ++j)
                for (int i = 0; i < m_dims.x; ++i) {
                    auto at = [&](int x, int y, int z) {
                        return m_nodes[index(std::clamp(x, 0, m_dims.x - 1), std::clamp(y, 0, m_dims.y - 1),
                                             std::clamp(z, 0, m_dims.z - 1))]
                            .density;
                    };
                    Node& node = m_nodes[index(i, j, k)];
                    node.gradX = (at(i + 1, j, k) - at(i - 1, j, k)) * inv2h;
                    node.gradY = (at(i, j + 1, k) - at(i, j - 1, k)) * inv2h;
                    node.gradZ = (at(i, j, k + 1) - at(i, j, k - 1)) * inv2h;
                }
    });
}

HairVolumeGrid::Sample HairVolumeGrid::sample(const glm::vec3& p) const
{
    Sample s;
    if (m_nodes.empty())
        return s;
    const glm::vec3 g = (p - m_origin) / m_cell;
    if (!(g.x >= 0.0f && g.y >= 0.0f && g.z >= 0.0f && g.x < static_cast<float>(m_dims.x - 1) &&
          g.y < static_cast<float>(m_dims.y - 1) && g.z < static_cast<float>(m_dims.z - 1)))
        return s;
    const glm::ivec3 i(g);
    const glm::vec3 f = g - glm::vec3(i);
    const std::size_t strideY = static_cast<std::size_t>(m_dims.x), strideZ = strideY * m_dims.y;
    const std::size_t base = index(i.x, i.y, i.z);
    // The mean move is weighted by each node's hair, not only by distance: an empty node (no move)
    // must not pull the hair's mean toward rest.
    float moveWeight = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = c >> 2;
        const float w = (dx ? f.x : 1.0f - f.x) * (dy ? f.y : 1.0f - f.y) * (dz ? f.z : 1.0f - f.z);
        const Node& n = m_nodes[base + dx + dy * strideY + dz * strideZ];
        s.density += w * n.density;
        s.gradient += w * glm::vec3(n.gradX, n.gradY, n.gradZ);
        const float wm = w * n.weight;
        moveWeight += wm;
        s.move += wm * glm::vec3(n.moveX, n.moveY, n.moveZ);
    }
    if (moveWeight > 0.0f)
        s.move /= moveWeight;
    s.hair = moveWeight;
    return s;
}

double HairVolumeGrid::totalWeight() const
{
    double sum = 0.0;
    for (const Node& n : m_nodes)
        sum += n.weight;
    return sum;
}

}  // namespace wisp
