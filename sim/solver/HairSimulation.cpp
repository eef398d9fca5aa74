#include "sim/solver/HairSimulation.h"

#include "sim/geometry/Body.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/geometry/SignedDistanceField.h"
#include "sim/solver/RestShapeSolve.h"
#include "sim/solver/SolverSettings.h"
#include "sim/util/ByteHash.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <unordered_map>
#include <unordered_set>

namespace wisp {

HairSimulation::HairSimulation(int threadCount)
    : m_solver(threadCount)
    , m_head(std::make_shared<const HeadModel>(TriangleMesh{}))
{
}
HairSimulation::~HairSimulation() = default;

std::string HairSimulation::prepareHead(HeadModelPtr model)
{
    const TriangleMesh& head = model->mesh();
    if (std::string error = validateMesh(head); !error.empty())
        return "head: " + error;
    const Aabb box = boundsOf(head);
    const float extent = glm::max(box.size().x, glm::max(box.size().y, box.size().z));
    std::string error;
    // The margin covers the hair offset and curls lying on the skin; beyond it the field is clamped.
    auto sdf = std::make_shared<SignedDistanceField>(SignedDistanceField::bake(
        head, extent / kColliderCellsAcross, 0.1f * extent + 0.01f, &error, &m_solver.threadPool()));
    if (sdf->empty())
        return "head: cannot build its collider: " + error;
    m_head = std::move(model);
    m_sdf = std::move(sdf);
    m_body = defaultBody(m_head->mesh());
    m_builder.forgetHead();
    return {};
}

namespace {

// Per simulated strand, the drawn strands it stands for: a key hair and its members, or 1.
std::vector<float> drawnStrandsPerSimulated(const Groom& groom, bool allStrands)
{
    if (allStrands)
        return std::vector<float>(groom.strandCount(), 1.0f);
    std::vector<float> drawn(groom.wispCount(), 0.0f);
    for (std::size_t i = 0; i < groom.strandCount(); ++i)
        drawn[groom.wispOf[i]] += 1.0f;
    return drawn;
}

// The scalp area the drawn hair grows from, m²: each drawn strand takes 1 / (its region's density),
// as where the growth weight is 1 (0, for the solver to estimate, when a region has no density).
float scalpAreaOf(const Groom& groom)
{
    double area = 0.0;
    for (std::size_t i = 0; i < groom.strandCount(); ++i) {
        const float density = groom.regionSettings[groom.regionOfStrand[i]].densityPerCm2 * 1e4f; // per m²
        if (!(density > 0.0f))
            return 0.0f;
        area += 1.0 / density;
    }
    return static_cast<float>(area);
}

} // namespace

std::string HairSimulation::start(Groom groom, const ParameterValues& values)
{
    SolverSettings settings = solverSettingsFrom(values);
    if (std::string error = validateSolverSettings(settings); !error.empty())
        return error;
    const bool allStrands = values.get(Param::SimulateAllStrands) != 0.0;
    HairCurves simulated = allStrands ? groom.rest : keyRestCurves(groom);
    saveWetness();
    m_allStrands = allStrands;
    solveCombedRest(groom, values, simulated);
    if (std::string error = m_solver.setStrands(simulated); !error.empty())
        return error;
    if (std::string error = m_solver.setSettings(settings); !error.empty())
        return error;
    m_solver.setCollider(m_sdf);
    setBody(values);
    if (std::string error = m_solver.setStrandVolume(drawnStrandsPerSimulated(groom, allStrands), scalpAreaOf(groom));
        !error.empty())
        return error;
    m_groom = std::move(groom);
    m_dryingHalfLife = values.getFloat(Param::DryingTime);
    m_simulatedOf.clear();
    const std::size_t count = m_solver.strandCount();
    for (std::size_t i = 0; i < count; ++i)
        m_simulatedOf.emplace(
            m_groom.strandIdentity(m_allStrands ? i : m_groom.keyStrand[i]), static_cast<std::uint32_t>(i));
    restoreWetness();
    m_airInSolver = false;
    return setStrandStiffness(m_groom);
}

const StrandStyle* HairSimulation::styleOf(std::size_t strand) const
{
    if (!m_style || m_style->empty())
        return nullptr;
    const auto found = m_style->find(m_groom.strandIdentity(strand));
    return found == m_style->end() ? nullptr : &found->second;
}

float HairSimulation::strandStiffnessScale(float regionScale, const StrandStyle* style)
{
    if (!style)
        return regionScale;
    const float scale = regionScale * style->stiffnessScale;
    return style->shape.size() >= 2 ? std::max(scale, regionScale * kCombSetsStiffness) : scale;
}

std::string HairSimulation::setStrandStiffness(const Groom& groom)
{
    m_baseStiffness.clear();
    m_baseStiffness.reserve(m_solver.strandCount());
    m_baseVolumeFactor.clear();
    m_baseVolumeFactor.reserve(m_solver.strandCount());
    const std::size_t count = m_allStrands ? groom.strandCount() : groom.wispCount();
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t strand = m_allStrands ? i : groom.keyStrand[i];
        const StrandStyle* style = styleOf(strand);
        m_baseStiffness.push_back(
            strandStiffnessScale(groom.regionStiffnessScale[groom.regionOfStrand[strand]], style));
        m_baseVolumeFactor.push_back(style && style->shape.size() >= 2 ? kCombedVolumeFactor : 1.0f);
    }
    if (std::string error = m_solver.setStiffnessScales(m_baseStiffness); !error.empty())
        return error;
    m_wetnessInSolver.assign(count, 0.0f);
    updateMaterial(true);
    return {};
}

