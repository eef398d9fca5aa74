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

namespace {
// Eight floats, one AVX register: a pair of neighbouring nodes along x (splat), or one node (sample).
using Float8 = float __attribute__((vector_size(8 * sizeof(float))));
inline Float8 load8(const float* p)
{
    Float8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store8(float* p, Float8 v)
{
    std::memcpy(p, &v, sizeof v);
}
} // namespace

void HairVolumeGrid::cellsOf(const float* x, const float* y, const float* z, int count, CellRow& out) const
{
    // A whole row in a few vector instructions; a shorter one is padded with NaN (outside).
    using Floats = float __attribute__((vector_size(kRowLanes * sizeof(float))));
    using Ints = int __attribute__((vector_size(kRowLanes * sizeof(int))));
    Floats px, py, pz;
    if (count == kRowLanes) {
        std::memcpy(&px, x, sizeof px);
        std::memcpy(&py, y, sizeof py);
        std::memcpy(&pz, z, sizeof pz);
    } else {
        px = py = pz = Floats{} + NAN;
        for (int l = 0; l < count; ++l) {
            px[l] = x[l];
            py[l] = y[l];
            pz[l] = z[l];
        }
    }
    const float inverseCell = 1.0f / m_cell;
    const Floats gx = (px - m_origin.x) * inverseCell, gy = (py - m_origin.y) * inverseCell,
                 gz = (pz - m_origin.z) * inverseCell;
    const Ints inside = (gx >= 0.0f) & (gy >= 0.0f) & (gz >= 0.0f) & (gx < static_cast<float>(m_dims.x - 1))
        & (gy < static_cast<float>(m_dims.y - 1)) & (gz < static_cast<float>(m_dims.z - 1));
    const Floats zero{};
    const Ints ix = __builtin_convertvector(inside ? gx : zero, Ints),
               iy = __builtin_convertvector(inside ? gy : zero, Ints),
               iz = __builtin_convertvector(inside ? gz : zero, Ints);
    const Floats fx = inside ? gx - __builtin_convertvector(ix, Floats) : zero,
                 fy = inside ? gy - __builtin_convertvector(iy, Floats) : zero,
                 fz = inside ? gz - __builtin_convertvector(iz, Floats) : zero;
    const Ints node = inside ? ix + m_dims.x * (iy + m_dims.y * iz) : Ints{} - 1;
    std::memcpy(out.ix, &ix, sizeof ix);
    std::memcpy(out.iy, &iy, sizeof iy);
    std::memcpy(out.iz, &iz, sizeof iz);
    std::memcpy(out.fx, &fx, sizeof fx);
    std::memcpy(out.fy, &fy, sizeof fy);
    std::memcpy(out.fz, &fz, sizeof fz);
    std::memcpy(out.node, &node, sizeof node);
}

void HairVolumeGrid::splatRow(int chunk, const float* x, const float* y, const float* z, const float* weight,
    const float* moveX, const float* moveY, const float* moveZ, int count)
{
    CellRow cells;
    cellsOf(x, y, z, count, cells);
    float* const grid = &m_chunks[static_cast<std::size_t>(chunk) * m_nodes.size()].weight;
    const std::ptrdiff_t strideY = 4 * static_cast<std::ptrdiff_t>(m_dims.x),
                         strideZ = strideY * static_cast<std::ptrdiff_t>(m_dims.y);
    std::uint8_t* const touched = m_touched.data() + static_cast<std::size_t>(chunk) * m_live.size();
    const std::size_t brickY = static_cast<std::size_t>(m_bricks.x),
                      brickZ = brickY * static_cast<std::size_t>(m_bricks.y);
    // Side-by-side particles (a row's neighbouring strands) often share a cell: their adds are
    // summed in registers and written once per run of one cell, so they do not wait on each other
    // through memory. Always in lane order: the same bits every time.
    int runNode = -1, ix = 0, iy = 0, iz = 0;
    Float8 run[4] = {};
    auto flush = [&] {
        if (runNode < 0)
            return;
        // The bricks of the eight nodes: one, unless the cell's far corner is in the next brick.
        const int bx = ix / kBrick, by = iy / kBrick, bz = iz / kBrick;
        const int nx = (ix + 1) / kBrick - bx, ny = (iy + 1) / kBrick - by, nz = (iz + 1) / kBrick - bz;
        std::uint8_t* brick = touched + brickIndex(bx, by, bz);
        if ((nx | ny | nz) == 0)
            *brick = 1;
        else
            for (int k = 0; k <= nz; ++k)
                for (int j = 0; j <= ny; ++j)
                    for (int i = 0; i <= nx; ++i)
                        brick[i + j * brickY + k * brickZ] = 1;
        float* const base = grid + 4 * static_cast<std::ptrdiff_t>(runNode);
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy) {
                float* const pair = base + dy * strideY + dz * strideZ;
                store8(pair, load8(pair) + run[2 * dz + dy]);
            }
    };
    for (int l = 0; l < count; ++l) {
        const float w = weight[l];
        if (cells.node[l] < 0 || !(w > 0.0f))
            continue;
        if (cells.node[l] != runNode) {
            flush();
            runNode = cells.node[l];
            ix = cells.ix[l];
            iy = cells.iy[l];
            iz = cells.iz[l];
            run[0] = run[1] = run[2] = run[3] = Float8{};
        }
        // (weight, weight x move) at the low and the high node along x, in one register.
        const float fx = cells.fx[l], fy = cells.fy[l], fz = cells.fz[l];
        const Float8 value = Float8{ 1.0f, moveX[l], moveY[l], moveZ[l], 1.0f, moveX[l], moveY[l], moveZ[l] };
        const Float8 wx = Float8{ 1.0f - fx, 1.0f - fx, 1.0f - fx, 1.0f - fx, fx, fx, fx, fx };
        const float wz[2] = { w * (1.0f - fz), w * fz }, wy[2] = { 1.0f - fy, fy };
        for (int dz = 0; dz < 2; ++dz)
            for (int dy = 0; dy < 2; ++dy)
                run[2 * dz + dy] += (wz[dz] * wy[dy]) * wx * value;
    }
    flush();
}

