#include "sim/solver/HairVolumeGrid.h"

#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace wisp {

namespace {
// body(begin, end) over [0, count): on the pool, or on the calling thread when there is none.
void forRange(
    ThreadPool* pool, std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body)
{
    if (pool)
        pool->parallelFor(count, grain, body);
    else if (count > 0)
        body(0, count);
}
} // namespace

bool HairVolumeGrid::setBounds(const glm::vec3& lo, const glm::vec3& hi)
{
    m_nodes.clear();
    m_hairDensity.clear();
    m_solid.clear();
    m_chunks.clear();
    m_touched.clear();
    m_live.clear();
    m_liveList.clear();
    m_dims = glm::ivec3(0);
    const glm::vec3 size = hi - lo;
    if (!(std::isfinite(size.x) && std::isfinite(size.y) && std::isfinite(size.z)) || !(size.x > 0.0f)
        || !(size.y > 0.0f) || !(size.z > 0.0f) || !(glm::length(size) < 1e3f))
        return false;
    // The finest cell whose nodes (one more than the cells each way) fit the memory bound.
    const std::size_t maxNodes = kMaxBytes / kBytesPerNode;
    float cell = std::max(kFinestCellMetres, std::cbrt(size.x * size.y * size.z / static_cast<float>(maxNodes)));
    glm::ivec3 dims;
    for (;;) {
        dims = glm::ivec3(glm::ceil(size / cell)) + 2; // and a node beyond each end
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
    m_hairDensity.assign(count, 0.0f);
    m_solid.assign(count, 0.0f);
    m_chunks.assign(count * kSplatChunks, Accumulator{});
    m_bricks = (dims + kBrick - 1) / kBrick;
    const std::size_t bricks = static_cast<std::size_t>(m_bricks.x) * m_bricks.y * m_bricks.z;
    m_live.assign(bricks, 0);
    m_touched.assign(bricks * kSplatChunks, 0);
    return true;
}

std::size_t HairVolumeGrid::memoryBytes() const
{
    return m_nodes.capacity() * sizeof(Node) + (m_hairDensity.capacity() + m_solid.capacity()) * sizeof(float)
        + m_chunks.capacity() * sizeof(Accumulator) + m_touched.capacity() + m_live.capacity()
        + m_liveList.capacity() * sizeof(std::uint32_t);
}

void HairVolumeGrid::setSolid(const std::function<float(const glm::vec3&)>& signedDistance)
{
    for (int k = 0; k < m_dims.z; ++k)
        for (int j = 0; j < m_dims.y; ++j)
            for (int i = 0; i < m_dims.x; ++i) {
                const float d = signedDistance(m_origin + m_cell * glm::vec3(i, j, k));
                m_solid[index(i, j, k)] = std::clamp(0.5f - d / m_cell, 0.0f, 1.0f);
            }
}

template <typename Fn> void HairVolumeGrid::forNodesOf(std::size_t brick, Fn&& fn) const
{
    const int bx = static_cast<int>(brick % static_cast<std::size_t>(m_bricks.x));
    const int by
        = static_cast<int>((brick / static_cast<std::size_t>(m_bricks.x)) % static_cast<std::size_t>(m_bricks.y));
    const int bz = static_cast<int>(brick / (static_cast<std::size_t>(m_bricks.x) * m_bricks.y));
    for (int k = bz * kBrick; k < std::min((bz + 1) * kBrick, m_dims.z); ++k)
        for (int j = by * kBrick; j < std::min((by + 1) * kBrick, m_dims.y); ++j)
            for (int i = bx * kBrick; i < std::min((bx + 1) * kBrick, m_dims.x); ++i)
                fn(i, j, k, index(i, j, k));
}

void HairVolumeGrid::clear(ThreadPool* pool)
{
    forRange(pool, kSplatChunks, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c)
            clearChunk(static_cast<int>(c));
    });
}

void HairVolumeGrid::clearChunk(int chunk)
{
    const std::size_t count = m_nodes.size(), bricks = m_live.size();
    Accumulator* a = m_chunks.data() + static_cast<std::size_t>(chunk) * count;
    std::uint8_t* touched = m_touched.data() + static_cast<std::size_t>(chunk) * bricks;
    for (std::size_t b = 0; b < bricks; ++b)
        if (touched[b]) {
            forNodesOf(b, [&](int, int, int, std::size_t n) { a[n] = Accumulator{ 0.0f, 0.0f, 0.0f, 0.0f }; });
            touched[b] = 0;
        }
}

void HairVolumeGrid::finish(ThreadPool* pool, float solidDensity)
{
    const std::size_t count = m_nodes.size(), bricks = m_live.size();
    // The bricks any chunk touched; the nodes of bricks touched last time and not now go empty.
    std::vector<std::uint32_t> now;
    for (std::size_t b = 0; b < bricks; ++b) {
        bool any = false;
        for (int c = 0; c < m_activeChunks && !any; ++c)
            any = m_touched[static_cast<std::size_t>(c) * bricks + b] != 0;
        if (any)
            now.push_back(static_cast<std::uint32_t>(b));
    }
    for (const std::uint32_t b : m_liveList)
        m_live[b] = 0;
    for (const std::uint32_t b : now)
        m_live[b] = 1;
    for (const std::uint32_t b : m_liveList)
        if (!m_live[b])
            forNodesOf(b, [&](int, int, int, std::size_t n) {
                m_nodes[n] = Node{};
                m_hairDensity[n] = 0.0f;
            });
    m_liveList = std::move(now);
    m_solidDensity = solidDensity;

    // First the sums (every live node), then what sample() reads, which takes the neighbours' sums.
    const float perVolume = 1.0f / (m_cell * m_cell * m_cell);
    forRange(pool, m_liveList.size(), 4, [&](std::size_t begin, std::size_t end) {
        for (std::size_t l = begin; l < end; ++l)
            forNodesOf(m_liveList[l], [&](int, int, int, std::size_t n) {
                Accumulator sum{ 0.0f, 0.0f, 0.0f, 0.0f };
                for (int c = 0; c < m_activeChunks; ++c) { // always in chunk order: the same bits on any thread count
                    const Accumulator& a = m_chunks[static_cast<std::size_t>(c) * count + n];
                    sum.weight += a.weight;
                    sum.moveX += a.moveX;
                    sum.moveY += a.moveY;
                    sum.moveZ += a.moveZ;
                }
                Node& node = m_nodes[n];
                node.weight = sum.weight;
                node.moveX = sum.moveX;
                node.moveY = sum.moveY;
                node.moveZ = sum.moveZ;
                m_hairDensity[n] = sum.weight * perVolume;
            });
    });
    const float inv2h = 0.5f / m_cell;
    forRange(pool, m_liveList.size(), 4, [&](std::size_t begin, std::size_t end) {
        for (std::size_t l = begin; l < end; ++l)
            forNodesOf(m_liveList[l], [&](int i, int j, int k, std::size_t n) {
                Node& node = m_nodes[n];
                node.density = m_hairDensity[n] + m_solid[n] * m_solidDensity;
                node.gradX = (densityAt(i + 1, j, k) - densityAt(i - 1, j, k)) * inv2h;
                node.gradY = (densityAt(i, j + 1, k) - densityAt(i, j - 1, k)) * inv2h;
                node.gradZ = (densityAt(i, j, k + 1) - densityAt(i, j, k - 1)) * inv2h;
            });
    });
}

double HairVolumeGrid::totalWeight() const
{
    double sum = 0.0;
    for (const Node& n : m_nodes)
        sum += n.weight;
    return sum;
}

} // namespace wisp
