#pragma once
// One head with its groom, its collider and a running solver: what the CLI, the editor's
// simulation thread and the tests drive. Keys are simulated (or every strand, by parameter);
// frames hold every drawn strand, members rebuilt from their key (Ward et al.'s level of detail).
//
// Thread: owned and called by one thread.

#include "sim/geometry/HeadModel.h"
#include "sim/geometry/TriangleMesh.h"
#include "sim/groom/Groom.h"
#include "sim/groom/GrowthRegion.h"
#include "sim/params/Parameters.h"
#include "sim/solver/Frame.h"
#include "sim/solver/Solver.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StyleEdits.h"

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
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
    [[nodiscard]] std::string setup(
        const TriangleMesh& head, std::span<const float> growthWeights, const ParameterValues& values);
    // The editor's groom: the growing regions of `regions` (see growingRegions) on `head`.
    [[nodiscard]] std::string setup(const TriangleMesh& head, const std::vector<GrowthRegion>& regions,
        std::uint32_t soloId, const ParameterValues& values);
    // The same on a head model already built (the editor's document shares its BVH): only the
    // collider is baked here. `head` must not be null.
    [[nodiscard]] std::string setup(
        HeadModelPtr head, std::span<const float> growthWeights, const ParameterValues& values);
    [[nodiscard]] std::string setup(HeadModelPtr head, const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
        const ParameterValues& values);
    // Regrooms on the same head (painted weights, wisp or groom parameters changed) while the hair
    // moves: every simulated strand that still exists keeps its motion, new strands start at rest,
    // removed ones vanish, nothing else jumps. On error returns the message and keeps running as before.
    [[nodiscard]] std::string regroom(
        const std::vector<GrowthRegion>& regions, std::uint32_t soloId, const ParameterValues& values);
    // Strands whose motion the last regroom carried over, and strands it started at rest.
    std::size_t carriedStrands() const { return m_carried; }
    std::size_t startedStrands() const { return m_started; }
    const GroomBuilder& groomBuilder() const { return m_builder; }
    // What the last groom built wants the artist to know (GroomResult::warnings).
    const std::vector<std::string>& groomWarnings() const { return m_groomWarnings; }

    // How each groom region's hair looks (per entry of groom().regionIds).
    const std::vector<StrandLook>& looks() const { return m_looks; }
    // The first paper's grid layout (see buildGridGroom); every strand simulated.
    [[nodiscard]] std::string setupGrid(const TriangleMesh& head, int width, int height, int particlesPerStrand,
        float lengthMetres, const ParameterValues& values);
    // Forces and solver parameters only; takes effect at the next step.
    [[nodiscard]] std::string applyForces(const ParameterValues& values);

    // --- Salon edits (StyleEdits.h) --------------------------------------------------------------
    // The artist's edits by strand identity; used by the next setup or regroom (call one after).
    // Strands whose applied wetness differs from the edits before become that wet now; the others
    // keep drying where they are.
    void setStyle(StyleEditsPtr style);
    const StyleEditsPtr& style() const { return m_style; }
    // The blow-dryers while the artist holds one (two with X symmetry); none when put down. Their
    // air adds up. Applies from the next step.
    void setDryers(std::vector<HairDryer> dryers) { m_dryers = std::move(dryers); }
    // Still-air drying half-life, seconds (the drying_time parameter; applyForces sets it).
    float dryingHalfLifeSeconds() const { return m_dryingHalfLife; }
    // Live wetness 0..1 of each wisp (groom order), and of each drawn strand (its wisp's).
    const std::vector<float>& wispWetness() const { return m_wetness; }
    bool anyWet() const;
    void strandWetness(std::vector<float>& out) const;
    // The wet brush, live: the wisps whose key hairs have these identities become at least this
    // wet (0..1) now.
    void wet(std::span<const std::uint64_t> keyIdentities, float wetness);
    // Holds a simulated strand (by identity) at `positions` (world), at rest: the comb while it
    // drags. False when no simulated strand has that identity or the point count differs.
    bool holdStrand(std::uint64_t identity, std::span<const glm::vec3> positions);
    // Combed strands whose solved rest shape still misses the comb, and by how much (metres).
    float worstRestGapMetres() const { return m_worstRestGap; }

    // Dries, blows (the dryer) and updates what wetness changes, then advances one step.
    void step();
    void resetToRest() { m_solver.resetToRest(); }
    // Back at the rest shape, then settled under gravity alone (no wind, gusts or dryer; damped
    // harder than the hair is, which changes how fast it settles, not where) until no particle
    // moves more than `stillMetres` over 10 steps, or `maxSteps` ran, or `cancelled` says so: the
    // hair as it hangs at rest, which is what an artist expects "rest" to look like (the groom's
    // rest shape is the shape without gravity). Forces and per-strand air are as before after it.
    // Returns the steps run. Deterministic, like step(). `substeps` (0: the solver's now) drapes at
    // that substep count: the editor's pacer may have lowered the running one, and the same rest
    // must look the same after New and after any Reset.
    int drapeAtRest(int maxSteps = kDrapeMaxSteps, float stillMetres = 2e-4f,
        const std::function<bool()>& cancelled = {}, int substeps = 0);
    static constexpr int kDrapeMaxSteps = 600;

    // Every drawn strand in world space, in the groom's strand order (wet wisps clumped).
    void buildFrame(HairCurves& out) const;
    // Only the simulated strands (keys, or all), world space.
    void copySimulated(std::vector<glm::vec3>& out) const { m_solver.copyPositions(out); }

    const Groom& groom() const { return m_groom; }
    const TriangleMesh& head() const { return m_head->mesh(); }
    const HeadModelPtr& headModel() const { return m_head; }
    const SignedDistanceField* collider() const { return m_sdf.get(); }
    const MeshBvh& bvh() const { return m_head->bvh(); }
    Solver& solver() { return m_solver; }
    const Solver& solver() const { return m_solver; }
    bool simulatesAllStrands() const { return m_allStrands; }
    // The neck and shoulders under this head (Body.h), collided with while the `body` parameter is on.
    const std::vector<Capsule>& body() const { return m_body; }

    // A comb sets the hair, as combing with product does: a combed strand is at least this many
    // times as stiff as its region (0.25, the default, becomes 0.6, which holds a lock combed
    // sideways; the solver carries a lock's weight to its root, so default hair could not).
    static constexpr float kCombSetsStiffness = 2.4f;
    // A comb also presses the hair together: a combed strand keeps up to this many times the density
    // of the hair around it (the volume grid's target, as soaked hair does) before the grid pushes it,
    // so the grid's push vanishes at the combed rest shape and does not undo the comb (README, "Hair
    // volume"; measured by StylingTest.CombedHairFollowsTheStroke... with volume on).
    static constexpr float kCombedVolumeFactor = 3.0f;
    // A strand's stiffness scale: its region's, times its hairspray, at least the comb's set.
    static float strandStiffnessScale(float regionScale, const StrandStyle* style);

    // Hair this little wet is dry (drying in still air is exponential and would never end).
    static constexpr float kDryBelow = 0.01f;
    // Collider resolution: about this many cells across the head's largest extent.
    static constexpr float kColliderCellsAcross = 96.0f;

