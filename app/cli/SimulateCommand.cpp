// wisp-cli simulate: groom a head, run the solver, write the strands.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/StepTimer.h"

#include "app/cli/HeadLoading.h"
#include "app/cli/OutputCheck.h"
#include "io/HairFiles.h"
#include "io/MeshReader.h"
#include "io/ParameterText.h"
#include "io/PresetFile.h"
#include "io/StrandPlacement.h"
#include "io/StrandText.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/groom/GrowthMap.h"
#include "sim/solver/HairSimulation.h"
#include "sim/util/SimdTarget.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace wisp::cli {

namespace {

std::vector<OptionSpec> simulateOptions()
{
    return optionsWithParameters({
        { "head", "FILE", "head mesh (OBJ, PLY, OFF, STL, glTF, GLB); default: the built-in head and its growth map" },
        { "scale", "FACTOR",
            "the head's metres per file unit (default: millimetres, centimetres or metres, guessed "
            "from the skull's width); the head is then centred" },
        { "up", "AXIS",
            "the head file's up axis, +x -x +y -y +z or -z (default: found from the head's shape; glTF is "
            "always +y)" },
        { "z-up", "", "the same as --up +z" },
        { "preset", "FILE", "a preset (JSON, see resources/presets): its parameters and its first region's wisp" },
        { "params", "FILE", "parameter file: 'key = value' lines with the keys below (applied after --preset)" },
        { "hair", "FILE",
            "grow these strands (.hair, .data) instead of the growth map: each is a simulated wisp "
            "rooted on the nearest point of the head. With --head they are in the head file's frame and "
            "placed with it; without, their unit is guessed from the span of their roots" },
        { "hair-scale", "FACTOR",
            "instead: multiply the --hair strands' coordinates (e.g. 0.001 for millimetres) and "
            "take them as they are in Wisp's frame" },
        { "steps", "N", "time steps to simulate (default 120)" },
        { "threads", "N", "solver threads (default: one per core)" },
        { "target", "NAME",
            "run the solver's kernels on this SIMD target instead of the best this CPU has (AVX-512, AVX2, SSE4, "
            "...: see wisp-cli bench); every target gives the same positions, bit for bit" },
        { "grid", "WxHxP", "the first paper's layout: W x H strands of P particles on the scalp" },
        { "out", "FILE", "write the strands there (wisp-strands text format, see the README)" },
        { "export", "FILE", "write the strands as .hair, .data, .obj, .gltf or .glb (the last three with the head)" },
        { "rest", "", "write the rest pose (the groom) instead of the last simulated frame" },
        { "keys-only", "", "write only the simulated strands (key hairs), not every drawn strand" },
        { "timing", "", "print every step's time" },
    });
}

} // namespace

