// wisp-cli bake: simulate a frame range with the head moving and write it as USD (.usda, every
// frame a time sample) or as a cyHair .hair sequence (one file per frame, written as it is
// simulated). Deterministic: the same inputs give byte-identical files, whatever --threads says,
// and any part of a range gives the frames the whole range gives (sim/motion/HairBake.h).

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/OutputCheck.h"

#include "io/FramePattern.h"
#include "io/HairFiles.h"
#include "io/ProjectFile.h"
#include "io/RegularFile.h"
#include "io/UsdaWriter.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/motion/HairBake.h"
#include "sim/params/MotionSettings.h"
#include "sim/solver/HairSimulation.h"
#include "sim/util/NumberText.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace wisp::cli {

namespace {

// "0..90 degrees": a motion setting's range as the registry states it.
std::string rangeText(MotionSetting setting)
{
    const MotionSettingInfo& info = motionSettingInfo(setting);
    return formatNumber(info.minimum) + ".." + formatNumber(info.maximum) + " " + std::string(info.unit);
}

std::vector<OptionSpec> bakeOptions()
{
    return optionsWithParameters({
        { "frames", "A:B", "the frames to write, 1 or more (frame 1 is 0 s; default: the project's timeline)" },
        { "fps", "N", "frames per second (default: the project's, else 24)" },
        { "motion", "KIND", "turn, nod, shake, walk or none: the procedural motion, replacing the project's" },
        { "amplitude", "X",
            "the motion's amplitude: " + rangeText(MotionSetting::TurnAmplitude) + " (turn, nod, shake) or "
                + rangeText(MotionSetting::WalkAmplitude) + " (walk)" },
        { "frequency", "HZ", "the motion's frequency, cycles per second, " + rangeText(MotionSetting::Frequency) },
        { "threads", "N", "solver threads (default: one per core; the result does not depend on it)" },
        { "memory-mib", "N", "the most a .usda bake may keep in memory, MiB (default 2048)" },
        { "no-drape", "", "start from the groom's rest shape instead of the hair settled under gravity" },
        { "out", "FILE",
            "FILE.usda (USD text, every frame a time sample; one frame: a still), or PATTERN.hair "
            "with # for the frame number (hair.####.hair: hair.0001.hair, ...)" },
    });
}

// "A:B" -> {A, B}; throws CliError.
std::pair<int, int> parseFrames(const std::string& text)
{
    int a = 0, b = 0;
    char tail = 0;
    if (std::sscanf(text.c_str(), "%d:%d%c", &a, &b, &tail) != 2)
        throw CliError{ kBadInput, "--frames: '" + text + "' is not A:B (e.g. 1:48)" };
    return { a, b };
}

// Per drawn strand: its region's hair thickness (the viewport's 80 µm where a region gives none).
std::vector<float> rootWidths(const HairSimulation& sim)
{
    const Groom& g = sim.groom();
    std::vector<float> widths(g.strandCount(), 80e-6f);
    const std::vector<StrandLook>& looks = sim.looks();
    for (std::size_t s = 0; s < widths.size() && s < g.regionOfStrand.size(); ++s)
        if (g.regionOfStrand[s] < looks.size() && looks[g.regionOfStrand[s]].rootThicknessMetres > 0.0f)
            widths[s] = looks[g.regionOfStrand[s]].rootThicknessMetres;
    return widths;
}

} // namespace