private:
    [[nodiscard]] std::string prepareHead(HeadModelPtr head);
    [[nodiscard]] std::string start(Groom groom, const ParameterValues& values);
    [[nodiscard]] std::string groomRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId,
        const ParameterValues& values, const Groom* previous, Groom& out, std::vector<StrandLook>& looks);
    [[nodiscard]] std::string setStrandStiffness(const Groom& groom);
    void solveCombedRest(const Groom& groom, const ParameterValues& values, HairCurves& simulated);
    const StrandStyle* styleOf(std::size_t strand) const;
    std::size_t wispOfSimulated(std::size_t s) const { return m_allStrands ? m_groom.wispOf[s] : s; }
    void saveWetness(); // live per-wisp wetness into m_liveWetness (before the groom changes)
    void restoreWetness(); // and back, for the new groom's wisps
    void updateMaterial(bool force);
    void setBody(const ParameterValues& values); // the solver collides with m_body or not

    Solver m_solver;
    HeadModelPtr m_head; // never null: an empty head until the first setup
    std::shared_ptr<SignedDistanceField> m_sdf;
    std::vector<Capsule> m_body; // head space
    bool m_bodyOn = false; // the solver and the drawn members collide with m_body
    Groom m_groom;
    GroomBuilder m_builder;
    std::vector<std::string> m_groomWarnings;
    std::vector<StrandLook> m_looks;
    bool m_allStrands = false;
    std::size_t m_carried = 0;
    std::size_t m_started = 0;

    StyleEditsPtr m_style;
    std::unordered_map<std::uint64_t, float> m_liveWetness; // by key-hair identity, nonzero only
    std::vector<float> m_wetness; // per wisp of m_groom
    std::vector<float> m_baseStiffness; // per simulated strand: region x hairspray
    std::vector<float> m_baseVolumeFactor; // per simulated strand: 1, or the comb's
    std::vector<float> m_wetnessInSolver; // per simulated strand: as last given to the solver
    bool m_airInSolver = false; // the solver has per-strand air set
    std::vector<HairDryer> m_dryers;
    float m_dryingHalfLife = 120.0f;
    std::unordered_map<std::uint64_t, std::uint32_t> m_simulatedOf; // identity -> solver strand
    struct SolvedRest {
        std::uint64_t key = 0; // hash of the target and the physics it was solved for
        std::vector<glm::vec3> rest;
    };
    std::unordered_map<std::uint64_t, SolvedRest> m_restCache; // by identity
    float m_worstRestGap = 0.0f;
};

} // namespace wisp
