// wisp-cli bench: the solver on standard workloads, so Wisp can be compared with the first
// paper's Table 1 and with other solvers doing the same work.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/StepTimer.h"

#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "sim/geometry/DefaultHead.h"
#include "sim/geometry/MeshBvh.h"
#include "sim/groom/GrowthMap.h"
#include "sim/groom/ScalpBrush.h"
#include "sim/solver/FloorSweep.h"
#include "sim/solver/HairSimulation.h"
#include "sim/style/StyleEdits.h"
#include "sim/util/CpuName.h"
#include "sim/util/SimdTarget.h"
#include "sim/util/ThreadPool.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace wisp::cli {

namespace {

// The physics a step runs, as `--without` names it and the JSON rows list it (physicsOf).
enum class Physics { HeadContact, Bending, Gusts, Volume, Capsules };
struct PhysicsName {
    Physics physics;
    const char* name;
};
constexpr PhysicsName kPhysicsNames[] = {
    { Physics::HeadContact, "head-contact" },
    { Physics::Bending, "bending" },
    { Physics::Gusts, "gusts" },
    { Physics::Volume, "volume" },
    { Physics::Capsules, "capsules" },
};
// What `--without` can turn off (the grid workloads' physics, the table's first entries): the
// capsules are the sphere's own.
constexpr int kPhysicsToTurnOff = 4;
static_assert(kPhysicsNames[kPhysicsToTurnOff].physics == Physics::Capsules, "what --without turns off comes first");

const char* nameOf(Physics physics)
{
    for (const PhysicsName& p : kPhysicsNames)
        if (p.physics == physics)
            return p.name;
    return "";
}

// The names of `list`, comma-separated, each in `quote`s (JSON) or bare (the table).
std::string namesOf(const std::vector<Physics>& list, const char* quote = "")
{
    std::string names;
    for (Physics p : list)
        names += (names.empty() ? "" : ", ") + std::string(quote) + nameOf(p) + quote;
    return names;
}

// The physics a solver steps with, read from the solver itself (not from what was asked).
std::vector<Physics> physicsOf(const Solver& solver)
{
    const SolverSettings& s = solver.settings();
    std::vector<Physics> on;
    if (solver.hasCollider())
        on.push_back(Physics::HeadContact);
    if (solver.anyStrandBends())
        on.push_back(Physics::Bending);
    if (blowsGusts(s.turbulence, s.wind))
        on.push_back(Physics::Gusts);
    if (s.volume > 0.0f)
        on.push_back(Physics::Volume);
    if (solver.capsuleCount() > 0)
        on.push_back(Physics::Capsules);
    return on;
}

struct BenchResult {
    std::string name;
    std::vector<Physics> physics{}; // what the solver was set up to step with (physicsOf)
    std::size_t particles = 0;
    std::size_t strands = 0;
    int threads = 0;
    int substeps = 0;
    int steps = 0;
    double medianMs = 0;
    double meanMs = 0;
    double solverBytesPerParticle = 0;
    double peakRssMb = 0;
    // Steps of the solver over `particles` (not dabs or releases): such a row gets a floor row.
    bool solverSteps = true;
    double floorMs = 0; // the floor's median at this particle count, this run (0: none)
    std::shared_ptr<const BenchResult> floor{}; // the floor's own row (timeSteps), when measured
};

// Peak resident memory of this process; reset between workloads so each reports its own.
void resetPeakRss()
{
    std::ofstream("/proc/self/clear_refs") << "5";
}
double peakRssMb()
{
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0)
            return std::stod(line.substr(6)) / 1024.0; // kB
    return 0.0;
}

struct RunOptions {
    int threads = 0;
    int warmupSteps = 20;
    int measuredSteps = 100;
    std::size_t sphereStrands = 10'000;
    std::string headPath; // brush-dab: a head file instead of the default head
    double volume = -1.0; // the volume parameter (hair-hair interaction); below 0: the default
    std::vector<Physics> without; // physics the grid workloads run without (--without)
    bool runsWithout(Physics p) const { return std::find(without.begin(), without.end(), p) != without.end(); }
};

