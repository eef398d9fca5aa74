// wisp-cli validate: says what a head, hair, preset or project file holds, or exactly what is
// wrong with it (exit status 1).

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"

#include "io/HairFiles.h"
#include "io/HeadPlacement.h"
#include "io/MeshReader.h"
#include "io/PresetFile.h"
#include "io/ProjectFile.h"
#include "io/RegularFile.h"
#include "sim/groom/GrowthMap.h"
#include "sim/solver/HairSimulation.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>

namespace wisp::cli {

namespace {

bool contains(const std::vector<std::string>& list, const std::string& item)
{
    return std::find(list.begin(), list.end(), item) != list.end();
}

std::string size(const Aabb& box)
{
    char text[96];
    std::snprintf(text, sizeof text, "%.4g x %.4g x %.4g", box.size().x, box.size().y, box.size().z);
    return text;
}

void printWarnings(const std::vector<std::string>& warnings)
{
    for (const std::string& w : warnings)
        std::cout << "  warning: " << w << "\n";
}

void validateHead(const std::string& path)
{
    io::Result<io::MeshReadResult> read = io::readMesh(path);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    const TriangleMesh& asRead = read.value().mesh;
    std::cout << path << ": head mesh, " << asRead.positions.size() << " vertices, " << asRead.triangles.size()
              << " triangles, " << size(boundsOf(asRead)) << " file units\n";
    // The same steps as `simulate --head`: placed, checked (io::checkPlacedHead), then the groom and
    // collider built with the default parameters, so what validate accepts simulate can use.
    TriangleMesh placed = asRead;
    io::HeadPlacementSettings settings; // as simulate and the editor place it
    if (io::formatFixesUpAxis(path))
        settings.up = io::Axis::PosY;
    const io::HeadPlacement placement = io::placeHead(placed, settings);
    std::cout << "  " << io::describePlacement(placement) << " -> " << size(boundsOf(placed)) << " m\n";
    if (!placement.note.empty())
        std::cout << "  check: " << placement.note << "\n";
    if (std::string problem = io::checkPlacedHead(placed); !problem.empty())
        throw CliError{ kBadInput, path + ": " + problem };
    HairSimulation sim(1);
    if (std::string error = sim.setup(placed, scalpGrowth(placed), ParameterValues{}); !error.empty())
        throw CliError{ kBadInput, path + ": " + error };
    std::cout << "  default groom: " << sim.groom().strandCount() << " strands\n";
    printWarnings(read.value().warnings);
    printWarnings(sim.groomWarnings());
}

void validateHair(const std::string& path)
{
    io::Result<io::HairReadResult> read = io::readHair(path);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    const HairCurves& c = read.value().strands;
    std::uint32_t fewest = c.strandCount() ? ~0u : 0, most = 0;
    for (std::size_t s = 0; s < c.strandCount(); ++s) {
        fewest = std::min(fewest, c.pointsIn(s));
        most = std::max(most, c.pointsIn(s));
    }
    Aabb box;
    if (!c.positions.empty())
        box = { c.positions.front(), c.positions.front() };
    for (const glm::vec3& p : c.positions) {
        box.min = glm::min(box.min, p);
        box.max = glm::max(box.max, p);
    }
    std::cout << path << ": hair, " << c.strandCount() << " strands, " << c.positions.size() << " points (" << fewest
              << " to " << most << " a strand), " << size(box) << " file units\n";
    printWarnings(read.value().warnings);
}

void validatePreset(const io::PresetReadResult& read, const std::string& path)
{
    const io::Preset& p = read.preset;
    std::cout << path << ": preset '" << p.name << "', " << p.regions.size() << " region(s)";
    for (const io::RegionLook& r : p.regions)
        std::cout << (&r == &p.regions.front() ? ": " : ", ") << r.name;
    std::cout << "\n";
    printWarnings(read.warnings);
}

void validateProject(const std::string& path)
{
    io::Result<io::ProjectReadResult> read = io::readProject(path, io::readHeadFile);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    const io::Project& p = read.value().project;
    std::cout << path << ": project, head " << (p.headEmbedded ? "embedded" : "from " + p.headSource) << " ("
              << p.head.positions.size() << " vertices, " << p.head.triangles.size() << " triangles), "
              << p.regions.size() << " region(s)";
    for (const GrowthRegion& r : p.regions)
        std::cout << (&r == &p.regions.front() ? ": " : ", ") << r.name
                  << (r.importedStrands ? " (" + std::to_string(r.importedStrands->strandCount()) + " imported strands)"
                                        : "");
    if (!p.style.empty())
        std::cout << "; " << p.style.size() << " styled strand(s)";
    std::cout << "\n";
    printWarnings(read.value().warnings);
}

} // namespace

int runValidate(int argc, char** argv)
{
    const std::vector<OptionSpec> options = { { "help", "", "show this help" } };
    const CommandLine args(argc, argv, 2, options, 1);
    if (args.has("help") || args.positional().empty()) {
        (args.has("help") ? std::cout : std::cerr)
            << "usage: wisp-cli validate FILE\n\n"
               "Says what FILE holds, or exactly what is wrong with it (exit status 1):\n"
               "  heads    .obj .ply .off .stl .gltf .glb\n"
               "  hair     .hair .data\n"
               "  presets  .json (format wisp-preset)\n"
               "  projects .wisp\n";
        return args.has("help") ? kSuccess : kUsage;
    }
    const std::string& path = args.positional().front();
    const std::string ext = io::lowerExtension(path);
    if (contains(io::supportedMeshExtensions(), ext))
        validateHead(path);
    else if (contains(io::hairReadExtensions(), ext))
        validateHair(path);
    else if (ext == "wisp")
        validateProject(path);
    else if (ext == "json") {
        io::Result<io::PresetReadResult> preset = io::readPreset(path);
        if (!preset) {
            // A project saved under .json is still a project.
            if (preset.error().toString().find("this is a Wisp project") != std::string::npos)
                validateProject(path);
            else
                throw CliError{ kBadInput, preset.error().toString() };
        } else {
            validatePreset(preset.value(), path);
        }
    } else {
        throw CliError{ kBadInput,
            path + ": Wisp does not know the extension '." + ext
                + "' (heads .obj .ply .off .stl .gltf .glb; hair .hair .data; presets .json; "
                  "projects .wisp)" };
    }
    return kSuccess;
}

} // namespace wisp::cli
