#pragma once
// Shared set-ups for the sim tests: the default head with its groom, and small measurements.

#include "sim/geometry/DefaultHead.h"
#include "sim/solver/HairSimulation.h"

#include <glm/geometric.hpp>

#include <memory>
#include <vector>

namespace wisp::test {

inline const DefaultHead& defaultHead()
{
    static const DefaultHead head = makeDefaultHead();
    return head;
}

// A lighter groom than the editor's default so physics tests stay quick.
inline ParameterValues testParameters()
{
    ParameterValues v;
    v.set(Param::Density, 2.0);
    v.set(Param::WispSize, 4);
    v.set(Param::WindSpeed, 0.0);
    v.set(Param::Turbulence, 0.0);
    // The head alone: sag, comb and stiffness measurements are made against the head; the neck and
    // shoulders (BodyTest) would hold long hair up. (The comb's rest-shape solve does not know the body.)
    v.set(Param::Body, 0);
    // Strands on their own: these tests measure one strand's physics (bending at any substep count,
    // settling, the comb's rest shape); hair-hair interaction has its own (VolumeTest.cpp).
    v.set(Param::Volume, 0.0);
    return v;
}

inline std::unique_ptr<HairSimulation> makeSimulation(const ParameterValues& v, int threads = 0)
{
    auto sim = std::make_unique<HairSimulation>(threads);
    const std::string error = sim->setup(defaultHead().mesh, defaultHead().growthWeights, v);
    if (!error.empty())
        throw std::runtime_error(error);
    return sim;
}

inline void run(HairSimulation& sim, int steps)
{
    for (int i = 0; i < steps; ++i)
        sim.step();
}

struct TipStats {
    glm::vec3 meanTip{ 0.0f };
    glm::vec3 meanRoot{ 0.0f };
};

inline TipStats tipStats(const HairSimulation& sim)
{
    std::vector<glm::vec3> p;
    sim.copySimulated(p);
    const HairCurves& layout = sim.simulatesAllStrands() ? sim.groom().rest : keyRestCurves(sim.groom());
    TipStats s;
    for (std::size_t i = 0; i < layout.strandCount(); ++i) {
        s.meanRoot += p[layout.offsets[i]];
        s.meanTip += p[layout.offsets[i + 1] - 1];
    }
    s.meanRoot /= static_cast<float>(layout.strandCount());
    s.meanTip /= static_cast<float>(layout.strandCount());
    return s;
}

// The simulated strands' tips (keys only unless every strand is simulated), world space.
inline std::vector<glm::vec3> simulatedTips(const HairSimulation& sim)
{
    std::vector<glm::vec3> p;
    sim.copySimulated(p);
    const HairCurves layout = sim.simulatesAllStrands() ? sim.groom().rest : keyRestCurves(sim.groom());
    std::vector<glm::vec3> tips;
    for (std::size_t i = 0; i < layout.strandCount(); ++i)
        tips.push_back(p[layout.offsets[i + 1] - 1]);
    return tips;
}

} // namespace wisp::test
