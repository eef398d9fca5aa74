// Solver's per-strand edits and reads (Solver.h): one particle moved, per-strand scales and air,
// a strand's state and rest directions in and out, positions out.
#include "sim/solver/Solver.h"

#include "sim/solver/HairVolumeGrid.h"
#include "sim/solver/SolverBlockKernel.h"
#include "sim/solver/SolverRows.h"
#include "sim/util/ThreadPool.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace wisp {

void Solver::moveParticle(std::size_t strand, std::size_t point, const glm::vec3& position)
{
    if (strand >= m_slotOfStrand.size())
        return;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (point == 0 || point >= b.points)
        return;
    ParticleRow& row = b.state[point];
    m_volumeSplatted = false; // the grid's last splats are of the old state
    row.x[slot.lane] = row.px[slot.lane] = position.x;
    row.y[slot.lane] = row.py[slot.lane] = position.y;
    row.z[slot.lane] = row.pz[slot.lane] = position.z;
    row.clearance[slot.lane] = -1.0f;
}

std::string Solver::setStiffnessScales(std::span<const float> perStrand)
{
    if (perStrand.size() != m_strandCount)
        return "stiffness scales: " + std::to_string(perStrand.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < perStrand.size(); ++i)
        if (!(perStrand[i] >= 0.0f && perStrand[i] <= 1e3f))
            return "stiffness scale of strand " + std::to_string(i) + ": " + std::to_string(perStrand[i])
                + " is not a finite number of at least 0";
    for (std::size_t i = 0; i < perStrand.size(); ++i) {
        const Slot slot = m_slotOfStrand[i];
        m_blocks[slot.block].stiffnessScale[slot.lane] = perStrand[i];
    }
    for (Block& b : m_blocks) // padding lanes copy their block's first strand
        for (int l = 0; l < kLanes; ++l)
            if (b.strand[l] < 0)
                b.stiffnessScale[l] = b.stiffnessScale[0];
    m_bendSharesStale = true;
    return {};
}

std::string Solver::setStrandAir(std::span<const float> dragScale, std::span<const glm::vec3> extraWind)
{
    if (!dragScale.empty() && dragScale.size() != m_strandCount)
        return "drag scales: " + std::to_string(dragScale.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    if (!extraWind.empty() && extraWind.size() != m_strandCount)
        return "strand winds: " + std::to_string(extraWind.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < dragScale.size(); ++i)
        if (!(dragScale[i] >= 0.0f && dragScale[i] <= 1e3f))
            return "drag scale of strand " + std::to_string(i) + ": " + std::to_string(dragScale[i])
                + " is not a finite number of at least 0";
    for (std::size_t i = 0; i < extraWind.size(); ++i)
        if (!(std::abs(extraWind[i].x) <= 1e3f && std::abs(extraWind[i].y) <= 1e3f && std::abs(extraWind[i].z) <= 1e3f))
            return "wind of strand " + std::to_string(i) + " is not a finite speed below 1000 m/s";
    const bool windy = std::ranges::any_of(extraWind, [](const glm::vec3& w) { return w != glm::vec3(0.0f); });
    m_blockWinds.assign(windy ? m_blocks.size() : 0, BlockWind{});
    for (std::size_t i = 0; i < m_blocks.size(); ++i)
        m_blocks[i].wind = windy ? &m_blockWinds[i] : nullptr;
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        Block& b = m_blocks[slot.block];
        b.dragScale[slot.lane] = dragScale.empty() ? 1.0f : dragScale[i];
        if (windy) {
            BlockWind& w = m_blockWinds[slot.block];
            w.x[slot.lane] = extraWind[i].x;
            w.y[slot.lane] = extraWind[i].y;
            w.z[slot.lane] = extraWind[i].z;
        }
    }
    return {};
}

