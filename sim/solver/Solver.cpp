#include "sim/solver/Solver.h"

#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/BendingModel.h"
#include "sim/solver/HairVolumeGrid.h"
#include "sim/solver/SolverBlockKernel.h"
#include "sim/solver/SolverLanes.h"
#include "sim/solver/SolverRows.h"
#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <span>

namespace wisp {

namespace {

// Above this many bytes of rows (state and rest) the kernel asks for the next block's rows while it
// runs a block: they then come from memory, not the caches. Below it the rows stay cached from one
// step to the next and the prefetches only cost their instructions. Measured on the sphere workload
// (29 Nov, Ice Lake, AVX-512, 2 threads, six interleaved rounds, median × the floor with and
// without them): 75,000 particles (4 MB) 3.59 / 3.08, 180,000 (10 MB) 3.65 / 3.28, 450,000 (26 MB)
// 3.63 / 4.39; groom-1m (55 MB) 7.22 / 8.65.
constexpr std::size_t kPrefetchNextBlockBytes = std::size_t{ 16 } << 20;

} // namespace

Solver::Solver(int threadCount)
    : m_pool(std::make_unique<ThreadPool>(threadCount))
{
}
Solver::~Solver() = default;

int Solver::threadCount() const
{
    return m_pool->threadCount();
}

std::string Solver::setStrands(const HairCurves& rest)
{
    if (rest.offsets.empty() || rest.offsets.front() != 0 || rest.offsets.back() != rest.positions.size())
        return "strands: the offsets do not match the points";
    // A block names its strands in 32 bits (Block::strand), and the strands' slots pack the block's
    // index beside the lane (Slot).
    if (rest.strandCount() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
        return "strands: " + std::to_string(rest.strandCount()) + " is more than the solver can hold ("
            + std::to_string(std::numeric_limits<std::int32_t>::max()) + ")";
    // Group strands by particle count: a block's 16 lanes must run the same loop.
    std::map<std::uint32_t, std::vector<std::uint32_t>> byCount;
    for (std::size_t i = 0; i < rest.strandCount(); ++i) {
        const std::span<const glm::vec3> s = rest.strand(i);
        if (s.size() < 2)
            return "strand " + std::to_string(i) + ": has " + std::to_string(s.size())
                + " points; at least 2 are needed";
        for (std::size_t j = 0; j < s.size(); ++j) {
            if (!std::isfinite(s[j].x) || !std::isfinite(s[j].y) || !std::isfinite(s[j].z))
                return "strand " + std::to_string(i) + ": point " + std::to_string(j) + " is not finite";
            if (j > 0 && !(glm::distance(s[j], s[j - 1]) > 1e-7f))
                return "strand " + std::to_string(i) + ": points " + std::to_string(j - 1) + " and " + std::to_string(j)
                    + " coincide (zero-length segment)";
        }
        byCount[static_cast<std::uint32_t>(s.size())].push_back(static_cast<std::uint32_t>(i));
    }

    std::size_t rows = 0, blockCount = 0;
    for (const auto& [count, strands] : byCount) {
        rows += count * ((strands.size() + kLanes - 1) / kLanes);
        blockCount += (strands.size() + kLanes - 1) / kLanes;
    }
    std::vector<ParticleRow> stateRows(rows);
    std::vector<RestRow> restRows(rows);
    std::vector<ShapeRow> shapeRows(blockCount * Block::kShapeRows);
    std::vector<glm::vec3> directions;
    std::vector<Block> blocks;
    std::size_t particles = 0;
    std::size_t nextRow = 0;
    for (const auto& [count, strands] : byCount) {
        for (std::size_t first = 0; first < strands.size(); first += kLanes) {
            Block b;
            b.points = count;
            b.state = std::span<ParticleRow>(stateRows.data() + nextRow, count);
            b.rest = std::span<RestRow>(restRows.data() + nextRow, count);
            b.shape = std::span<ShapeRow>(shapeRows.data() + blocks.size() * Block::kShapeRows, Block::kShapeRows);
            nextRow += count;
            directions.assign(count, glm::vec3(0.0f));
            for (int l = 0; l < kLanes; ++l) {
                // Padding lanes repeat the block's first strand and are never copied out.
                const bool real = first + static_cast<std::size_t>(l) < strands.size();
                const std::uint32_t strand = strands[real ? first + static_cast<std::size_t>(l) : first];
                b.strand[l] = real ? static_cast<std::int32_t>(strand) : -1;
                const std::span<const glm::vec3> s = rest.strand(strand);
                float total = 0.0f;
                b.shape[0].x[l] = s[0].x;
                b.shape[0].y[l] = s[0].y;
                b.shape[0].z[l] = s[0].z;
                b.rest[0].length[l] = 0.0f;
                for (std::uint32_t j = 1; j < count; ++j) {
                    const glm::vec3 d = s[j] - s[j - 1];
                    const float len = glm::length(d);
                    directions[j] = d / len;
                    b.rest[j].length[l] = len;
                    total += len;
                }
                b.strandLength[l] = total;
                storeRestFrames(b, l, directions);
                b.stiffnessScale[l] = 1.0f;
                b.dragScale[l] = 1.0f;
                b.volumeWeight[l] = real ? total / static_cast<float>(count - 1) : 0.0f;
                b.volumeTargetScale[l] = 1.0f;
            }
            particles += count * std::min<std::size_t>(kLanes, strands.size() - first);
            blocks.push_back(std::move(b));
        }
    }
    m_blocks = std::move(blocks);
    m_stateRows = std::move(stateRows); // moving keeps the buffers, so the blocks' views stay valid
    m_restRows = std::move(restRows);
    m_shapeRows = std::move(shapeRows);
    m_slotOfStrand.assign(rest.strandCount(), {});
    for (std::uint32_t i = 0; i < m_blocks.size(); ++i)
        for (std::uint32_t l = 0; l < kLanes; ++l)
            if (m_blocks[i].strand[l] >= 0)
                m_slotOfStrand[static_cast<std::size_t>(m_blocks[i].strand[l])] = { i, l };
    m_blockWinds.clear(); // no strand has a wind of its own (setStrandAir)
    m_restOffsets = rest.offsets;
    m_bendSharesStale = true;
    m_globalShapeStale = true;
    m_globalShapeRows.clear();
    m_strandCount = rest.strandCount();
    m_particleCount = particles;
    m_scalpArea = 0.0f;
    updateVolumeBounds();
    resetToRest();
    return {};
}

std::string Solver::setSettings(const SolverSettings& settings)
{
    std::string error = validateSolverSettings(settings);
    if (!error.empty())
        return error;
    if (settings.hairOffsetMetres != m_settings.hairOffsetMetres) // clearances are measured from the offset
        forgetClearances();
    m_settings = settings;
    return {};
}

void Solver::setCollider(std::shared_ptr<const SignedDistanceField> headSdf)
{
    m_sdf = headSdf && !headSdf->empty() ? std::move(headSdf) : nullptr;
    m_field = m_sdf ? std::make_unique<CollisionField>(*m_sdf) : nullptr;
    m_volumeGrid.reset(); // its solid is the head
    forgetClearances();
}

void Solver::setCapsules(std::vector<Capsule> capsules)
{
    // The bounds cover the capsules too: forgotten only when they change (the editor sets them again
    // with every force parameter, while a slider is dragged, and every particle would look at the
    // head again each time).
    if (capsules == m_capsules)
        return;
    m_capsules = std::move(capsules);
    forgetClearances();
}

void Solver::forgetClearances()
{
    for (Block& b : m_blocks)
        for (ParticleRow& row : b.state)
            row.clearance = Lane{} - 1.0f;
}

void Solver::setHeadTransform(const glm::mat4& headToWorld)
{
    m_headToWorld = headToWorld;
}

void Solver::resetToRest()
{
    m_volumeSplatted = false; // the grid's last splats are of the old state
    m_previousHeadToWorld = m_headToWorld;
    const glm::mat3 rotation(m_headToWorld);
    const glm::vec3 translation(m_headToWorld[3]);
    for (Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l)
            placeLaneAtRest(b, l, rotation, translation);
}

bool Solver::anyStrandBends() const
{
    if (m_bendSharesStale || m_bendSharesFor.x != m_settings.stiffness) // (the next step sets the shares)
        return m_settings.stiffness > 0.0f && std::any_of(m_blocks.begin(), m_blocks.end(), [](const Block& b) {
            for (int l = 0; l < kLanes; ++l)
                if (b.strand[l] >= 0 && b.stiffnessScale[l] > 0.0f)
                    return true;
            return false;
        });
    return std::any_of(m_blocks.begin(), m_blocks.end(), [](const Block& b) { return b.bends; });
}

// The bend shares of every segment for a substep of `substepSeconds` (BendingModel.h): from the
// rigidity of each lane's stiffness (settings x the strand's scale) and the segment lengths.
void Solver::updateBendShares(float substepSeconds)
{
    const float globalStiffness = m_settings.stiffness;
    if (m_bendSharesFor == glm::vec2(globalStiffness, substepSeconds) && !m_bendSharesStale)
        return;
    m_bendSharesFor = { globalStiffness, substepSeconds };
    m_bendSharesStale = false;
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        std::vector<float> lengths;
        for (std::size_t i = begin; i < end; ++i) {
            Block& b = m_blocks[i];
            const int n = static_cast<int>(b.points);
            lengths.resize(b.points);
            b.bends = false;
            for (int l = 0; l < kLanes; ++l) {
                const float rigidity = bending::rigidity(std::min(1.0f, globalStiffness * b.stiffnessScale[l]));
                for (int j = 0; j < n; ++j)
                    lengths[j] = b.rest[j].length[l];
                for (int j = 1; j < n; ++j) {
                    const bending::Constraint k = bending::constraint(rigidity, substepSeconds, lengths.data(), n, j);
                    RestRow& r = b.rest[j];
                    r.bendChild[l] = k.child;
                    r.bendDamping[l] = k.damping;
                    r.bendParentRatio[l] = k.parentRatio;
                    b.bends = b.bends || k.child != 0.0f || k.damping != 0.0f || k.parentRatio != 0.0f;
                }
            }
        }
    });
}