// Workload steps are timed alone; a solver's steps (`floorPool`: its pool) are timed in turns
// with the floor's (FloorSweep.h) over as many particles, a round of kFloorRoundSteps of each at a
// time on the same threads, so that both see the same machine: on a shared host the speed drifts
// by a tenth or more within a minute, and a floor timed after the workload moved the ratio by as
// much (groom-1m's at AVX-512: 7.5x to 10.9x across six runs in one sitting).
constexpr int kFloorRoundSteps = 10;

template <typename StepFn>
void timeSteps(const RunOptions& o, StepFn&& step, BenchResult& r, ThreadPool* floorPool = nullptr)
{
    auto timed = [](StepTimer& timer, auto&& stepOnce, int steps) {
        for (int i = 0; i < steps; ++i) {
            timer.start();
            stepOnce();
            timer.stop();
        }
    };
    for (int i = 0; i < o.warmupSteps; ++i)
        step();
    StepTimer timer;
    r.steps = o.measuredSteps;
    if (!floorPool || r.particles == 0) {
        timed(timer, step, o.measuredSteps);
        r.medianMs = timer.medianMs();
        r.meanMs = timer.meanMs();
        return;
    }
    // The workload's own peak, before the floor's rows are made beside it.
    r.peakRssMb = peakRssMb();
    FloorSweep sweep(r.particles, 15, *floorPool);
    auto floor = std::make_shared<BenchResult>(BenchResult{ "floor" });
    floor->particles = sweep.particleCount();
    floor->strands = sweep.strandCount();
    floor->threads = sweep.threadCount();
    floor->substeps = 1;
    floor->steps = o.measuredSteps;
    floor->solverBytesPerParticle
        = static_cast<double>(sweep.bytesPerStep()) / 2.0 / static_cast<double>(floor->particles);
    floor->peakRssMb = -1.0; // (the process holds the workload too: no figure of its own)
    for (int i = 0; i < o.warmupSteps; ++i)
        sweep.step();
    StepTimer floorTimer;
    for (int done = 0; done < o.measuredSteps; done += kFloorRoundSteps) {
        const int steps = std::min(kFloorRoundSteps, o.measuredSteps - done);
        timed(timer, step, steps);
        timed(
            floorTimer, [&] { sweep.step(); }, steps);
    }
    r.medianMs = timer.medianMs();
    r.meanMs = timer.meanMs();
    floor->medianMs = floor->floorMs = floorTimer.medianMs();
    floor->meanMs = floorTimer.meanMs();
    r.floorMs = floor->medianMs;
    r.floor = std::move(floor);
}

// The first paper's grid on the default head: head collision on, gravity 9.8 m/s², wind on.
// One substep: the paper's step is one Verlet integration and one constraint relaxation. The paper
// collides with the head only: no neck and shoulders.
BenchResult gridWorkload(const std::string& name, int width, int height, int particles, const RunOptions& o)
{
    const DefaultHead head = makeDefaultHead();
    ParameterValues v;
    v.set(Param::Gravity, 9.8);
    v.set(Param::WindSpeed, 5.0);
    v.set(Param::Turbulence, 0.5);
    v.set(Param::Substeps, 1);
    v.set(Param::Body, 0);
    if (o.volume >= 0.0)
        v.set(Param::Volume, o.volume);
    // --without: each feature off as an artist would turn it off, the head's contact by giving the
    // solver no head (its volume grid then has no solid head either).
    if (o.runsWithout(Physics::Bending))
        v.set(Param::Stiffness, 0.0);
    if (o.runsWithout(Physics::Gusts))
        v.set(Param::Turbulence, 0.0);
    if (o.runsWithout(Physics::Volume))
        v.set(Param::Volume, 0.0);
    HairSimulation sim(o.threads);
    if (std::string error = sim.setupGrid(head.mesh, width, height, particles, 0.3f, v); !error.empty())
        throw CliError{ kBadInput, name + ": " + error };
    if (o.runsWithout(Physics::HeadContact))
        sim.solver().setCollider(nullptr);
    BenchResult r{ name };
    r.particles = sim.solver().particleCount();
    r.strands = sim.solver().strandCount();
    r.threads = sim.solver().threadCount();
    r.substeps = sim.solver().settings().substeps;
    timeSteps(
        o, [&] { sim.step(); }, r, &sim.solver().threadPool());
    r.physics = physicsOf(sim.solver()); // (as the steps ran)
    // After the steps: the volume grid and its per-thread slots are made by the first step.
    r.solverBytesPerParticle = static_cast<double>(sim.solver().memoryBytes()) / static_cast<double>(r.particles);
    return r;
}

