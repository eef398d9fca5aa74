#include "sim/HairSimulation.h"

#include "sim/MeshBvh.h"
#include "sim/SignedDistanceField.h"
#include "sim/SolverSettings.h"

#include <glm/common.hpp>

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