// The combed strands' rest shapes, solved so that they sag onto the comb (RestShapeSolve.h).
// Solutions are kept by identity and reused while the comb, the stiffness and gravity stay.
void HairSimulation::solveCombedRest(const Groom& groom, const ParameterValues& values, HairCurves& simulated)
{
    m_worstRestGap = 0.0f;
    if (!m_style || m_style->empty())
        return;
    const SolverSettings settings = solverSettingsFrom(values);
    HairCurves targets;
    std::vector<float> scales;
    std::vector<std::pair<std::size_t, std::uint64_t>> solving; // simulated strand, cache key
    std::unordered_map<std::uint64_t, SolvedRest> used;
    for (std::size_t i = 0; i < simulated.strandCount(); ++i) {
        const std::size_t strand = m_allStrands ? i : groom.keyStrand[i];
        const auto found = m_style->find(groom.strandIdentity(strand));
        if (found == m_style->end() || found->second.shape.size() < 2)
            continue;
        const std::uint64_t identity = found->first;
        const std::span<const glm::vec3> target = simulated.strand(i);
        const float scale
            = strandStiffnessScale(groom.regionStiffnessScale[groom.regionOfStrand[strand]], &found->second);
        ByteHash hash; // the target and the physics it is solved for
        hash.add(target.data(), target.size_bytes());
        hash.add(scale);
        hash.add(settings.stiffness);
        hash.add(settings.gravity);
        hash.add(settings.substeps);
        hash.add(settings.timeStepSeconds);
        hash.add(settings.dampingPerSecond);
        hash.add(settings.dragPerSecond);
        hash.add(settings.velocityCorrection);
        hash.add(settings.globalShape);
        const std::uint64_t key = hash.value;
        if (const auto cached = m_restCache.find(identity);
            cached != m_restCache.end() && cached->second.key == key && cached->second.rest.size() == target.size()) {
            std::copy(cached->second.rest.begin(), cached->second.rest.end(), simulated.strandForWrite(i).begin());
            used.emplace(identity, std::move(cached->second));
            continue;
        }
        const std::size_t t = targets.addStrand(static_cast<std::uint32_t>(target.size()));
        std::copy(target.begin(), target.end(), targets.strandForWrite(t).begin());
        scales.push_back(scale);
        solving.emplace_back(i, key);
    }
    if (!solving.empty()) {
        const RestShapeSolution solution = solveRestShapes(targets, scales, settings, m_sdf);
        m_worstRestGap = solution.worstGapMetres;
        for (std::size_t t = 0; t < solving.size(); ++t) {
            const auto [i, key] = solving[t];
            const std::span<const glm::vec3> rest = solution.rest.strand(t);
            std::copy(rest.begin(), rest.end(), simulated.strandForWrite(i).begin());
            const std::size_t strand = m_allStrands ? i : groom.keyStrand[i];
            used[groom.strandIdentity(strand)] = SolvedRest{ key, { rest.begin(), rest.end() } };
        }
    }
    m_restCache = std::move(used);
}

