#include "app/editor/SettledScene.h"

#include "sim/solver/HairSimulation.h"
#include "sim/solver/SolverSettings.h"

#include <cmath>
#include <exception>
#include <memory>

namespace wisp {

int settleStepsFor(double seconds, double timeStepSeconds)
{
    if (!(seconds > 0.0) || !(timeStepSeconds > 0.0) || !std::isfinite(seconds))
        return 0;
    const double steps = std::round(seconds / timeStepSeconds);
    return steps >= kMaxSettleSteps ? kMaxSettleSteps : static_cast<int>(steps);
}

void fillFrame(const HairSimulation& sim, const ParameterValues& values, Frame& frame)
{
    sim.buildFrame(frame.strands);
    frame.looks = sim.looks();
    if (!frame.looks.empty())
        frame.lookOfStrand = sim.groom().regionOfStrand;
    frame.simulatedStrands = sim.solver().strandCount();
    frame.simulatedParticles = sim.solver().particleCount();
    frame.wind = solverSettingsFrom(values).wind;
    frame.wetness.clear();
    if (sim.anyWet())
        sim.strandWetness(frame.wetness);
}

SettledFrame settleScene(
    const SceneToSettle& scene, int steps, int solverThreads, const std::function<bool()>& cancelled)
{
    SettledFrame result;
    try {
        auto sim = std::make_unique<HairSimulation>(solverThreads);
        if (scene.style)
            sim->setStyle(scene.style);
        result.error = sim->setup(scene.head, scene.regions, scene.soloId, scene.values);
        if (!result.error.empty())
            return result;
        if (std::string error = sim->applyForces(scene.values); !error.empty()) {
            result.error = error;
            return result;
        }
        sim->drapeAtRest(
            HairSimulation::kDrapeMaxSteps, kDrapeStillMetres, cancelled, scene.values.getInt(Param::Substeps));
        const double timeStep = sim->solver().settings().timeStepSeconds;
        for (int i = 0; i < steps; ++i) {
            if (cancelled && cancelled()) {
                result.error = "cancelled";
                return result;
            }
            sim->step();
        }
        auto frame = std::make_shared<Frame>();
        frame->step = static_cast<std::uint64_t>(steps);
        frame->simulatedSeconds = steps * timeStep;
        fillFrame(*sim, scene.values, *frame);
        result.frame = std::move(frame);
    } catch (const std::exception& e) {
        result.error = std::string("settle: ") + e.what(); // sim/ does not throw, but memory can run out
    }
    return result;
}

} // namespace wisp
