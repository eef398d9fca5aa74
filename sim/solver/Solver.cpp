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
#include <map>
#include <span>

namespace wisp {

using namespace lanes;

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
    // Group strands by particle count: a block's 8 lanes must run the same loop.
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

    std::size_t rows = 0;
    for (const auto& [count, strands] : byCount)
        rows += count * ((strands.size() + kLanes - 1) / kLanes);
    std::vector<ParticleRow> stateRows(rows);
    std::vector<RestRow> restRows(rows);
    std::vector<ShapeRow> shapeRows(rows);
    std::vector<Block> blocks;
    std::size_t particles = 0;
    std::size_t nextRow = 0;
    for (const auto& [count, strands] : byCount) {
        for (std::size_t first = 0; first < strands.size(); first += kLanes) {
            Block b;
            b.points = count;
            b.state = std::span<ParticleRow>(stateRows.data() + nextRow, count);
            b.rest = std::span<RestRow>(restRows.data() + nextRow, count);
            b.shape = std::span<ShapeRow>(shapeRows.data() + nextRow, count);
            nextRow += count;
            for (int l = 0; l < kLanes; ++l) {
                // Padding lanes repeat the block's first strand and are never copied out.
                const bool real = first + static_cast<std::size_t>(l) < strands.size();
                const std::uint32_t strand = strands[real ? first + static_cast<std::size_t>(l) : first];
                b.strand[l] = real ? static_cast<std::int64_t>(strand) : -1;
                const std::span<const glm::vec3> s = rest.strand(strand);
                float total = 0.0f;
                for (std::uint32_t j = 0; j < count; ++j) {
                    RestRow& r = b.rest[j];
                    ShapeRow& q = b.shape[j];
                    if (j == 0) {
                        q.x[l] = s[0].x;
                        q.y[l] = s[0].y;
                        q.z[l] = s[0].z;
                        r.length[l] = 0.0f;
                    } else {
                        const glm::vec3 d = s[j] - s[j - 1];
                        const float len = glm::length(d);
                        q.x[l] = d.x / len;
                        q.y[l] = d.y / len;
                        q.z[l] = d.z / len;
                        r.length[l] = len;
                        total += len;
                    }
                }
                b.strandLength[l] = total;
                storeRestFrames(b, l);
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

namespace {

// The scalp area the simulated roots cover, m², when nobody said: the cells of a 1 cm grid that
// hold a root, each about 1 cm² / 1.5 of surface (a plane cuts 1.5 cells per cell area on average).
float estimatedScalpArea(std::span<const Solver::Block> blocks)
{
    constexpr float kCell = 0.01f;
    std::vector<std::int64_t> cells;
    for (const Solver::Block& b : blocks)
        for (int l = 0; l < kLanes; ++l)
            if (b.strand[l] >= 0) {
                const glm::ivec3 c(glm::floor(glm::vec3(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]) / kCell));
                cells.push_back((static_cast<std::int64_t>(c.x & 0x1FFFFF) << 42)
                    | (static_cast<std::int64_t>(c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF));
            }
    std::sort(cells.begin(), cells.end());
    const auto distinct = std::unique(cells.begin(), cells.end()) - cells.begin();
    return static_cast<float>(distinct) * kCell * kCell / 1.5f;
}

} // namespace

// The head-space box every particle stays in (its root's box grown by its strand's length), and
// the hair per scalp area from the particles' weights.
void Solver::updateVolumeBounds()
{
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    double hair = 0.0;
    for (const Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l) {
            if (b.strand[l] < 0)
                continue;
            const glm::vec3 root(b.shape[0].x[l], b.shape[0].y[l], b.shape[0].z[l]);
            lo = glm::min(lo, root - b.strandLength[l]);
            hi = glm::max(hi, root + b.strandLength[l]);
            hair += static_cast<double>(b.volumeWeight[l]) * (b.points - 1);
        }
    m_volumeLo = lo;
    m_volumeHi = hi;
    if (!(m_scalpArea > 0.0f))
        m_scalpArea = estimatedScalpArea(m_blocks);
    m_hairPerScalpArea = m_scalpArea > 0.0f ? static_cast<float>(hair / m_scalpArea) : 0.0f;
    // A regroom (a brush dab) barely moves the box: the grid is kept while the new box fits in it
    // and fills at least half of it; laying it out again (32 MiB and the head's solid) costs about
    // 0.3 s, far more than a dab.
    if (m_volumeGrid && !m_volumeGrid->empty()) {
        const glm::vec3 gridLo = m_volumeGrid->origin();
        const glm::vec3 gridHi = gridLo + m_volumeGrid->cellMetres() * glm::vec3(m_volumeGrid->dims() - 1);
        const glm::vec3 size = glm::max(hi - lo, glm::vec3(0.0f)), gridSize = gridHi - gridLo;
        const bool fits = glm::all(glm::greaterThanEqual(lo, gridLo)) && glm::all(glm::lessThanEqual(hi, gridHi));
        if (fits && size.x * size.y * size.z >= 0.5f * gridSize.x * gridSize.y * gridSize.z)
            return;
    }
    m_volumeGrid.reset(); // laid out again on the next step with volume on
}

float Solver::volumeTargetDensity() const
{
    return m_settings.volume > 0.0f ? m_hairPerScalpArea / (m_settings.volume * kVolumeDepthMetres) : 0.0f;
}

std::string Solver::setStrandVolume(std::span<const float> drawnStrands, float scalpAreaSquareMetres)
{
    if (!drawnStrands.empty() && drawnStrands.size() != m_strandCount)
        return "drawn strands: " + std::to_string(drawnStrands.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < drawnStrands.size(); ++i)
        if (!(drawnStrands[i] >= 0.0f && drawnStrands[i] <= 1e6f))
            return "drawn strands of strand " + std::to_string(i) + ": " + std::to_string(drawnStrands[i])
                + " is not a finite number of at least 0";
    if (!(scalpAreaSquareMetres >= 0.0f && scalpAreaSquareMetres <= 1e4f))
        return "scalp area: " + std::to_string(scalpAreaSquareMetres) + " m² is not a finite area of at least 0";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        Block& b = m_blocks[slot.block];
        const float drawn = drawnStrands.empty() ? 1.0f : drawnStrands[i];
        b.volumeWeight[slot.lane] = drawn * b.strandLength[slot.lane] / static_cast<float>(b.points - 1);
    }
    m_scalpArea = scalpAreaSquareMetres;
    updateVolumeBounds();
    return {};
}

std::string Solver::setVolumeTargetScales(std::span<const float> perStrand)
{
    if (!perStrand.empty() && perStrand.size() != m_strandCount)
        return "volume target scales: " + std::to_string(perStrand.size()) + " for " + std::to_string(m_strandCount)
            + " strands";
    for (std::size_t i = 0; i < perStrand.size(); ++i)
        if (!(perStrand[i] >= 0.01f && perStrand[i] <= 1e3f))
            return "volume target scale of strand " + std::to_string(i) + ": " + std::to_string(perStrand[i])
                + " is not a finite number within 0.01..1000";
    for (std::size_t i = 0; i < m_strandCount; ++i) {
        const Slot slot = m_slotOfStrand[i];
        m_blocks[slot.block].volumeTargetScale[slot.lane] = perStrand.empty() ? 1.0f : perStrand[i];
    }
    return {};
}

// How hard hair denser than its target pushes down the density gradient: the acceleration is this
// times (density / target - 1, at most 1) times the gradient of density / target (1/m), so hair at
// twice its target that thins out over 2 cm pushes at 200 m/s² before the cap. Capped at
// kVolumeMaxAcceleration (3 g) so a particle deep in a knot is not flung. Measured on the default
// groom (tests/sim/VolumeTest.cpp): 1 m²/s² leaves the top at 8 mm, 4 gives 18 mm, 10 gives 20 mm.
constexpr float kVolumeStiffness = 4.0f; // m²/s²
constexpr float kVolumeMaxAcceleration = 30.0f; // m/s²
// The push's stiffness is at most this times (cell / substep)², measured: 1 substep at 60 Hz with
// 8 segments leaves 0 % of tips moving at 0.6 (VolumeTest's settling cases).
constexpr float kVolumeStableShare = 0.6f;
// Damping of the motion along the push where hair is denser than its target, per second: the share
// 1 - exp(-this dt) of it is taken each substep (the same at any substep count).
constexpr float kVolumeDampingPerSecond = 30.0f;
// The grid is laid again after at least this long of substeps (Solver::step): 1/120 s, the default
// substep (two at 60 Hz), so the default scene lays it every substep.
constexpr float kVolumeRefreshSeconds = 1.0f / 120.0f;
// A particle that moved this far in one substep (or went non-finite) is left out of the grid.
constexpr float kVolumeMaxMoveMetres = 0.5f;

// One substep's hair-hair interaction, before the blocks advance (so contact, after it, stays the
// last word): every particle splats its weight and its move over the last substep into the grid;
// then each particle's velocity is blended toward the hair's mean velocity there by the hair
// friction (PIC/FLIP-style, Petrovic et al. 2005 sec. 4; McAdams et al. 2009), and where the
// density is above the target the particle is accelerated down the density gradient (the hair's
// own volume: Petrovic et al.'s pressure term, here only above the target, so hair at or below
// its volume feels nothing). Both change only the previous position (the velocity): the position
// is as the last substep left it, so length and contact stay as they were.
int Solver::volumeRefreshSubsteps(float substepSeconds)
{
    return std::max(1, static_cast<int>(kVolumeRefreshSeconds / substepSeconds + 1e-3f));
}

void Solver::volumePass(const StepConstants& c, int substepsUntilNext)
{
    if (!m_volumeGrid) {
        m_volumeGrid = std::make_unique<HairVolumeGrid>();
        if (m_volumeGrid->setBounds(m_volumeLo, m_volumeHi) && m_sdf)
            m_volumeGrid->setSolid([&](const glm::vec3& p) { return m_sdf->distance(p); });
    }
    HairVolumeGrid& grid = *m_volumeGrid;
    if (grid.empty())
        return;
    ++m_volumePasses;
    // Few particles (the editor's keys): the calling thread does it all; waking the pool for each of
    // the pass's loops would cost more than they do.
    constexpr std::size_t kParallelVolumeParticles = 50'000;
    ThreadPool* pool = m_particleCount >= kParallelVolumeParticles ? m_pool.get() : nullptr;
    // Each chunk in use is cleared by the thread that splats it; finish() reads only those in use.
    grid.setChunks(pool ? HairVolumeGrid::kSplatChunks : 1);
    const std::size_t blockCount = m_blocks.size();
    const std::size_t kChunks = static_cast<std::size_t>(grid.chunks());
    const glm::mat3 toHead = glm::transpose(c.rotation);
    // A fixed split of the blocks into chunks, each summed in block order, row by row (a row's 16
    // particles are neighbours on the scalp, so in the grid): the same bits on any thread count.
    auto splatChunks = [&](std::size_t begin, std::size_t end) {
        for (std::size_t chunk = begin; chunk < end; ++chunk) {
            grid.clearChunk(static_cast<int>(chunk)); // the last pass's splats, by the thread that splats now
            for (std::size_t i = chunk * blockCount / kChunks; i < (chunk + 1) * blockCount / kChunks; ++i) {
                const Block& b = m_blocks[i];
                for (std::uint32_t j = 0; j < b.points; ++j) { // row by row: a row's strands lie side by side
                    const ParticleRow& r = b.state[j];
                    const V3 x{ r.x, r.y, r.z };
                    const V3 move = x - V3{ r.px, r.py, r.pz };
                    // A particle gone non-finite or flying off (its strand is put back at rest at
                    // the end of the step) must not spread through the grid.
                    const Lane weight = select(l1Length(move) < kVolumeMaxMoveMetres, b.volumeWeight, splat(0.0f));
                    const V3 head = c.transformed ? transform(toHead, x - splat(c.translation)) : x;
                    grid.splatRow(static_cast<int>(chunk), reinterpret_cast<const float*>(&head.x),
                        reinterpret_cast<const float*>(&head.y), reinterpret_cast<const float*>(&head.z),
                        reinterpret_cast<const float*>(&weight), reinterpret_cast<const float*>(&move.x),
                        reinterpret_cast<const float*>(&move.y), reinterpret_cast<const float*>(&move.z));
                }
            }
        }
    };
    if (pool)
        pool->parallelFor(kChunks, 1, splatChunks);
    else
        splatChunks(0, kChunks);
    VolumeRead& v = m_volumeRead;
    v.target = volumeTargetDensity();
    grid.finish(pool, v.target);

    // The share of the difference from the hair's mean velocity lost this substep: hair_friction
    // is the share lost per 1/60 s, the same at any substep.
    v.blend = 1.0f - std::pow(1.0f - m_settings.hairFriction, c.dt * 60.0f);
    // The push is a stiff spring taken explicitly: past about (cell / dt)² it overshoots and hair
    // bounces on hair (one substep at 60 Hz did, 22 % of tips moving after 10 s), so its stiffness
    // is capped there; at the default two substeps the cap is about 2 m²/s².
    // (The grid is read for substepsUntilNext substeps: the spring's step is that long.)
    const float cell = grid.cellMetres();
    const float refreshSeconds = c.dt * static_cast<float>(substepsUntilNext);
    v.stiffness = std::min(kVolumeStiffness, kVolumeStableShare * cell * cell / (refreshSeconds * refreshSeconds));
    v.pushDamping = 1.0f - std::exp(-kVolumeDampingPerSecond * c.dt);
}

// The read of volumePass's grid for one block, all 16 lanes at once: each particle's velocity is
// blended toward the hair's mean velocity there by the hair friction, and where the density is
// above the target it is accelerated down the density gradient (see volumePass).
void Solver::volumeRead(Block& b, const StepConstants& c) const
{
    const HairVolumeGrid& grid = *m_volumeGrid;
    const VolumeRead& v = m_volumeRead;
    const Lane keep = v.target * b.volumeTargetScale;
    const Lane inverseKeep = splat(1.0f) / keep;
    const glm::mat3 toHead = glm::transpose(c.rotation);
    const float dt2 = c.dt * c.dt;
    HairVolumeGrid::SampleRow here;
    auto lane = [](const float* p) {
        Lane l;
        std::memcpy(&l, p, sizeof l);
        return l;
    };
    for (std::uint32_t j = 1; j < b.points; ++j) { // roots are pinned
        ParticleRow& r = b.state[j];
        const V3 x{ r.x, r.y, r.z };
        const V3 head = c.transformed ? transform(toHead, x - splat(c.translation)) : x;
        grid.sampleRow(reinterpret_cast<const float*>(&head.x), reinterpret_cast<const float*>(&head.y),
            reinterpret_cast<const float*>(&head.z), here);
        const Lane density = lane(here.density);
        const Mask inHair = density > 0.0f;
        if (!anyOf(inHair))
            continue;
        V3 move = x - V3{ r.px, r.py, r.pz };
        const Lane hair = lane(here.hair);
        const Mask hasHair = hair > 0.0f;
        const Lane inverseHair = select(hasHair, splat(1.0f) / hair, splat(0.0f));
        const V3 mean = V3{ lane(here.momentumX), lane(here.momentumY), lane(here.momentumZ) } * inverseHair;
        move = select(hasHair, move + (mean - move) * splat(v.blend), move);
        const Lane excess = density * inverseKeep - 1.0f;
        const Mask pushing = excess > 0.0f;
        if (anyOf(pushing)) {
            V3 push = V3{ lane(here.gradX), lane(here.gradY), lane(here.gradZ) }
                * ((-v.stiffness) * lmin(excess, splat(1.0f)) * inverseKeep);
            const Lane length = lsqrt(dot(push, push));
            push = push * select(length > kVolumeMaxAcceleration, kVolumeMaxAcceleration / length, splat(1.0f));
            if (c.transformed)
                push = transform(c.rotation, push);
            // Pressure alone makes hair bounce on the hair beneath it (a stiff spring taken
            // explicitly): the motion along the push is damped where it pushes.
            const Mask along = pushing & (length > 0.0f);
            const V3 direction = select(along, V3{ push.x / length, push.y / length, push.z / length }, V3{});
            const V3 damped = move - direction * (v.pushDamping * dot(move, direction));
            move = select(pushing, damped + push * splat(dt2), move);
        }
        const V3 now = select(inHair, x - move, V3{ r.px, r.py, r.pz });
        r.px = now.x;
        r.py = now.y;
        r.pz = now.z;
    }
}

std::string Solver::setSettings(const SolverSettings& settings)
{
    std::string error = validateSolverSettings(settings);
    if (!error.empty())
        return error;
    if (settings.hairOffsetMetres != m_settings.hairOffsetMetres) // clearances are measured from the offset
        for (Block& b : m_blocks)
            for (ParticleRow& row : b.state)
                row.clearance = splat(-1.0f);
    m_settings = settings;
    return {};
}

void Solver::setCollider(std::shared_ptr<const SignedDistanceField> headSdf)
{
    m_sdf = headSdf && !headSdf->empty() ? std::move(headSdf) : nullptr;
    m_field = m_sdf ? std::make_unique<CollisionField>(*m_sdf) : nullptr;
    m_volumeGrid.reset(); // its solid is the head
    for (Block& b : m_blocks)
        for (ParticleRow& row : b.state)
            row.clearance = splat(-1.0f);
}

void Solver::setCapsules(std::vector<Capsule> capsules)
{
    m_capsules = std::move(capsules);
}

void Solver::setHeadTransform(const glm::mat4& headToWorld)
{
    m_headToWorld = headToWorld;
}

void Solver::resetToRest()
{
    m_previousHeadToWorld = m_headToWorld;
    const glm::mat3 rotation(m_headToWorld);
    const glm::vec3 translation(m_headToWorld[3]);
    for (Block& b : m_blocks)
        for (int l = 0; l < kLanes; ++l)
            placeLaneAtRest(b, l, rotation, translation);
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
            const Block& b = m_blocks[i];
            const int n = static_cast<int>(b.points);
            lengths.resize(b.points);
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
                float arc = 0.0f;
                for (std::uint32_t j = 0; j < b.points; ++j) {
                    if (j > 0) {
                        const ShapeRow& d = b.shape[j];
                        const float length = b.rest[j].length[l];
                        p += glm::vec3(d.x[l], d.y[l], d.z[l]) * length;
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
    for (const Capsule& cap : m_capsules)
        c.capsulesWorld.push_back(
            { c.rotation * cap.a + c.translation, c.rotation * cap.b + c.translation, cap.radiusMetres });
    c.resetCounter = &m_strandsReset;

    // Blocks are independent within a substep, so any split over threads gives the same bits.
    const bool globalShape = !m_globalShapeRows.empty();
    const bool volume = s.volume > 0.0f && !m_blocks.empty();
    auto advance = [&](int first, int end) {
        m_pool->parallelFor(m_blocks.size(), 4, [&](std::size_t begin, std::size_t stop) {
            for (std::size_t i = begin; i < stop; ++i) {
                Block& b = m_blocks[i];
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
            }
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
        const int refreshEvery = volumeRefreshSubsteps(c.dt);
        for (int first = 0; first < c.substeps; first += refreshEvery) {
            const int end = std::min(first + refreshEvery, c.substeps);
            c.substep = first;
            volumePass(c, end - first);
            advance(first, end);
        }
    } else {
        advance(0, c.substeps); // each block runs all its substeps in one go, in cache
    }
    m_previousHeadToWorld = m_headToWorld;
    m_time += s.timeStepSeconds;
}

} // namespace wisp