void HairSimulation::setStyle(StyleEditsPtr style)
{
    saveWetness();
    auto applied = [](const StyleEditsPtr& edits, std::uint64_t id) {
        if (!edits)
            return 0.0f;
        const auto found = edits->find(id);
        return found == edits->end() ? 0.0f : found->second.wetness;
    };
    auto setLive = [this](std::uint64_t id, float wetness) {
        if (wetness > 0.0f)
            m_liveWetness[id] = wetness;
        else
            m_liveWetness.erase(id);
    };
    if (style)
        for (const auto& [id, s] : *style)
            if (s.wetness != applied(m_style, id))
                setLive(id, s.wetness);
    if (m_style)
        for (const auto& [id, s] : *m_style)
            if (s.wetness != applied(style, id))
                setLive(id, applied(style, id));
    m_style = std::move(style);
    restoreWetness();
    if (m_wetnessInSolver.size() == m_solver.strandCount())
        updateMaterial(false);
}

void HairSimulation::saveWetness()
{
    if (m_wetness.size() != m_groom.wispCount())
        return;
    for (std::size_t w = 0; w < m_wetness.size(); ++w) {
        const std::uint64_t id = m_groom.strandIdentity(m_groom.keyStrand[w]);
        if (m_wetness[w] > 0.0f)
            m_liveWetness[id] = m_wetness[w];
        else
            m_liveWetness.erase(id);
    }
}

void HairSimulation::restoreWetness()
{
    m_wetness.assign(m_groom.wispCount(), 0.0f);
    if (m_liveWetness.empty())
        return;
    for (std::size_t w = 0; w < m_wetness.size(); ++w)
        if (const auto found = m_liveWetness.find(m_groom.strandIdentity(m_groom.keyStrand[w]));
            found != m_liveWetness.end())
            m_wetness[w] = found->second;
}

bool HairSimulation::anyWet() const
{
    return std::any_of(m_wetness.begin(), m_wetness.end(), [](float w) { return w > 0.0f; });
}

void HairSimulation::strandWetness(std::vector<float>& out) const
{
    out.resize(m_groom.strandCount());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = m_wetness.empty() ? 0.0f : m_wetness[m_groom.wispOf[i]];
}

// Wet hair's material in the solver: softer (stiffness) and less volume (the density it keeps), where its wetness moved
// by more than a little since the solver was last told, so a slow drying costs a few updates a second, not one per
// step.
void HairSimulation::updateMaterial(bool force)
{
    const std::size_t count = m_solver.strandCount();
    if (m_baseStiffness.size() != count || m_wetnessInSolver.size() != count || m_baseVolumeFactor.size() != count)
        return;
    bool changed = force;
    for (std::size_t s = 0; s < count && !changed; ++s) {
        const float w = m_wetness.empty() ? 0.0f : m_wetness[wispOfSimulated(s)];
        changed = std::abs(w - m_wetnessInSolver[s]) > 0.02f || (w == 0.0f) != (m_wetnessInSolver[s] == 0.0f);
    }
    if (!changed)
        return;
    std::vector<float> scales(count), volumeTargets(count);
    for (std::size_t s = 0; s < count; ++s) {
        const float w = m_wetness.empty() ? 0.0f : m_wetness[wispOfSimulated(s)];
        m_wetnessInSolver[s] = w;
        scales[s] = m_baseStiffness[s] * wetStiffnessFactor(w);
        volumeTargets[s] = std::max(m_baseVolumeFactor[s], wetVolumeFactor(w));
    }
    // Both are sized to the solver's strands, which the solver cannot refuse.
    [[maybe_unused]] const bool accepted
        = m_solver.setStiffnessScales(scales).empty() && m_solver.setVolumeTargetScales(volumeTargets).empty();
    assert(accepted);
}

void HairSimulation::wet(std::span<const std::uint64_t> keyIdentities, float wetness)
{
    if (!(wetness > 0.0f) || keyIdentities.empty())
        return;
    wetness = std::min(wetness, 1.0f);
    const std::unordered_set<std::uint64_t> wanted(keyIdentities.begin(), keyIdentities.end());
    for (std::size_t w = 0; w < m_wetness.size(); ++w)
        if (wanted.count(m_groom.strandIdentity(m_groom.keyStrand[w])))
            m_wetness[w] = std::max(m_wetness[w], wetness);
    updateMaterial(false);
}