// N strands x 15 particles rooted all over a sphere of radius 0.1 m (a Fibonacci lattice),
// 0.3 m long, gravity 9.81, drag 0.5 toward a wind of (2, 0, 0.5) m/s, dt 1/60 s, sphere collision.
BenchResult sphereWorkload(const RunOptions& o)
{
    const std::size_t n = o.sphereStrands;
    HairCurves rest;
    rest.offsets.reserve(n + 1);
    rest.positions.reserve(n * 15);
    const float golden = glm::pi<float>() * (3.0f - std::sqrt(5.0f));
    for (std::size_t i = 0; i < n; ++i) {
        const float y = 1.0f - 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
        const float r = std::sqrt(1.0f - y * y);
        const float a = golden * static_cast<float>(i);
        const glm::vec3 dir(r * std::cos(a), y, r * std::sin(a));
        auto points = rest.strandForWrite(rest.addStrand(15));
        for (int j = 0; j < 15; ++j)
            points[j] = dir * (0.1f + 0.3f * static_cast<float>(j) / 14.0f);
    }
    Solver solver(o.threads);
    if (std::string error = solver.setStrands(rest); !error.empty())
        throw CliError{ kBadInput, "sphere: " + error };
    SolverSettings s;
    s.timeStepSeconds = 1.0f / 60.0f;
    s.substeps = 1;
    s.gravity = { 0.0f, -9.81f, 0.0f };
    s.dragPerSecond = 0.5f;
    s.wind = { 2.0f, 0.0f, 0.5f };
    s.dampingPerSecond = 0.0f;
    s.stiffness = 0.0f;
    s.friction = 0.0f;
    s.hairOffsetMetres = 0.0f;
    if (const std::string error = solver.setSettings(s); !error.empty())
        throw CliError{ kBadInput, "sphere workload: " + error };
    solver.setCapsules({ Capsule{ { 0, 0, 0 }, { 0, 0, 0 }, 0.1f } });
    BenchResult r{ "sphere" };
    r.particles = solver.particleCount();
    r.strands = solver.strandCount();
    r.threads = solver.threadCount();
    r.substeps = s.substeps;
    timeSteps(
        o, [&] { solver.step(); }, r, &solver.threadPool());
    r.physics = physicsOf(solver); // (as the steps ran)
    r.solverBytesPerParticle = static_cast<double>(solver.memoryBytes()) / static_cast<double>(r.particles);
    return r;
}

// A head for the brush workload: the file given with --head, placed as the editor places it
// (io/HeadPlacement.h), or the default head.
TriangleMesh benchHead(const std::string& path)
{
    if (path.empty())
        return makeDefaultHead().mesh;
    io::Result<io::MeshReadResult> read = io::readMesh(path);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    TriangleMesh mesh = std::move(read).value().mesh;
    io::HeadPlacementSettings settings;
    if (io::formatFixesUpAxis(path))
        settings.up = io::Axis::PosY;
    io::placeHead(mesh, settings);
    return mesh;
}

// The scene the editor starts a head from a file with: one region, "Scalp", grown on its scalp.
std::vector<GrowthRegion> scalpOf(const TriangleMesh& head)
{
    std::vector<GrowthRegion> regions(1);
    regions[0].name = "Scalp";
    regions[0].weights = scalpGrowth(head);
    return regions;
}