void Solver::copyState(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& previous) const
{
    copyPositions(positions);
    previous.resize(positions.size());
    for (std::size_t strand = 0; strand < m_strandCount; ++strand) {
        const Slot slot = m_slotOfStrand[strand];
        const Block& b = m_blocks[slot.block];
        for (std::uint32_t j = 0; j < b.points; ++j) {
            const ParticleRow& row = b.state[j];
            previous[m_restOffsets[strand] + j] = { row.px[slot.lane], row.py[slot.lane], row.pz[slot.lane] };
        }
    }
}

bool Solver::setStrandState(
    std::size_t strand, std::span<const glm::vec3> positions, std::span<const glm::vec3> previous)
{
    if (strand >= m_strandCount)
        return false;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (positions.size() != b.points || previous.size() != b.points)
        return false;
    m_volumeSplatted = false; // the grid's last splats are of the old state
    for (std::uint32_t j = 0; j < b.points; ++j)
        if (!std::isfinite(
                positions[j].x + positions[j].y + positions[j].z + previous[j].x + previous[j].y + previous[j].z))
            return false;
    for (std::uint32_t j = 1; j < b.points; ++j) { // the root stays where its rest shape pins it
        ParticleRow& row = b.state[j];
        row.x[slot.lane] = positions[j].x;
        row.y[slot.lane] = positions[j].y;
        row.z[slot.lane] = positions[j].z;
        row.px[slot.lane] = previous[j].x;
        row.py[slot.lane] = previous[j].y;
        row.pz[slot.lane] = previous[j].z;
        row.clearance[slot.lane] = -1.0f;
    }
    return true;
}

bool Solver::setStrandRestDirections(std::size_t strand, std::span<const glm::vec3> restShape)
{
    if (strand >= m_strandCount)
        return false;
    const Slot slot = m_slotOfStrand[strand];
    Block& b = m_blocks[slot.block];
    if (restShape.size() != b.points)
        return false;
    const int l = static_cast<int>(slot.lane);
    if (glm::distance(restShape[0], glm::vec3(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l])) > 1e-6f)
        return false;
    for (std::uint32_t j = 1; j < b.points; ++j) {
        const float length = glm::distance(restShape[j], restShape[j - 1]);
        if (!(std::abs(length - b.rest[j].length[l]) <= 1e-3f * b.rest[j].length[l]))
            return false;
    }
    std::vector<glm::vec3> directions(b.points, glm::vec3(0.0f));
    for (std::uint32_t j = 1; j < b.points; ++j)
        directions[j] = glm::normalize(restShape[j] - restShape[j - 1]);
    storeRestFrames(b, l, directions);
    m_globalShapeStale = true;
    return true;
}

void Solver::copyPositions(std::vector<glm::vec3>& out) const
{
    out.resize(m_restOffsets.empty() ? 0 : m_restOffsets.back());
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const Block& b = m_blocks[i];
            for (int l = 0; l < kLanes; ++l) {
                if (b.strand[l] < 0)
                    continue;
                glm::vec3* dst = out.data() + m_restOffsets[static_cast<std::size_t>(b.strand[l])];
                for (std::uint32_t j = 0; j < b.points; ++j)
                    dst[j] = { b.state[j].x[l], b.state[j].y[l], b.state[j].z[l] };
            }
        }
    });
}

std::size_t Solver::memoryBytes() const
{
    return m_restOffsets.capacity() * sizeof(std::uint32_t) + m_blocks.capacity() * sizeof(Block)
        + m_slotOfStrand.capacity() * sizeof(Slot) + m_blockWinds.capacity() * sizeof(BlockWind)
        + m_stateRows.capacity() * sizeof(ParticleRow) + m_restRows.capacity() * sizeof(RestRow)
        + m_shapeRows.capacity() * sizeof(ShapeRow) + m_globalShapeRows.capacity() * sizeof(GlobalShapeRow)
        + (m_volumeGrid ? m_volumeGrid->memoryBytes() : 0);
}

} // namespace wisp