void HairVolumeGrid::sampleRow(const float* x, const float* y, const float* z, SampleRow& out, int count) const
{
    CellRow cells;
    cellsOf(x, y, z, count, cells);
    const std::ptrdiff_t strideY = m_dims.x, strideZ = strideY * m_dims.y;
    for (int l = 0; l < count; ++l) {
        Float8 sum{};
        if (cells.node[l] >= 0) {
            const float fx = cells.fx[l], fy = cells.fy[l], fz = cells.fz[l];
            const float wz[2] = { 1.0f - fz, fz }, wy[2] = { 1.0f - fy, fy }, wx[2] = { 1.0f - fx, fx };
            const Node* const base = m_nodes.data() + cells.node[l];
            for (int dz = 0; dz < 2; ++dz)
                for (int dy = 0; dy < 2; ++dy) {
                    const Node* const row = base + dy * strideY + dz * strideZ;
                    const float wyz = wz[dz] * wy[dy];
                    sum += load8(&row[0].density) * (wyz * wx[0]);
                    sum += load8(&row[1].density) * (wyz * wx[1]);
                }
        }
        out.density[l] = sum[0];
        out.gradX[l] = sum[1];
        out.gradY[l] = sum[2];
        out.gradZ[l] = sum[3];
        out.momentumX[l] = sum[4];
        out.momentumY[l] = sum[5];
        out.momentumZ[l] = sum[6];
        out.hair[l] = sum[7];
    }
}

double HairVolumeGrid::totalWeight() const
{
    double sum = 0.0;
    for (const Node& n : m_nodes)
        sum += n.weight;
    return sum;
}

} // namespace wisp