// One brush dab while the hair simulates, as the editor does it: the dab on the growth weights,
// then the regroom that brings new roots into the running solver (HairSimulation::regroom). Dabs
// walk around the scalp, adding on one lap and erasing on the next, so the groom neither fills up
// nor empties. The default scene's groom parameters.
BenchResult brushWorkload(const RunOptions& o)
{
    const TriangleMesh head = benchHead(o.headPath);
    std::vector<GrowthRegion> regions = scalpOf(head);
    const ParameterValues v;
    HairSimulation sim(o.threads);
    if (std::string error = sim.setup(head, regions, kNoSolo, v); !error.empty())
        throw CliError{ kBadInput, "brush-dab: " + error };
    const ScalpBrush brush(head);
    const Aabb box = boundsOf(head);
    std::vector<glm::vec3> path;
    for (int i = 0; i < 48; ++i) {
        const float a = glm::two_pi<float>() * static_cast<float>(i) / 48.0f;
        const glm::vec3 around = box.center()
            + glm::vec3(0.6f * box.size().x * std::cos(a), 0.15f * box.size().y, 0.6f * box.size().z * std::sin(a));
        path.push_back(sim.bvh().closestPoint(around).point);
    }
    BrushSettings settings;
    settings.radiusMetres = 0.02f;
    int dab = 0;
    BenchResult r{ o.headPath.empty() ? "brush-dab"
                                      : "brush-dab (" + o.headPath.substr(o.headPath.rfind('/') + 1) + ")" };
    r.solverSteps = false;
    r.threads = sim.solver().threadCount();
    r.substeps = sim.solver().settings().substeps;
    timeSteps(
        o,
        [&] {
            settings.mode = (dab / static_cast<int>(path.size())) % 2 == 0 ? BrushMode::Add : BrushMode::Erase;
            brush.dab(path[static_cast<std::size_t>(dab) % path.size()], settings, regions[0].weights.forWrite());
            ++dab;
            if (std::string error = sim.regroom(regions, kNoSolo, v); !error.empty())
                throw CliError{ kBadInput, "brush-dab: " + error };
        },
        r);
    r.particles = sim.solver().particleCount();
    r.strands = sim.groom().strandCount();
    r.physics = physicsOf(sim.solver());
    r.solverBytesPerParticle
        = static_cast<double>(sim.solver().memoryBytes()) / static_cast<double>(std::max<std::size_t>(1, r.particles));
    return r;
}

// Letting go of a comb stroke while the hair simulates, as the editor does it: the combed key hairs
// (those rooted within 3 cm of a point walking around the scalp, about a 2 cm brush's catch) get
// their current shape turned 20 degrees about the root as their new shape, then the regroom solves
// the rest shapes that hold it (RestShapeSolve.h) and restarts those strands. ms per release.
BenchResult combWorkload(const RunOptions& o)
{
    const TriangleMesh head = benchHead(o.headPath);
    const std::vector<GrowthRegion> regions = scalpOf(head);
    const ParameterValues v;
    HairSimulation sim(o.threads);
    if (std::string error = sim.setup(head, regions, kNoSolo, v); !error.empty())
        throw CliError{ kBadInput, "comb-release: " + error };
    for (int i = 0; i < 120; ++i)
        sim.step();
    const Aabb box = boundsOf(head);
    auto edits = std::make_shared<StyleEdits>();
    std::size_t combed = 0;
    int stroke = 0;
    BenchResult r{ o.headPath.empty() ? "comb-release"
                                      : "comb-release (" + o.headPath.substr(o.headPath.rfind('/') + 1) + ")" };
    r.solverSteps = false;
    r.threads = sim.solver().threadCount();
    r.substeps = sim.solver().settings().substeps;
    timeSteps(
        o,
        [&] {
            const float a = glm::two_pi<float>() * static_cast<float>(stroke % 48) / 48.0f;
            const glm::vec3 at = box.center()
                + glm::vec3(0.6f * box.size().x * std::cos(a), 0.15f * box.size().y, 0.6f * box.size().z * std::sin(a));
            const float turn = glm::radians(stroke % 2 == 0 ? 20.0f : -20.0f);
            ++stroke;
            HairCurves frame;
            sim.buildFrame(frame);
            const Groom& g = sim.groom();
            const glm::vec3 point = sim.bvh().closestPoint(at).point;
            const glm::mat3 rotation(glm::rotate(glm::mat4(1.0f), turn, glm::vec3(1.0f, 0.0f, 0.0f)));
            for (std::size_t w = 0; w < g.wispCount(); ++w) {
                const std::uint32_t k = g.keyStrand[w];
                if (glm::distance(g.rootPositions[k], point) > 0.03f)
                    continue;
                const auto strand = frame.strand(k);
                std::vector<glm::vec3> shape;
                for (const glm::vec3& p : strand)
                    shape.push_back(strand.front() + rotation * (p - strand.front()));
                (*edits)[g.strandIdentity(k)].shape = std::move(shape);
                ++combed;
            }
            sim.setStyle(std::make_shared<const StyleEdits>(*edits));
            if (std::string error = sim.regroom(regions, kNoSolo, v); !error.empty())
                throw CliError{ kBadInput, "comb-release: " + error };
        },
        r);
    r.particles = sim.solver().particleCount();
    r.strands = combed / static_cast<std::size_t>(std::max(1, stroke)); // combed key hairs per release
    r.physics = physicsOf(sim.solver());
    r.solverBytesPerParticle
        = static_cast<double>(sim.solver().memoryBytes()) / static_cast<double>(std::max<std::size_t>(1, r.particles));
    return r;
}