// The global shape's rows for a substep of `substepSeconds` (pullTowardGlobalShape): each
// particle's rest position, and its share s_j = 1 - (1 - g f_j)^(dt / kGlobalShapeStepSeconds),
// which moves as far per second at any substep count (as damping's exp(-k dt) does), with
// f_j = max(0, 1 - u_j / kGlobalShapeReach) at u_j, the rest arc length from the root over the
// strand's. None while the global shape is 0: the step then reads nothing more.
void Solver::updateGlobalShape(float substepSeconds)
{
    const float g = m_settings.globalShape;
    if (!(g > 0.0f)) {
        if (!m_globalShapeRows.empty()) {
            m_globalShapeRows = {};
            for (Block& b : m_blocks)
                b.globalShape = {};
        }
        return;
    }
    if (!m_globalShapeStale && m_globalShapeFor == glm::vec2(g, substepSeconds) && !m_globalShapeRows.empty())
        return;
    m_globalShapeFor = { g, substepSeconds };
    m_globalShapeStale = false;
    m_globalShapeRows.resize(m_restRows.size());
    const float exponent = substepSeconds / kGlobalShapeStepSeconds;
    m_pool->parallelFor(m_blocks.size(), 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            Block& b = m_blocks[i];
            GlobalShapeRow* rows = m_globalShapeRows.data() + (b.rest.data() - m_restRows.data());
            b.globalShape = std::span<const GlobalShapeRow>(rows, b.points);
            for (int l = 0; l < kLanes; ++l) {
                glm::vec3 p(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]);
                RestDirections directions(b, l);
                float arc = 0.0f;
                for (std::uint32_t j = 0; j < b.points; ++j) {
                    if (j > 0) {
                        const float length = b.rest[j].length[l];
                        p += directions.next() * length;
                        arc += length;
                    }
                    const float fade = std::max(0.0f, 1.0f - arc / (kGlobalShapeReach * b.strandLength[l]));
                    const float perStep = std::min(1.0f, g * fade);
                    rows[j].x[l] = p.x;
                    rows[j].y[l] = p.y;
                    rows[j].z[l] = p.z;
                    rows[j].share[l] = j == 0 ? 0.0f : 1.0f - std::pow(1.0f - perStep, exponent);
                }
            }
        }
    });
}