bool HairSimulation::holdStrand(std::uint64_t identity, std::span<const glm::vec3> positions)
{
    const auto found = m_simulatedOf.find(identity);
    return found != m_simulatedOf.end() && m_solver.setStrandState(found->second, positions, positions);
}

void HairSimulation::step()
{
    const bool wet = anyWet();
    if (!m_dryers.empty() || wet || m_airInSolver) {
        const std::size_t count = m_solver.strandCount();
        const float dt = m_solver.settings().timeStepSeconds;
        std::vector<glm::vec3> air;
        if (!m_dryers.empty()) {
            // The air a strand feels: the mean over three points along it (a third, two thirds, the tip).
            std::vector<glm::vec3> positions;
            m_solver.copyPositions(positions);
            const std::size_t points = count > 0 ? positions.size() / count : 0;
            air.resize(count);
            for (std::size_t s = 0; s < count && points >= 2; ++s) {
                const glm::vec3* p = positions.data() + s * points;
                for (const HairDryer& dryer : m_dryers) // the head shadows the jet
                    air[s] += (dryerAirAt(dryer, p[points / 3], m_sdf.get())
                                  + dryerAirAt(dryer, p[2 * points / 3], m_sdf.get())
                                  + dryerAirAt(dryer, p[points - 1], m_sdf.get()))
                        / 3.0f;
            }
        }
        for (std::size_t w = 0; w < m_wetness.size(); ++w) {
            if (m_wetness[w] <= 0.0f)
                continue;
            const std::size_t key = m_allStrands ? m_groom.keyStrand[w] : w;
            const float speed = air.empty() ? 0.0f : glm::length(air[key]);
            m_wetness[w] = std::max(0.0f, m_wetness[w] + dryingRate(m_wetness[w], speed, m_dryingHalfLife) * dt);
            if (m_wetness[w] < kDryBelow)
                m_wetness[w] = 0.0f; // still-air drying never ends on its own
        }
        std::vector<float> drag;
        if (wet) {
            drag.resize(count);
            for (std::size_t s = 0; s < count; ++s)
                drag[s] = wetDragFactor(m_wetness[wispOfSimulated(s)]);
        }
        // Sized to the solver's strands (drag) and the drawn ones (air), as it asks.
        [[maybe_unused]] const bool accepted = m_solver.setStrandAir(drag, air).empty();
        assert(accepted);
        m_airInSolver = !m_dryers.empty() || wet;
        updateMaterial(false);
    }
    m_solver.step();
}

int HairSimulation::drapeAtRest(int maxSteps, float stillMetres, const std::function<bool()>& cancelled, int substeps)
{
    m_solver.resetToRest();
    const SolverSettings settings = m_solver.settings();
    SolverSettings still = settings;
    still.wind = glm::vec3(0.0f);
    still.turbulence = 0.0f;
    constexpr float kDrapeDampingPerSecond = 8.0f; // about critically damped for a 25 cm strand
    still.dampingPerSecond = std::max(settings.dampingPerSecond, kDrapeDampingPerSecond);
    if (substeps > 0)
        still.substeps = substeps;
    if (!m_solver.setSettings(still).empty())
        return 0;
    // No dryer; wet hair keeps its softness (the stiffness scales). Empty spans are always taken.
    [[maybe_unused]] const bool noAir = m_solver.setStrandAir({}, {}).empty();
    assert(noAir);
    m_airInSolver = false; // step() gives the air back where wetness or a dryer needs it
    std::vector<glm::vec3> before, now;
    m_solver.copyPositions(before);
    int steps = 0;
    while (steps < maxSteps && !(cancelled && cancelled())) {
        m_solver.step();
        if (++steps % 10 != 0)
            continue;
        m_solver.copyPositions(now);
        float moved = 0.0f;
        for (std::size_t i = 0; i < now.size(); ++i)
            moved = std::max(moved, glm::distance(now[i], before[i]));
        if (moved < stillMetres)
            break;
        before.swap(now);
    }
    // The settings the solver held before the drape: accepted then, accepted now.
    [[maybe_unused]] const bool restored = m_solver.setSettings(settings).empty();
    assert(restored);
    return steps;
}