int runSimulate(int argc, char** argv)
{
    const std::vector<OptionSpec> options = simulateOptions();
    const CommandLine args(argc, argv, 2, options);
    if (args.has("help")) {
        std::cout << "usage: wisp-cli simulate [options]\n\n" << describeOptions(options);
        return kSuccess;
    }

    // Outputs first: a bad path found after the simulation wastes the whole run.
    if (const auto out = args.text("out"))
        checkOutputPath(*out, "--out", {});
    if (const auto out = args.text("export"))
        checkOutputPath(*out, "--export", io::hairWriteExtensions());

    ParameterValues values;
    if (const auto path = args.text("preset")) {
        io::Result<io::PresetReadResult> preset = io::readPreset(*path);
        if (!preset)
            throw CliError{ kBadInput, preset.error().toString() };
        for (const std::string& warning : preset.value().warnings)
            std::cerr << "wisp-cli simulate: " << *path << ": " << warning << "\n";
        const io::Preset& p = preset.value().preset;
        values = p.parameters;
        if (!p.regions.empty()) {
            for (const ParameterInfo& info : allParameters())
                if (info.group == ParamGroup::Wisp)
                    values.set(info.id, p.regions.front().wisp.get(info.id));
            if (p.regions.size() > 1)
                std::cerr << "wisp-cli simulate: " << *path << ": " << p.regions.size()
                          << " regions; the command line grows one, with the first region's wisp\n";
        }
    }
    if (const auto path = args.text("params")) {
        const io::Result<io::ParameterFile> file = io::readParameterText(*path);
        if (!file)
            throw CliError{ kBadInput, file.error().toString() };
        for (const auto& [id, value] : file.value().values)
            values.set(id, value);
    }
    args.applyParameters(values); // options win over the file
    const auto steps = static_cast<int>(args.integer("steps", 120, 0, 10'000'000));
    const auto threads = static_cast<int>(args.integer("threads", 0, 0, 1024));
    if (const auto target = args.text("target")) {
        if (std::string why = forceSimdTarget(*target); !why.empty())
            throw CliError{ kBadInput, "--target: " + why };
    }

    std::optional<io::Axis> up;
    if (const auto text = args.text("up")) {
        up = io::parseAxis(*text);
        if (!up)
            throw CliError{ kBadInput, "--up: '" + *text + "' is no axis (+x, -x, +y, -y, +z or -z)" };
    }
    if (args.has("z-up")) {
        if (up && *up != io::Axis::PosZ)
            throw CliError{ kBadInput, "--z-up contradicts --up " + *args.text("up") };
        up = io::Axis::PosZ;
    }

    TriangleMesh head;
    std::vector<float> weights;
    std::optional<io::HeadPlacement> headPlacement;
    if (const auto path = args.text("head")) {
        LoadedHead loaded = loadHead(
            *path, args.has("scale") ? std::optional(args.real("scale", 1.0)) : std::nullopt, up, "simulate");
        headPlacement = loaded.placement;
        head = std::move(loaded.mesh);
        weights = scalpGrowth(head);
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
            throw CliError{ kBadInput, "--grid: '" + *grid + "' is not WxHxP (e.g. 35x35x30)" };
        error = sim.setupGrid(head, w, h, p, values.getFloat(Param::Length), values);
    } else if (const auto hairPath = args.text("hair")) {
        io::Result<io::HairReadResult> hair = io::readHair(*hairPath);
        if (!hair)
            throw CliError{ kBadInput, hair.error().toString() };
        for (const std::string& warning : hair.value().warnings)
            std::cerr << "wisp-cli simulate: " << *hairPath << ": " << warning << "\n";
        std::vector<GrowthRegion> regions(1);
        regions[0].name = std::filesystem::path(*hairPath).filename().string();
        regions[0].weights.assign(head.positions.size(), 0.0f);
        regions[0].values = values;
        HairCurves strands = std::move(hair).value().strands;
        const double hairScale = args.real("hair-scale", 1.0);
        if (!(hairScale > 0.0 && hairScale < 1e6))
            throw CliError{ kBadInput, "--hair-scale: " + *args.text("hair-scale") + " must be a positive factor" };
        // One placement for the editor and the command line (io/StrandPlacement.h).
        const io::StrandPlacement placed = io::placeStrands(strands, headPlacement ? &*headPlacement : nullptr,
            args.has("hair-scale") ? static_cast<float>(hairScale) : 0.0f);
        std::cout << *hairPath << ": " << placed.description << "\n";
        if (!placed.note.empty())
            std::cerr << "wisp-cli simulate: " << *hairPath << ": warning: " << placed.note << "\n";
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& p : strands.positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw CliError{ kBadInput,
                    *hairPath + ": point " + std::to_string(&p - strands.positions.data())
                        + " is not finite once placed (" + placed.description + ")" };
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const Aabb box = boundsOf(head);
        // Hair is rooted on the head and at most a few metres long: a point farther than this from
        // the head's box is in other units or corrupt, and the solver would only reset it forever.
        constexpr float kMaxHairDistanceMetres = 10.0f;
        for (std::size_t i = 0; i < strands.positions.size(); ++i) {
            const glm::vec3& p = strands.positions[i];
            const glm::dvec3 outside
                = glm::max(glm::max(glm::dvec3(box.min - p), glm::dvec3(p - box.max)), glm::dvec3(0.0));
            const double away = glm::length(outside);
            if (!(away <= kMaxHairDistanceMetres)) {
                char metres[32];
                std::snprintf(metres, sizeof metres, "%.3g m", away);
                throw CliError{ kBadInput,
                    *hairPath + ": point " + std::to_string(i) + " lies " + metres
                        + " from the head, more than 10 m: the strands must be in the head's "
                          "space, in metres (see --hair-scale)" };
            }
        }
        const float headExtent = glm::length(box.size()), hairExtent = glm::length(hi - lo);
        if (hairExtent > 5.0f * headExtent)
            std::cerr << "wisp-cli simulate: " << *hairPath << ": the strands span " << hairExtent << " m, the head "
                      << headExtent << " m; if they are in other units, give --hair-scale\n";
        regions[0].importedStrands = std::make_shared<HairCurves>(std::move(strands));
        error = sim.setup(head, regions, kNoSolo, values);
    } else {
        error = sim.setup(head, weights, values);
    }
    if (!error.empty())
        throw CliError{ kBadInput, (args.has("head") ? *args.text("head") + ": " : std::string()) + error };
    for (const std::string& warning : sim.groomWarnings())
        std::cerr << "wisp-cli simulate: warning: " << warning << "\n";
    if (args.has("hair") && sim.groom().strandCount() == 0)
        throw CliError{ kBadInput,
            *args.text("hair")
                + ": no strand could be rooted on the head (are they in its space "
                  "and units? see --hair-scale)" };

    std::cout << "strands " << sim.groom().strandCount() << " (simulated " << sim.solver().strandCount()
              << ", particles " << sim.solver().particleCount() << "), threads " << sim.solver().threadCount()
              << ", steps " << steps << "\n";
    StepTimer timer;
    for (int i = 0; i < steps; ++i) {
        timer.start();
        sim.step();
        const double ms = timer.stop();
        if (args.has("timing"))
            std::cout << "step " << i + 1 << " " << ms << " ms\n";
    }
    if (steps > 0)
        std::cout << "ms per step: median " << timer.medianMs() << ", mean " << timer.meanMs() << ", max "
                  << timer.maxMs() << "\n";
    if (sim.solver().strandsReset() > 0)
        std::cout << "strands reset after going unstable: " << sim.solver().strandsReset() << "\n";

    if (args.has("out") || args.has("export")) {
        HairCurves curves;
        const bool keysOnly = args.has("keys-only") && !sim.simulatesAllStrands();
        if (args.has("rest")) {
            curves = keysOnly ? keyRestCurves(sim.groom()) : sim.groom().rest;
        } else if (keysOnly) {
            curves = keyRestCurves(sim.groom());
            sim.copySimulated(curves.positions);
        } else {
            sim.buildFrame(curves);
        }
        if (const auto out = args.text("out")) {
            if (const io::Result<void> written = io::writeStrandText(*out, curves); !written)
                throw CliError{ kBadInput, written.error().toString() };
            std::cout << "wrote " << curves.strandCount() << " strands to " << *out << "\n";
        }
        if (const auto out = args.text("export")) {
            io::HairExportOptions options;
            options.head = &sim.head();
            if (const io::Result<void> written = io::writeHair(*out, curves, options); !written)
                throw CliError{ kBadInput, written.error().toString() };
            std::cout << "exported " << curves.strandCount() << " strands to " << *out << "\n";
        }
    }
    return kSuccess;
}

} // namespace wisp::cli