void Solver::step()
{
    StepConstants c;
    const SolverSettings& s = m_settings;
    c.substeps = s.substeps;
    c.dt = substepSeconds(s);
    c.keep = std::exp(-s.dampingPerSecond * c.dt);
    updateBendShares(c.dt);
    updateGlobalShape(c.dt);
    c.friction = s.friction;
    c.offset = s.hairOffsetMetres;
    c.velocityCorrection = s.velocityCorrection;
    c.drag = s.dragPerSecond;
    c.turbulence = s.turbulence;
    c.gravity = s.gravity;
    c.wind = s.wind;
    c.time = m_time;
    c.rotation = glm::mat3(m_headToWorld);
    c.translation = glm::vec3(m_headToWorld[3]);
    c.previousRotation = glm::mat3(m_previousHeadToWorld);
    c.previousTranslation = glm::vec3(m_previousHeadToWorld[3]);
    c.transformed = m_headToWorld != glm::mat4(1.0f) || m_previousHeadToWorld != glm::mat4(1.0f);
    {
        // The head point now at world x was at M x + m a step ago (M = R_prev R^T, m = T_prev - M T),
        // so over one substep it moves ((I - M) x - m) / substeps.
        const glm::mat3 back = c.previousRotation * glm::transpose(c.rotation);
        const float share = 1.0f / static_cast<float>(c.substeps);
        c.headMoveLinear = (glm::mat3(1.0f) - back) * share;
        c.headMoveOffset = -(c.previousTranslation - back * c.translation) * share;
    }
    c.field = m_field.get();
    c.prefetchNextBlock
        = m_stateRows.size() * sizeof(ParticleRow) + m_restRows.size() * sizeof(RestRow) > kPrefetchNextBlockBytes;
    for (const Capsule& cap : m_capsules)
        c.capsulesWorld.push_back(
            { c.rotation * cap.a + c.translation, c.rotation * cap.b + c.translation, cap.radiusMetres });
    c.resetCounter = &m_strandsReset;

    // Blocks are independent within a substep, so any split over threads gives the same bits.
    const bool globalShape = !m_globalShapeRows.empty();
    const bool volume = s.volume > 0.0f && !m_blocks.empty();
    // Runs substeps [first, end) block by block; with volume each block first reads the grid before
    // each substep, and splats its end state for the next pass when `splatAtEnd`.
    auto advance = [&](int first, int end, bool splatAtEnd) {
        // Runs of blocks long enough that a thread's next block is nearly always the next one in
        // memory (the kernel asks for its rows and fields while running this one: a run's first
        // block starts cold), short enough that the threads still finish together.
        const std::size_t grain
            = std::clamp<std::size_t>(m_blocks.size() / (32 * static_cast<std::size_t>(threadCount())), 4, 64);
        m_pool->parallelFor(m_blocks.size(), grain, [&](std::size_t begin, std::size_t stop) {
            HairVolumeGrid* const splatInto
                = volume && splatAtEnd && !m_volumeGrid->empty() ? m_volumeGrid.get() : nullptr;
            const int slot = splatInto ? splatInto->claimSlot() : 0;
            for (std::size_t i = begin; i < stop; ++i) {
                Block& b = m_blocks[i];
                if (i + 1 < stop) // the next block this thread runs: its fields, while this one runs
                    prefetchBlock(m_blocks[i + 1]);
                auto run = [&](int from, int to) { advanceBlock(b, c, from, to, globalShape); };
                if (!volume) {
                    run(first, end);
                    continue;
                }
                // The grid stays the same over [first, end): the block reads it before each of
                // these substeps and runs them in one go, in cache.
                for (int substep = first; substep < end; ++substep) {
                    volumeRead(b, c);
                    run(substep, substep + 1);
                }
                if (splatInto)
                    volumeSplat(b, c, slot); // for the next pass, while the block is in cache
            }
            if (splatInto)
                splatInto->releaseSlot(slot);
        });
    };
    if (volume) {
        // Hair-hair interaction needs every strand where it is when the grid is laid: the substeps
        // run outside the blocks, in runs after each of the volume grid's passes (its read is the
        // first thing each block does before each substep, in advance()).
        // The grid is laid again every kVolumeRefreshSeconds of substeps (every substep at the
        // default two substeps at 60 Hz; once a step for a heavy scene's many short substeps): in
        // that time hair moving at 0.5 m/s moves 4 mm, half a cell, so the field read at each
        // particle's own new position barely differs, while the pass is most of a substep's cost.
        // The push's stiffness is capped for the refresh interval, not the substep (volumePass).
        // A dense groom lays it every kVolumeDenseRefreshSeconds, across steps if need be (the
        // blocks still read it before every substep), SolverVolume.cpp.
        const bool dense = volumeDense();
        const int refreshEvery = volumeRefreshSubsteps(c.dt, dense);
        const bool acrossSteps = dense && refreshEvery > c.substeps;
        if (m_headToWorld != m_volumeSplatHead) // the last splats are in the last step's head space
            m_volumeSplatted = false;
        // Each step lays the grid first, unless a dense groom's interval goes on from the last step
        // (and the grid is still there with its fixed point).
        if (!acrossSteps || !m_volumeGrid || m_volumeUnitsStale)
            m_volumeSubstepsToPass = 0;
        m_volumeSubstepsToPass = std::min(m_volumeSubstepsToPass, refreshEvery);
        for (int first = 0; first < c.substeps;) {
            if (m_volumeSubstepsToPass == 0) {
                c.substep = first;
                volumePass(c, acrossSteps ? refreshEvery : std::min(refreshEvery, c.substeps - first));
                m_volumeSubstepsToPass = refreshEvery;
            }
            const int end = std::min(first + m_volumeSubstepsToPass, c.substeps);
            m_volumeSubstepsToPass -= end - first;
            // The blocks splat for the next pass when it comes right after this run (or first thing
            // next step); a dense groom's run in the middle of its interval does not.
            const bool splatAtEnd = m_volumeSubstepsToPass == 0 || !acrossSteps;
            advance(first, end, splatAtEnd);
            m_volumeSplatted = splatAtEnd;
            if (splatAtEnd)
                m_volumeSplatHead = m_headToWorld;
            first = end;
        }
    } else {
        advance(0, c.substeps, false); // each block runs all its substeps in one go, in cache
        m_volumeSplatted = false;
        m_volumeSubstepsToPass = 0;
    }
    m_previousHeadToWorld = m_headToWorld;
    m_time += s.timeStepSeconds;
}

} // namespace wisp