struct Workload {
    std::string name;
    std::string description;
    std::function<BenchResult(const RunOptions&)> run;
};

std::vector<Workload> workloads()
{
    auto grid = [](const std::string& name, int w, int h, int p) {
        return Workload{ name,
            std::to_string(w) + " x " + std::to_string(h) + " strands x " + std::to_string(p)
                + " particles on the default head (Table 1 of the force-driven paper)",
            [=](const RunOptions& o) { return gridWorkload(name, w, h, p, o); } };
    };
    return {
        grid("paper-15x15x10", 15, 15, 10),
        grid("paper-20x20x15", 20, 20, 15),
        grid("paper-25x25x20", 25, 25, 20),
        grid("paper-35x35x30", 35, 35, 30),
        grid("groom-1m", 250, 250, 16),
        { "sphere", "N strands x 15 particles on a 0.1 m sphere, wind (2, 0, 0.5) m/s (set N with --strands)",
            sphereWorkload },
        { "brush-dab",
            "one 2 cm growth-brush dab plus the live regroom, on the default head or --head FILE "
            "(ms per dab; particles and strands are the simulation's)",
            brushWorkload },
        { "comb-release",
            "letting go of a comb stroke: the combed keys' rest shapes solved and the live regroom, "
            "on the default head or --head FILE (ms per release; strands: combed key hairs per release)",
            combWorkload },
    };
}

// `--without`'s list: known names, comma-separated (spaces around a name are allowed, a name
// given twice counts once); an error names the first item that is not one, and the choices.
std::vector<Physics> physicsToTurnOff(const std::string& list)
{
    const std::string choices = namesOf({ Physics::HeadContact, Physics::Bending, Physics::Gusts, Physics::Volume });
    std::vector<Physics> off;
    std::size_t from = 0;
    while (true) {
        const std::size_t comma = std::min(list.find(',', from), list.size());
        std::string item = list.substr(from, comma - from);
        item.erase(0, item.find_first_not_of(' '));
        item.erase(item.find_last_not_of(' ') + 1);
        if (item.empty())
            throw CliError{ kBadInput,
                "--without: expects physics names separated by commas, with none empty (there are: " + choices + ")" };
        const auto named = std::find_if(
            kPhysicsNames, kPhysicsNames + kPhysicsToTurnOff, [&](const PhysicsName& p) { return item == p.name; });
        if (named == kPhysicsNames + kPhysicsToTurnOff)
            throw CliError{ kBadInput,
                "--without: no physics '" + item + "' to turn off (there are: " + choices + ")" };
        if (std::find(off.begin(), off.end(), named->physics) == off.end())
            off.push_back(named->physics);
        if (comma == list.size())
            return off;
        from = comma + 1;
    }
}

bool isGridWorkload(const std::string& name)
{
    return name == "groom-1m" || name.rfind("paper-", 0) == 0;
}

