#pragma once
// The hair solver: strands are chains of particles pinned at the root, advanced with Verlet
// integration under gravity, implicit wind drag and per-particle gusts, bent toward their rest
// shape (BendingModel.h), kept inextensible by follow-the-leader with velocity correction, and
// put out of the head and the body last, keeping their segment length where the segment can reach
// (Coulomb friction there).
//
// Papers: Verlet step and wind (eq. 1-3 of "Real Time Physical Force-Driven Hair Animation");
// inextensibility by Dynamic Follow-The-Leader (Müller, Kim, Chentanez 2012, "Fast Simulation of
// Inextensible Hair and Fur"); bending as XPBD (Macklin, Müller, Chentanez 2016) toward local shape
// targets (Han & Harada 2012); friction as in Macklin et al. 2014, "Unified Particle Physics".
//
// Data-oriented: strands with the same particle count are packed 16 to a block, each block's
// particles interleaved so that one instruction advances the same particle of 16 strands. A block is
// the unit of parallel work, so results are bit-identical for any thread count.
//
// Thread: one owner thread calls everything (in the editor, the simulation thread).

#include "sim/geometry/HairCurves.h"
#include "sim/solver/SolverSettings.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace wisp {

class HairVolumeGrid;
class SignedDistanceField;
class ThreadPool;
struct StepConstants; // one step's settings as the kernels read them (SolverRows.h)

// A collider for neck and shoulders, head space; a sphere when a == b.
struct Capsule {
    glm::vec3 a{ 0.0f };
    glm::vec3 b{ 0.0f };
    float radiusMetres = 0.0f;
    bool operator==(const Capsule&) const = default;
};

class Solver {
public:
    // threadCount 0: one thread per core.
    explicit Solver(int threadCount = 0);
    ~Solver();
    Solver(const Solver&) = delete;
    Solver& operator=(const Solver&) = delete;

    // Rest shapes in head space; the first point of each strand is its root, pinned to the head.
    // Every strand needs at least 2 points and finite, non-coincident neighbours. Returns an error
    // (and keeps the previous strands) otherwise. Particles start at rest.
    [[nodiscard]] std::string setStrands(const HairCurves& rest);
    [[nodiscard]] std::string setSettings(const SolverSettings& settings);
    const SolverSettings& settings() const { return m_settings; }
    void setCollider(std::shared_ptr<const SignedDistanceField> headSdf); // null: no head collision
    bool hasCollider() const { return m_sdf != nullptr; }
    void setCapsules(std::vector<Capsule> capsules);
    std::size_t capsuleCount() const { return m_capsules.size(); }
    // Whether any strand bends: a bend share on some lane, as the last step set them (a stiffness
    // or stiffness scales of 0 leave a block limp); until a step sets them for the settings now,
    // whether the stiffness and some strand's scale ask for it.
    bool anyStrandBends() const;
    // Rigid transform (rotation + translation) from head space to world space; roots follow it.
    void setHeadTransform(const glm::mat4& headToWorld);
    const glm::mat4& headTransform() const { return m_headToWorld; }

    // Advances one time step (settings().substeps substeps).
    void step();
    // Puts every particle back at its rest position, at rest.
    void resetToRest();

    // Puts one particle somewhere (world space), at rest there. Roots stay pinned. For direct
    // manipulation, and for tests that need a broken strand.
    void moveParticle(std::size_t strand, std::size_t point, const glm::vec3& position);

    // Per strand (the layout of setStrands): multiplies settings().stiffness, the product capped at
    // 1 (a region's stiffness scale, hairspray). All 1 after setStrands.
    [[nodiscard]] std::string setStiffnessScales(std::span<const float> perStrand);

    // Per strand: scales the drag toward the wind (wet hair is heavier, so the same air moves it
    // less) and adds a wind of its own, m/s world space (a hair dryer's cone). An empty span means
    // 1 and no wind of its own. Both 1 and none after setStrands.
    [[nodiscard]] std::string setStrandAir(std::span<const float> dragScale, std::span<const glm::vec3> extraWind);

