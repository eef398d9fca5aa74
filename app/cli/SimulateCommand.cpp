// wisp-cli simulate: groom a head, run the solver, write the strands.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/StepTimer.h"

#include "io/MeshReader.h"
#include "io/ParameterText.h"
#include "io/StrandText.h"
#include "sim/DefaultHead.h"
#include "sim/GrowthMap.h"
#include "sim/HairSimulation.h"

#include <cstdio>
#include <iostream>

namespace wisp::cli {

namespace {

std::vector<OptionSpec> simulateOptions()
{
    std::vector<OptionSpec> options = {
        {"help", "", "show this help"},
        {"head", "FILE", "head mesh (OBJ, PLY, OFF, STL), +Y up; default: the built-in head and its growth map"},
        {"scale", "FACTOR", "multiply the head's coordinates (e.g. 0.001 for a head modelled in millimetres)"},
        {"params", "FILE", "parameter file: 'key = value' lines with the keys below"},
        {"steps", "N", "time steps to simulate (default 120)"},
        {"threads", "N", "solver threads (default: one per core)"},
        {"grid", "WxHxP", "the first paper's layout: W x H strands of P particles on the scalp"},
        {"out", "FILE", "write the strands there (wisp-strands text format, see the README)"},
        {"keys-only", "", "write only the simulated strands (key hairs), not every drawn strand"},
        {"timing", "", "print every step's time"},
    };
    const std::vector<OptionSpec> parameters = parameterOptions();
    options.insert(options.end(), parameters.begin(), parameters.end());
    return options;
}

}  // namespace

int runSimulate(int argc, char** argv)
{
    const std::vector<OptionSpec> options = simulateOptions();
    const CommandLine args(argc, argv, 2, options);
    if (args.has("help")) {
        std::cout << "usage: wisp-cli simulate [options]\n\n" << describeOptions(options);
        return kSuccess;
    }

    ParameterValues values;
    if (const auto path = args.text("params")) {
        const io::Result<io::ParameterFile> file = io::readParameterText(*path);
        if (!file)
            throw CliError{kBadInput, file.error().toString()};
        for (const auto& [id, value] : file.value().values)
            values.set(id, value);
    }
    args.applyParameters(values);  // options win over the file
    const auto steps = static_cast<int>(args.integer("steps", 120, 0, 10'000'000));
    const auto threads = static_cast<int>(args.integer("threads", 0, 0, 1024));

    TriangleMesh head;
    std::vector<float> weights;
    if (const auto path = args.text("head")) {
        io::Result<io::MeshReadResult> mesh = io::readMesh(*path);
        if (!mesh)
            throw CliError{kBadInput, mesh.error().toString()};
        for (const std::string& warning : mesh.value().warnings)
            std::cerr << "wisp-cli simulate: " << *path << ": " << warning << "\n";
        head = std::move(mesh).value().mesh;
        const double scale = args.real("scale", 1.0);
        if (!(scale > 0.0) || scale > 1e6)
            throw CliError{kBadInput, "--scale: " + *args.text("scale") + " must be a positive factor"};
        for (glm::vec3& p : head.positions)
            p *= static_cast<float>(scale);
        weights = upperHeadGrowth(head);
    } else {
        DefaultHead d = makeDefaultHead();
        head = std::move(d.mesh);
        weights = std::move(d.growthWeights);
    }

    HairSimulation sim(threads);
    std::string error;
    if (const auto grid = args.text("grid")) {
        int w = 0, h = 0, p = 0;
        char tail = 0;
        if (std::sscanf(grid->c_str(), "%dx%dx%d%c", &w, &h, &p, &tail) != 3)
            throw CliError{kBadInput, "--grid: '" + *grid + "' is not WxHxP (e.g. 35x35x30)"};
        error = sim.setupGrid(head, w, h, p, values.getFloat(Param::Length), values);
    } else {
        error = sim.setup(head, weights, values);
    }
    if (!error.empty())
        throw CliError{kBadInput, (args.has("head") ? *args.text("head") + ": " : std::string()) + error};

    std::cout << "strands " << sim.groom().strandCount() << " (simulated " << sim.solver().strandCount() << ", particles "
              << sim.solver().particleCount() << "), threads " << sim.solver().threadCount() << ", steps " << steps << "\n";
    StepTimer timer;
    for (int i = 0; i < steps; ++i) {
        timer.start();
        sim.step();
        const double ms = timer.stop();
        if (args.has("timing"))
            std::cout << "step " << i + 1 << " " << ms << " ms\n";
    }
    if (steps > 0)
        std::cout << "ms per step: median " << timer.medianMs() << ", mean " << timer.meanMs() << ", max " << timer.maxMs()
                  << "\n";
    if (sim.solver().strandsReset() > 0)
        std::cout << "strands reset after going unstable: " << sim.solver().strandsReset() << "\n";

    if (const auto out = args.text("out")) {
        HairCurves curves;
        if (args.has("keys-only")) {
            curves = keyRestCurves(sim.groom());
            if (sim.simulatesAllStrands())
                curves = sim.groom().rest;
            sim.copySimulated(curves.positions);
        } else {
            sim.buildFrame(curves);
        }
        if (std::string writeError = io::writeStrandText(*out, curves); !writeError.empty())
            throw CliError{kBadInput, writeError};
        std::cout << "wrote " << curves.strandCount() << " strands to " << *out << "\n";
    }
    return kSuccess;
}

}  // namespace wisp::cli
