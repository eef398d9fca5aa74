#include "sim/HairSimulation.h"

#include "sim/MeshBvh.h"
#include "sim/SignedDistanceField.h"
#include "sim/SolverSettings.h"

#include <glm/common.hpp>

#include <unordered_map>

namespace wisp {

HairSimulation::HairSimulation(int threadCount) : m_solver(threadCount), m_bvh(std::make_unique<MeshBvh>()) {}
HairSimulation::~HairSimulation() = default;

std::string HairSimulation::prepareHead(const TriangleMesh& head)
{
    if (std::string error = validateMesh(head); !error.empty())
        return "head: " + error;
    const Aabb box = boundsOf(head);
    const float extent = glm::max(box.size().x, glm::max(box.size().y, box.size().z));
    std::string error;
    // The margin covers the hair offset and curls lying on the skin; beyond it the field is clamped.
    auto sdf = std::make_shared<SignedDistanceField>(
        SignedDistanceField::bake(head, extent / kColliderCellsAcross, 0.1f * extent + 0.01f, &error));
    if (sdf->empty())
        return "head: cannot build its collider: " + error;
    m_head = head;
    m_sdf = std::move(sdf);
    m_bvh = std::make_unique<MeshBvh>(m_head);
    m_builder.forgetHead();
    return {};
}

std::string HairSimulation::start(Groom groom, const ParameterValues& values)
{
    SolverSettings settings = solverSettingsFrom(values);
    if (std::string error = validateSolverSettings(settings); !error.empty())
        return error;
    m_allStrands = values.get(Param::SimulateAllStrands) != 0.0;
    const HairCurves simulated = m_allStrands ? groom.rest : keyRestCurves(groom);
    if (std::string error = m_solver.setStrands(simulated); !error.empty())
        return error;
    m_solver.setSettings(settings);
    m_solver.setCollider(m_sdf);
    m_groom = std::move(groom);
    return setStrandStiffness(m_groom);
}

std::string HairSimulation::setStrandStiffness(const Groom& groom)
{
    std::vector<float> scales;
    scales.reserve(m_solver.strandCount());
    if (m_allStrands)
        for (std::size_t i = 0; i < groom.strandCount(); ++i)
            scales.push_back(groom.regionStiffnessScale[groom.regionOfStrand[i]]);
    else
        for (std::uint32_t k : groom.keyStrand)
            scales.push_back(groom.regionStiffnessScale[groom.regionOfStrand[k]]);
    return m_solver.setStiffnessScales(scales);
}

std::string HairSimulation::groomRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
                                         const ParameterValues& values, const Groom* previous, Groom& out,
                                         std::vector<StrandLook>& looks)
{
    std::vector<GroomRegionInput> inputs;
    looks.clear();
    for (const GrowthRegion* r : growingRegions(regions, soloId)) {
        if (std::string error = validateRegion(*r, m_head.positions.size()); !error.empty())
            return error;
        inputs.push_back({r->id, r->weights, groomSettingsFrom(r->values), r->values.getFloat(Param::StiffnessScale),
                          r->importedStrands.get()});
        looks.push_back({r->rootColour, r->tipColour});
    }
    GroomResult result = m_builder.build(m_head, inputs, groomSettingsFrom(values), m_sdf.get(), previous, m_bvh.get());
    if (!result.ok())
        return result.error;
    out = std::move(result.groom);
    return {};
}

std::string HairSimulation::setup(const TriangleMesh& head, const std::vector<GrowthRegion>& regions,
                                  std::uint32_t soloId, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    if (std::string error = prepareHead(head); !error.empty())
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

std::string HairSimulation::regroom(const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
                                    const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    Groom groom;
    std::vector<StrandLook> looks;
    if (std::string error = groomRegions(regions, soloId, values, &m_groom, groom, looks); !error.empty())
        return error;

    // The simulated strands of the old groom, by identity, with their motion.
    const bool allBefore = m_allStrands;
    std::unordered_map<std::uint64_t, std::uint32_t> before;
    const auto simulated = [](const Groom& g, bool all, std::size_t i) { return all ? i : g.keyStrand[i]; };
    const std::size_t countBefore = allBefore ? m_groom.strandCount() : m_groom.wispCount();
    for (std::size_t i = 0; i < countBefore; ++i)
        before.emplace(m_groom.strandIdentity(simulated(m_groom, allBefore, i)), static_cast<std::uint32_t>(i));
    std::vector<glm::vec3> positions, previous;
    m_solver.copyState(positions, previous);
    const std::vector<std::uint32_t> offsetsBefore = [&] {
        std::vector<std::uint32_t> o{0};
        for (std::size_t i = 0; i < countBefore; ++i)
            o.push_back(o.back() + static_cast<std::uint32_t>(m_groom.settings.segments + 1));
        return o;
    }();

    if (std::string error = start(std::move(groom), values); !error.empty())
        return error;  // start refuses before changing the solver
    m_looks = std::move(looks);
    m_carried = m_started = 0;
    const std::size_t countNow = m_allStrands ? m_groom.strandCount() : m_groom.wispCount();
    for (std::size_t i = 0; i < countNow; ++i) {
        const auto it = before.find(m_groom.strandIdentity(simulated(m_groom, m_allStrands, i)));
        bool carried = false;
        if (it != before.end() && offsetsBefore[it->second + 1] <= positions.size()) {
            const std::size_t first = offsetsBefore[it->second];
            const std::size_t count = offsetsBefore[it->second + 1] - first;
            carried = m_solver.setStrandState(i, std::span(positions).subspan(first, count),
                                              std::span(previous).subspan(first, count));
        }
        ++(carried ? m_carried : m_started);
    }
    return {};
}

std::string HairSimulation::setup(const TriangleMesh& head, std::span<const float> growthWeights,
                                  const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    const GroomSettings groomSettings = groomSettingsFrom(values);
    if (std::string error = validateGroomSettings(groomSettings); !error.empty())
        return error;
    if (std::string error = prepareHead(head); !error.empty())
        return error;
    GroomResult groom = buildGroom(m_head, growthWeights, groomSettings, m_sdf.get());
    if (!groom.ok())
        return groom.error;
    m_looks.clear();  // one region, in the viewport's own colours
    return start(std::move(groom.groom), values);
}

std::string HairSimulation::setupGrid(const TriangleMesh& head, int width, int height, int particlesPerStrand,
                                      float lengthMetres, const ParameterValues& values)
{
    if (std::string error = validateSolverSettings(solverSettingsFrom(values)); !error.empty())
        return error;
    if (std::string error = prepareHead(head); !error.empty())
        return error;
    GroomResult groom = buildGridGroom(m_head, *m_bvh, width, height, particlesPerStrand, lengthMetres, m_sdf.get());
    if (!groom.ok())
        return groom.error;
    ParameterValues all = values;
    all.set(Param::SimulateAllStrands, 1.0);
    m_looks.clear();
    return start(std::move(groom.groom), all);
}

std::string HairSimulation::applyForces(const ParameterValues& values)
{
    return m_solver.setSettings(solverSettingsFrom(values));
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
    buildMembers(m_groom, keys, glm::mat3(1.0f), out);
}

}  // namespace wisp