    // Hair-hair interaction (settings().volume > 0; HairVolumeGrid.h): per strand, how many drawn
    // strands it stands for (a key hair and its members; empty: 1 each), so the density matches
    // what is drawn; and the scalp area (m²) the drawn hair grows from, which with the hair's
    // length sets the density the hair keeps (0: estimated from the simulated roots). Both as
    // after setStrands until set again.
    [[nodiscard]] std::string setStrandVolume(std::span<const float> drawnStrands, float scalpAreaSquareMetres);
    // Per strand: multiplies the density the hair may reach before it pushes its neighbours away
    // (wet hair: above 1, so it takes less room). Empty: 1 for every strand.
    [[nodiscard]] std::string setVolumeTargetScales(std::span<const float> perStrand);
    // Drawn hair per scalp area (metres of hair per m²) and the density it keeps at this volume
    // (metres of hair per m³; 0 when the volume is off), for tests and the README.
    float hairPerScalpArea() const { return m_hairPerScalpArea; }
    float volumeTargetDensity() const;
    // The grid of the last step with volume on (null before one).
    const HairVolumeGrid* volumeGrid() const { return m_volumeGrid.get(); }
    // Grid passes (splat and finish) since construction: one per substep, or fewer where substeps
    // are shorter than the grid's refresh interval (Solver.cpp, kVolumeRefreshSeconds).
    std::uint64_t volumePasses() const { return m_volumePasses; }
    // The grid's level of detail at the strand's block (Solver::volumeSplat), its finest row: 1 where
    // every strand splats, k where every k-th one does; for tests.
    int volumeStrideOfStrand(std::size_t strand) const;
    // How many rows of the strand's block splat and are sampled as one, at their centroid
    // (Solver::volumeSplat): 1, or for a dense groom up to 4 (0 for no such strand).
    int volumeRowsPerSampleOfStrand(std::size_t strand) const;

    // World-space positions in the layout of the rest curves given to setStrands.
    void copyPositions(std::vector<glm::vec3>& out) const;
    // Positions and previous positions (Verlet's velocity), world space, in that layout.
    void copyState(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& previous) const;
    // Carries one strand's motion over from another solver (a regroom while simulating): its
    // points except the pinned root. False, changing nothing, when the point count differs or a
    // value is not finite.
    bool setStrandState(std::size_t strand, std::span<const glm::vec3> positions, std::span<const glm::vec3> previous);

    // Turns one strand's rest shape (head space) without changing its segment lengths: the inverse
    // statics of combed hair (RestShapeSolve) adjusts rest directions between substeps. False,
    // changing nothing, when the point count, the root or a segment length (beyond 0.1%) differs.
    bool setStrandRestDirections(std::size_t strand, std::span<const glm::vec3> rest);

    std::size_t strandCount() const { return m_strandCount; }
    std::size_t particleCount() const { return m_particleCount; }
    int threadCount() const;
    // The pool the steps run on, for other work between steps on the thread that steps (the head's
    // SDF bake, HairSimulation::prepareHead): one pool for the whole simulation.
    ThreadPool& threadPool() { return *m_pool; }
    double simulatedSeconds() const { return m_time; }
    // Strands that went non-finite or stretched past any plausible length and were put back at rest.
    std::uint64_t strandsReset() const { return m_strandsReset; }
    // Bytes the solver holds for its particles (state, rest shape, lanes), for the memory budget.
    std::size_t memoryBytes() const;

    struct CollisionField; // the head's distances and normals, laid out for lookups (SolverRows.h)
    struct ParticleRow;
    struct RestRow;
    struct ShapeRow;
    struct Block; // 16 strands of equal particle count, interleaved (defined in SolverRows.h)
    struct GlobalShapeRow; // a particle's rest position and its global shape share (SolverRows.h)
    struct BlockWind; // a block's strands' winds of their own (SolverRows.h)
    struct VolumeRead {
        float target = 0.0f; // density the hair keeps, metres of hair per m³
        float blend = 0.0f; // share of the difference from the hair's mean move lost this substep
        float stiffness = 0.0f; // m²/s²
        float pushDamping = 0.0f; // share of the motion along the push taken this substep
    };