int runBake(int argc, char** argv)
{
    const std::vector<OptionSpec> options = bakeOptions();
    const CommandLine args(argc, argv, 2, options, 1);
    if (args.has("help")) {
        std::cout << "usage: wisp-cli bake [PROJECT] --frames A:B [--fps N] [--motion turn|nod|shake|walk] "
                     "[--threads N] [--<parameter> VALUE ...] --out FILE.usda|PATTERN.hair\n\n"
                     "Simulates the frames with the head moving (the project's keys and motion, or --motion) and "
                     "writes them.\nWithout PROJECT: the built-in head with the default groom. Progress goes to "
                     "stderr.\n\n"
                  << describeOptions(options);
        return kSuccess;
    }
    const auto out = args.text("out");
    if (!out)
        throw CliError{ kUsage, "needs --out FILE.usda or --out PATTERN.hair (see --help)" };
    checkOutputPath(*out, "--out", { "usda", "hair" });
    const bool usd = io::lowerExtension(*out) == "usda";
    if (!usd && std::filesystem::path(*out).filename().string().find('#') == std::string::npos)
        throw CliError{ kBadInput,
            "--out: " + *out
                + ": a .hair sequence needs # in the file name for the frame "
                  "number (e.g. hair.####.hair)" };

    // The scene: a project, or the built-in head with the default groom.
    HeadMotion motion;
    BakeRange range;
    bool rangeGiven = false;
    auto sim = std::make_unique<HairSimulation>(static_cast<int>(args.integer("threads", 0, 0, 1024)));
    std::string error;
    if (!args.positional().empty()) {
        const std::string& path = args.positional().front();
        io::Result<io::ProjectReadResult> read = io::readProject(path, io::readHeadFile);
        if (!read)
            throw CliError{ kBadInput, read.error().toString() };
        for (const std::string& warning : read.value().warnings)
            std::cerr << "wisp-cli bake: " << path << ": " << warning << "\n";
        io::Project p = std::move(read).value().project;
        args.applyParameters(p.parameters); // options win over the project's (every region's wisp too)
        for (GrowthRegion& region : p.regions)
            for (const ParameterInfo& info : allParameters())
                if (info.group == ParamGroup::Wisp && args.has(std::string(info.key)))
                    region.values.set(info.id, p.parameters.get(info.id));
        if (!p.style.empty())
            sim->setStyle(std::make_shared<const StyleEdits>(p.style));
        error = sim->setup(p.head, p.regions, p.soloRegion, p.parameters);
        if (error.empty())
            error = sim->applyForces(p.parameters);
        if (!error.empty())
            throw CliError{ kBadInput, path + ": " + error };
        motion = p.motion;
        range = p.timeline;
        rangeGiven = true;
    } else {
        const DefaultHead head = makeDefaultHead();
        ParameterValues values;
        args.applyParameters(values);
        error = sim->setup(head.mesh, head.growthWeights, values);
        if (!error.empty())
            throw CliError{ kBadInput, error };
    }
    for (const std::string& warning : sim->groomWarnings())
        std::cerr << "wisp-cli bake: warning: " << warning << "\n";

    if (const auto frames = args.text("frames")) {
        std::tie(range.firstFrame, range.lastFrame) = parseFrames(*frames);
        rangeGiven = true;
    }
    if (!rangeGiven)
        throw CliError{ kUsage, "needs --frames A:B (or a project with a timeline)" };
    if (args.has("fps"))
        range.fps = args.real("fps", range.fps);
    if (std::string e = validateBakeRange(range); !e.empty())
        throw CliError{ kBadInput, "--frames/--fps: " + e };

    if (const auto name = args.text("motion")) {
        const std::optional<MotionKind> kind = motionFromName(*name);
        if (!kind)
            throw CliError{ kBadInput, "--motion: '" + *name + "' is not turn, nod, shake, walk or none" };
        motion.setProcedural(motionPreset(*kind));
    }
    ProceduralMotion procedural = motion.procedural();
    if (args.has("amplitude"))
        procedural.amplitude = args.real("amplitude", procedural.amplitude);
    if (args.has("frequency"))
        procedural.frequencyHz = args.real("frequency", procedural.frequencyHz);
    if (procedural.kind != MotionKind::None)
        if (std::string e = HeadMotion::validateProcedural(procedural); !e.empty())
            throw CliError{ kBadInput, "--motion " + std::string(motionName(procedural.kind)) + ": " + e };
    motion.setProcedural(procedural);

    BakeOptions bake;
    bake.range = range;
    bake.keepFrames = usd;
    bake.drapeFirst = !args.has("no-drape");
    bake.memoryBoundBytes = static_cast<std::size_t>(args.integer("memory-mib", 2048, 1, 1 << 24)) << 20;
    const bool terminal = ::isatty(STDERR_FILENO) != 0;
    int lastTenth = -1;
    using Clock = std::chrono::steady_clock;
    Clock::time_point afterFrameOne{};
    bake.progress = [&](int done, int total) {
        if (done == 1)
            afterFrameOne = Clock::now();
        // A line that rewrites itself on a terminal; a line per tenth in a log.
        const int percent = static_cast<int>(100LL * done / total);
        if (terminal) {
            std::cerr << "\rwisp-cli bake: frame " << done << " of " << total << " (" << percent << " %)" << std::flush;
            if (done == total)
                std::cerr << "\n";
        } else if (percent / 10 != lastTenth) {
            lastTenth = percent / 10;
            std::cerr << "wisp-cli bake: frame " << done << " of " << total << " (" << percent << " %)\n";
        }
    };
    int written = 0;
    if (!usd) {
        bake.onFrame = [&](const BakedFrame& frame, const BakeCache& layout) -> std::string {
            HairCurves curves;
            curves.offsets = layout.offsets;
            curves.positions = frame.positions;
            const std::string path = io::framePath(*out, frame.frame);
            if (const io::Result<void> written = io::writeHair(path, curves); !written)
                return written.error().toString();
            ++written;
            return {};
        };
    }

    const glm::vec3 pivot = pivotOf(sim->head());
    const auto start = Clock::now();
    const BakeResult result = bakeMotion(*sim, motion, pivot, bake);
    const auto end = Clock::now();
    // Wall-clock: the drape (frame 1), then each later frame (its steps and its frame built).
    const double drapeMs = std::chrono::duration<double, std::milli>(afterFrameOne - start).count();
    const double frameMs = range.lastFrame > 1
        ? std::chrono::duration<double, std::milli>(end - afterFrameOne).count() / (range.lastFrame - 1)
        : 0.0;
    if (!result.error.empty())
        throw CliError{ kBadInput, result.error };

    const std::size_t points = result.cache.pointCount();
    if (usd) {
        io::UsdaScene scene;
        scene.offsets = result.cache.offsets;
        scene.widthsMetres = io::taperedWidths(scene.offsets, rootWidths(*sim), 0.25f);
        scene.framesPerSecond = range.fps;
        scene.animated = range.frameCount() > 1;
        scene.head = &sim->head();
        for (const BakedFrame& f : result.cache.frames)
            scene.frames.push_back({ static_cast<double>(f.frame), f.positions, f.headToWorld });
        if (const io::Result<void> usdWritten = io::writeUsda(*out, scene); !usdWritten)
            throw CliError{ kBadInput, usdWritten.error().toString() };
        written = 1;
    }
    std::cout << "baked frames " << range.firstFrame << ":" << range.lastFrame << " at " << range.fps << " fps ("
              << result.cache.stepsPerFrame << " steps of " << result.cache.stepSeconds * 1000.0
              << " ms a frame, motion " << motionName(motion.procedural().kind) << ", " << motion.keys().size()
              << " keys): " << result.cache.offsets.size() - 1 << " strands, " << points << " points, "
              << result.cache.bytesPerFrame() << " bytes a cached frame; drape " << drapeMs << " ms, then " << frameMs
              << " ms a frame; wrote " << (usd ? *out : std::to_string(written) + " files " + *out) << "\n";
    return kSuccess;
}

} // namespace wisp::cli