double ratioToFloor(const BenchResult& r)
{
    return r.floorMs > 0.0 ? r.medianMs / r.floorMs : 0.0;
}

// `text` as a JSON string's contents: quotes and backslashes escaped, control characters left out
// (a --head file's name goes into a row's name).
std::string jsonText(const std::string& text)
{
    std::string out;
    for (char c : text)
        if (c == '"' || c == '\\')
            out += std::string("\\") + c;
        else if (static_cast<unsigned char>(c) >= 0x20)
            out += c;
    return out;
}

std::string json(const BenchResult& r)
{
    char peak[32] = "null"; // (the floor's row: timed beside the workload, no peak of its own)
    if (r.peakRssMb >= 0.0)
        std::snprintf(peak, sizeof peak, "%.1f", r.peakRssMb);
    const std::string name = jsonText(r.name), cpu = jsonText(cpuModelName());
    const std::string physics = namesOf(r.physics, "\""); // (the floor's row: none)
    auto print = [&](char* to, std::size_t size) {
        return std::snprintf(to, size,
            "{\"name\": \"%s\", \"target\": \"%s\", \"particles\": %zu, \"strands\": %zu, \"threads\": %d, "
            "\"substeps\": %d, \"steps\": %d, \"ms_per_step\": %.4f, \"ms_per_step_mean\": %.4f, "
            "\"floor_ms_per_step\": %.4f, \"ratio_to_floor\": %.2f, \"physics\": [%s], \"cpu\": \"%s\", "
            "\"solver_bytes_per_particle\": %.1f, \"peak_rss_mb\": %s}",
            name.c_str(), solverSimdTarget(), r.particles, r.strands, r.threads, r.substeps, r.steps, r.medianMs,
            r.meanMs, r.floorMs, ratioToFloor(r), physics.c_str(), cpu.c_str(), r.solverBytesPerParticle, peak);
    };
    // Sized first, so that a long file name or CPU name never cuts the row short.
    std::string row(static_cast<std::size_t>(std::max(0, print(nullptr, 0))), '\0');
    print(row.data(), row.size() + 1);
    return row;
}

} // namespace

