#pragma once
// One head with its groom, its collider and a running solver: what the CLI, the editor's
// simulation thread and the tests drive. Keys are simulated (or every strand, by parameter);
// frames hold every drawn strand, members rebuilt from their key (Ward et al.'s level of detail).
//
// Thread: owned and called by one thread.

#include "sim/Frame.h"
#include "sim/Groom.h"
#include "sim/GrowthRegion.h"
#include "sim/Parameters.h"
#include "sim/Solver.h"
#include "sim/TriangleMesh.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace wisp {

class SignedDistanceField;
class MeshBvh;

class HairSimulation {
public:
    explicit HairSimulation(int threadCount = 0);
    ~HairSimulation();

    // Grooms `head` where `growthWeights` allow (one region with the Wisp-group entries of
    // `values`), bakes its collider and starts the solver at rest. On error returns the message and
    // keeps what it had.
    std::string setup(const TriangleMesh& head, std::span<const float> growthWeights, const ParameterValues& values);
    // The editor's groom: the growing regions of `regions` (see growingRegions) on `head`.
    std::string setup(const TriangleMesh& head, const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
                      const ParameterValues& values);
    // Regrooms on the same head (painted weights, wisp or groom parameters changed) while the hair
    // moves: every simulated strand that still exists keeps its motion, new strands start at rest,
    // removed ones vanish, nothing else jumps. On error returns the message and keeps running as before.
    std::string regroom(const std::vector<GrowthRegion>& regions, std::uint32_t soloId, const ParameterValues& values);
    // Strands whose motion the last regroom carried over, and strands it started at rest.
    std::size_t carriedStrands() const { return m_carried; }
    std::size_t startedStrands() const { return m_started; }
    const GroomBuilder& groomBuilder() const { return m_builder; }

    // How each groom region's hair looks (per entry of groom().regionIds).
    const std::vector<StrandLook>& looks() const { return m_looks; }
    // The first paper's grid layout (see buildGridGroom); every strand simulated.
    std::string setupGrid(const TriangleMesh& head, int width, int height, int particlesPerStrand, float lengthMetres,
                          const ParameterValues& values);
    // Forces and solver parameters only; takes effect at the next step.
    std::string applyForces(const ParameterValues& values);

    void step() { m_solver.step(); }
    void resetToRest() { m_solver.resetToRest(); }

    // Every drawn strand in world space, in the groom's strand order.
    void buildFrame(HairCurves& out) const;
    // Only the simulated strands (keys, or all), world space.
    void copySimulated(std::vector<glm::vec3>& out) const { m_solver.copyPositions(out); }

    const Groom& groom() const { return m_groom; }
    const TriangleMesh& head() const { return m_head; }
    const SignedDistanceField* collider() const { return m_sdf.get(); }
    const MeshBvh& bvh() const { return *m_bvh; }
    Solver& solver() { return m_solver; }
    const Solver& solver() const { return m_solver; }
    bool simulatesAllStrands() const { return m_allStrands; }

    // Collider resolution: about this many cells across the head's largest extent.
    static constexpr float kColliderCellsAcross = 96.0f;

private:
    std::string prepareHead(const TriangleMesh& head);
    std::string start(Groom groom, const ParameterValues& values);
    std::string groomRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId, const ParameterValues& values,
                             const Groom* previous, Groom& out, std::vector<StrandLook>& looks);
    std::string setStrandStiffness(const Groom& groom);

    Solver m_solver;
    TriangleMesh m_head;
    std::shared_ptr<SignedDistanceField> m_sdf;
    std::unique_ptr<MeshBvh> m_bvh;
    Groom m_groom;
    GroomBuilder m_builder;
    std::vector<StrandLook> m_looks;
    bool m_allStrands = false;
    std::size_t m_carried = 0;
    std::size_t m_started = 0;
};

}  // namespace wisp