    // The target density (the density hair keeps, metres of hair per m³) is hairPerScalpArea /
    // (volume x this). Not a layer one could measure on the head: hair hangs over far more than
    // the scalp, and the grid spreads a thin layer over a cell; it is chosen so that the default
    // groom at the default volume stands about 2 cm off the scalp on top (README, "Hair volume").
    static constexpr float kVolumeDepthMetres = 0.3f;

private:
    // Every particle looks at the head and the capsules on its next substep (their clearance bounds
    // are measured from colliders and an offset that changed).
    void forgetClearances();
    void updateBendShares(float substepSeconds);
    void updateGlobalShape(float substepSeconds);
    void updateVolumeBounds();
    // The grid's pass (splat and finish) before a substep; its read, block by block, just before
    // the block advances (the block is then in cache for both).
    void volumePass(const StepConstants& c, int substepsUntilNext);
    // Substeps between two grid passes; for a dense groom (volumeDense()) they may span steps.
    static int volumeRefreshSubsteps(float substepSeconds, bool dense = false);
    // The grid is (or will be, when laid) Kernel::NearestSmoothed: more than kVolumeFullGridParticles.
    bool volumeDense() const;
    void volumeRead(Block& b, const StepConstants& c) const;
    void volumeSplat(Block& b, const StepConstants& c, int slot); // into the grid's slot, and its level of detail

    std::unique_ptr<ThreadPool> m_pool;
    SolverSettings m_settings;
    std::shared_ptr<const SignedDistanceField> m_sdf;
    std::unique_ptr<CollisionField> m_field;
    std::vector<Capsule> m_capsules;
    glm::mat4 m_headToWorld{ 1.0f };
    glm::mat4 m_previousHeadToWorld{ 1.0f };
    std::vector<Block> m_blocks;
    std::vector<ParticleRow> m_stateRows;
    std::vector<RestRow> m_restRows;
    std::vector<ShapeRow> m_shapeRows;
    // Per block, the strands' winds of their own (a hair dryer; Block::wind points here), only
    // while some strand has one: most scenes have none, and every block would carry 192 bytes.
    std::vector<BlockWind> m_blockWinds;
    // In the layout of m_restRows, only while settings().globalShape > 0 (empty otherwise, so the
    // step reads nothing more when it is off).
    std::vector<GlobalShapeRow> m_globalShapeRows;
    std::vector<std::uint32_t> m_restOffsets; // layout of the caller's curves
    struct Slot { // where a strand is: a block and its lane in it, in four bytes
        std::uint32_t block : 28;
        std::uint32_t lane : 4;
    };
    std::vector<Slot> m_slotOfStrand;
    std::unique_ptr<HairVolumeGrid> m_volumeGrid; // made on the first step with volume on
    VolumeRead m_volumeRead; // this substep's, set by volumePass
    glm::vec3 m_volumeLo{ 0.0f }, m_volumeHi{ 0.0f }; // head-space box every particle stays in
    // The grid holds the blocks' splats of their state now, splatted by step() at the end of its
    // last run in the head space of m_volumeSplatHead; whatever moves particles clears it.
    bool m_volumeSplatted = false;
    glm::mat4 m_volumeSplatHead{ 1.0f };
    // Substeps until the grid is laid again (0: before the next substep). Only a dense groom carries
    // it from one step to the next (kVolumeDenseRefreshSeconds); otherwise each step lays it first.
    int m_volumeSubstepsToPass = 0;
    bool m_volumeUnitsStale = true; // the particles' weights changed since the grid's fixed point was set
    float m_scalpArea = 0.0f; // m², given or estimated
    float m_hairPerScalpArea = 0.0f; // metres of drawn hair per m² of scalp
    std::size_t m_strandCount = 0;
    std::size_t m_particleCount = 0;
    double m_time = 0.0;
    std::uint64_t m_strandsReset = 0;
    std::uint64_t m_volumePasses = 0;
    glm::vec2 m_bendSharesFor{ -1.0f }; // (stiffness, substep) the rest rows' bend shares were computed for
    bool m_bendSharesStale = true;
    glm::vec2 m_globalShapeFor{ -1.0f }; // (global shape, substep) m_globalShapeRows were computed for
    bool m_globalShapeStale = true; // the rest shape changed since
};

} // namespace wisp