int runBench(int argc, char** argv)
{
    const std::vector<OptionSpec> options = {
        { "help", "", "show this help" },
        { "json", "", "print one JSON object a line per workload instead of a table" },
        { "workload", "NAME", "run only this workload (see the list below)" },
        { "threads", "N", "solver threads (default: one per core)" },
        { "strands", "N", "strands of the sphere workload (default 10000)" },
        { "steps", "N", "measured steps per workload after 20 warm-up steps (default 100, at least 50)" },
        { "volume", "V",
            "hair-hair interaction of the grid workloads, 0..1 (0 off; default: the volume parameter's default)" },
        { "head", "FILE",
            "head mesh for the brush-dab and comb-release workloads (OBJ, PLY, OFF, STL; default: the built-in head)" },
        { "target", "NAME",
            "run the solver's kernels on this SIMD target instead of the best this CPU has (AVX-512, AVX2, SSE4, "
            "...: the first line of the table lists them)" },
        { "without", "LIST",
            "run the grid workloads without these physics, comma-separated: head-contact (the solver gets no "
            "head), bending (stiffness 0), gusts (turbulence 0), volume (volume 0); to see what each costs" },
    };
    const CommandLine args(argc, argv, 2, options);
    const std::vector<Workload> all = workloads();
    if (args.has("help")) {
        std::cout << "usage: wisp-cli bench [options]\n\n" << describeOptions(options) << "\nworkloads:\n";
        for (const Workload& w : all)
            std::cout << "  " << w.name << std::string(w.name.size() < 16 ? 16 - w.name.size() : 1, ' ')
                      << w.description << "\n";
        std::cout << "\nms_per_step is the median wall-clock time of one solver step; peak_rss_mb the process's\n"
                     "peak resident memory during that workload. Each stepping workload is timed in turns\n"
                     "with the floor, 10 steps of each at a time on the same threads: the minimal\n"
                     "follow-the-leader sweep over as many particles (each position and previous position\n"
                     "read and written once, one length constraint, nothing else), printed in the row after\n"
                     "it; x floor is the workload's ratio to it, how far it is from what this machine allows.\n"
                     "physics (JSON) lists what the workload's solver was set up to step with, read from the\n"
                     "solver: head-contact, bending, gusts, volume, capsules.\n";
        return kSuccess;
    }
    RunOptions o;
    o.threads = static_cast<int>(args.integer("threads", 0, 0, 1024));
    o.measuredSteps = static_cast<int>(args.integer("steps", 100, 50, 1'000'000));
    o.sphereStrands = static_cast<std::size_t>(args.integer("strands", 10'000, 1, 4'000'000));
    o.headPath = args.text("head").value_or("");
    if (args.has("volume"))
        o.volume = args.real("volume", 0.0);
    if (o.volume != -1.0 && !checkParameterValue(Param::Volume, o.volume).empty())
        throw CliError{ kBadInput, "--" + checkParameterValue(Param::Volume, o.volume) };
    if (const auto without = args.text("without"))
        o.without = physicsToTurnOff(*without);
    if (o.runsWithout(Physics::Volume) && o.volume != -1.0)
        throw CliError{ kBadInput, "--without volume and --volume: give one of them" };
    const auto only = args.text("workload");
    if (only) {
        bool known = false;
        for (const Workload& w : all)
            known = known || w.name == *only;
        if (!known) {
            std::string names;
            for (const Workload& w : all)
                names += " " + w.name;
            throw CliError{ kBadInput, "--workload: no workload '" + *only + "' (there are:" + names + ")" };
        }
        if (!o.without.empty() && !isGridWorkload(*only))
            throw CliError{ kBadInput,
                "--without: the " + *only
                    + " workload keeps its own physics; --without is for the grid workloads "
                      "(paper-*, groom-1m)" };
    }
    if (const auto target = args.text("target")) {
        if (std::string why = forceSimdTarget(*target); !why.empty())
            throw CliError{ kBadInput, "--target: " + why };
    }
    const bool asJson = args.has("json");
    if (!asJson) {
        std::string available;
        for (const std::string& t : availableSimdTargets())
            available += (available.empty() ? "" : ", ") + t;
        std::printf("target %s (chosen at run time of %s; %d floats a register, the solver's lanes are 16)\n",
            solverSimdTarget(), available.c_str(), solverVectorFloats());
        if (const unsigned cores = std::thread::hardware_concurrency(); cores > 0)
            std::printf("cpu %s, %u logical cores\n", cpuModelName().c_str(), cores);
        else
            std::printf("cpu %s\n", cpuModelName().c_str());
        if (!o.without.empty())
            std::printf("the grid workloads without %s\n", namesOf(o.without).c_str());
        std::printf("%-16s %10s %8s %7s %8s %12s %12s %8s %10s %10s\n", "workload", "particles", "strands", "threads",
            "substeps", "ms/step", "mean ms", "x floor", "B/particle", "peak MB");
    }
    auto print = [&](const BenchResult& r) {
        if (asJson) {
            std::printf("%s\n", json(r).c_str());
        } else {
            char ratio[16] = "-";
            if (r.floorMs > 0.0)
                std::snprintf(ratio, sizeof ratio, "%.2f", ratioToFloor(r));
            char peak[16] = "-";
            if (r.peakRssMb >= 0.0)
                std::snprintf(peak, sizeof peak, "%.1f", r.peakRssMb);
            std::printf("%-16s %10zu %8zu %7d %8d %12.4f %12.4f %8s %10.1f %10s\n", r.name.c_str(), r.particles,
                r.strands, r.threads, r.substeps, r.medianMs, r.meanMs, ratio, r.solverBytesPerParticle, peak);
        }
        std::fflush(stdout);
    };
    for (const Workload& w : all) {
        if (only && w.name != *only)
            continue;
        resetPeakRss();
        BenchResult r = w.run(o);
        if (!r.floor) // (a workload timed beside its floor read its own peak before the floor's rows)
            r.peakRssMb = peakRssMb();
        print(r);
        if (r.floor)
            print(*r.floor);
    }
    return kSuccess;
}

} // namespace wisp::cli