std::string HairSimulation::groomRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
    const ParameterValues& values, const Groom* previous, Groom& out, std::vector<StrandLook>& looks)
{
    std::vector<GroomRegionInput> inputs;
    looks.clear();
    for (const GrowthRegion* r : growingRegions(regions, soloId)) {
        if (std::string error = validateRegion(*r, m_head->mesh().positions.size()); !error.empty())
            return error;
        inputs.push_back({ r->id, r->weights, groomSettingsFrom(r->values), r->values.getFloat(Param::StiffnessScale),
            r->importedStrands.get() });
        looks.push_back({ r->rootColour, r->tipColour, r->values.getFloat(Param::HairThickness) });
    }
    GroomResult result = m_builder.build(
        m_head->mesh(), inputs, groomSettingsFrom(values), m_sdf.get(), previous, &m_head->bvh(), m_style.get());
    if (!result.ok())
        return result.error;
    m_groomWarnings = std::move(result.warnings);
    out = std::move(result.groom);
    return {};
}

std::string HairSimulation::setup(const TriangleMesh& head, const std::vector<GrowthRegion>& regions,
    std::uint32_t soloId, const ParameterValues& values)
{
    return setup(std::make_shared<const HeadModel>(head), regions, soloId, values);
}

std::string HairSimulation::setup(
    const TriangleMesh& head, std::span<const float> growthWeights, const ParameterValues& values)
{
    return setup(std::make_shared<const HeadModel>(head), growthWeights, values);
}

std::string HairSimulation::setup(
    HeadModelPtr head, const std::vector<GrowthRegion>& regions, std::uint32_t soloId, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    if (std::string error = prepareHead(std::move(head)); !error.empty())
        return error;
    Groom groom;
    std::vector<StrandLook> looks;
    if (std::string error = groomRegions(regions, soloId, values, nullptr, groom, looks); !error.empty())
        return error;
    m_looks = std::move(looks);
    m_carried = 0;
    m_started = groom.strandCount();
    return start(std::move(groom), values);
}

std::string HairSimulation::regroom(
    const std::vector<GrowthRegion>& regions, std::uint32_t soloId, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    Groom groom;
    std::vector<StrandLook> looks;
    if (std::string error = groomRegions(regions, soloId, values, &m_groom, groom, looks); !error.empty())
        return error;

    // The simulated strands of the old groom, by identity, with their motion and their roots. A
    // pore's identity is its index in its region's pore layout, and a new density lays out other
    // pores: the same identity is the same strand only where it grows from the same place.
    const bool allBefore = m_allStrands;
    std::unordered_map<std::uint64_t, std::uint32_t> before;
    const auto simulated = [](const Groom& g, bool all, std::size_t i) { return all ? i : g.keyStrand[i]; };
    const std::size_t countBefore = allBefore ? m_groom.strandCount() : m_groom.wispCount();
    std::vector<glm::vec3> rootsBefore(countBefore);
    for (std::size_t i = 0; i < countBefore; ++i) {
        before.emplace(m_groom.strandIdentity(simulated(m_groom, allBefore, i)), static_cast<std::uint32_t>(i));
        rootsBefore[i] = m_groom.rootPositions[simulated(m_groom, allBefore, i)];
    }
    std::vector<glm::vec3> positions, previous;
    m_solver.copyState(positions, previous);
    const std::vector<std::uint32_t> offsetsBefore = [&] {
        std::vector<std::uint32_t> o{ 0 };
        for (std::size_t i = 0; i < countBefore; ++i)
            o.push_back(o.back() + static_cast<std::uint32_t>(m_groom.settings.segments + 1));
        return o;
    }();

    if (std::string error = start(std::move(groom), values); !error.empty())
        return error; // start refuses before changing the solver
    m_looks = std::move(looks);
    m_carried = m_started = 0;
    const std::size_t countNow = m_allStrands ? m_groom.strandCount() : m_groom.wispCount();
    for (std::size_t i = 0; i < countNow; ++i) {
        const auto it = before.find(m_groom.strandIdentity(simulated(m_groom, m_allStrands, i)));
        bool carried = false;
        if (it != before.end() && offsetsBefore[it->second + 1] <= positions.size()
            && glm::distance(rootsBefore[it->second], m_groom.rootPositions[simulated(m_groom, m_allStrands, i)])
                < 1e-6f) {
            const std::size_t first = offsetsBefore[it->second];
            const std::size_t count = offsetsBefore[it->second + 1] - first;
            const std::span<const glm::vec3> was = std::span(positions).subspan(first, count);
            const float length = m_groom.lengths[simulated(m_groom, m_allStrands, i)];
            if (std::abs(strandLength(was) - length) > 1e-3f) {
                // Cut, grown or shrunk: the strand keeps its place, at its new length, at rest.
                const std::vector<glm::vec3> now = resampleByArcLength(shapeWithLength(was, length), count);
                carried = now.size() == count && m_solver.setStrandState(i, now, now);
            } else {
                carried = m_solver.setStrandState(i, was, std::span(previous).subspan(first, count));
            }
        }
        ++(carried ? m_carried : m_started);
    }
    return {};
}

std::string HairSimulation::setup(
    HeadModelPtr head, std::span<const float> growthWeights, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    const GroomSettings groomSettings = groomSettingsFrom(values);
    if (std::string error = validateGroomSettings(groomSettings); !error.empty())
        return error;
    if (std::string error = prepareHead(std::move(head)); !error.empty())
        return error;
    GroomResult groom = buildGroom(m_head->mesh(), growthWeights, groomSettings, m_sdf.get());
    if (!groom.ok())
        return groom.error;
    m_groomWarnings = std::move(groom.warnings);
    m_looks.clear(); // one region, in the viewport's own colours
    return start(std::move(groom.groom), values);
}

std::string HairSimulation::setupGrid(const TriangleMesh& head, int width, int height, int particlesPerStrand,
    float lengthMetres, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    if (std::string error = prepareHead(std::make_shared<const HeadModel>(head)); !error.empty())
        return error;
    GroomResult groom
        = buildGridGroom(m_head->mesh(), m_head->bvh(), width, height, particlesPerStrand, lengthMetres, m_sdf.get());
    if (!groom.ok())
        return groom.error;
    ParameterValues all = values;
    all.set(Param::SimulateAllStrands, 1.0);
    m_looks.clear();
    return start(std::move(groom.groom), all);
}

std::string HairSimulation::applyForces(const ParameterValues& values)
{
    if (std::string error = m_solver.setSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    m_dryingHalfLife = values.getFloat(Param::DryingTime);
    setBody(values);
    return {};
}

void HairSimulation::setBody(const ParameterValues& values)
{
    m_bodyOn = values.get(Param::Body) != 0.0;
    m_solver.setCapsules(m_bodyOn ? m_body : std::vector<Capsule>{});
}

void HairSimulation::buildFrame(HairCurves& out) const
{
    out.offsets = m_groom.rest.offsets;
    if (m_allStrands) {
        m_solver.copyPositions(out.positions);
        return;
    }
    std::vector<glm::vec3> keys;
    m_solver.copyPositions(keys);
    out.positions.resize(m_groom.rest.positions.size());
    std::vector<float> wetClump;
    if (anyWet()) {
        wetClump.resize(m_wetness.size());
        for (std::size_t w = 0; w < m_wetness.size(); ++w)
            wetClump[w] = wetClumping(m_wetness[w]);
    }
    // Members are rebuilt in world space: the head's transform turns their root offsets and places
    // the head and the body they are kept out of (a moving head, HeadMotion.h).
    const glm::mat4& headToWorld = m_solver.headTransform();
    const glm::mat3 rotation(headToWorld);
    const glm::vec3 translation(headToWorld[3]);
    MemberContact contact;
    contact.head = m_sdf.get();
    contact.headRotation = rotation;
    contact.headTranslation = translation;
    contact.offsetMetres = m_solver.settings().hairOffsetMetres;
    std::vector<Capsule> bodyWorld;
    if (m_bodyOn) {
        bodyWorld.reserve(m_body.size());
        for (const Capsule& c : m_body)
            bodyWorld.push_back({ rotation * c.a + translation, rotation * c.b + translation, c.radiusMetres });
        contact.body = bodyWorld;
    }
    buildMembers(m_groom, keys, rotation, out, wetClump, &contact);
}

} // namespace wisp
