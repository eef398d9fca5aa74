// wisp-cli convert: hair from one format to another (cyHair .hair, USC .data in; .hair, .data,
// OBJ polylines, glTF and GLB out), optionally with a head beside the strands.

#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/OutputCheck.h"

#include "io/HairFiles.h"
#include "io/MeshReader.h"

#include <iostream>

namespace wisp::cli {

namespace {

std::string joined(const std::vector<std::string>& extensions)
{
    std::string s;
    for (const std::string& e : extensions)
        s += (s.empty() ? "." : ", .") + e;
    return s;
}

} // namespace

int runConvert(int argc, char** argv)
{
    const std::vector<OptionSpec> options = {
        { "help", "", "show this help" },
        { "head", "FILE", "a head mesh to write beside the strands (.gltf, .glb and .obj outputs)" },
        { "scale", "FACTOR", "multiply every coordinate, strands and head alike (default 1: kept as stored)" },
        { "root-width", "METRES", "glTF _WIDTH at each root (default 0.00008)" },
        { "tip-width", "METRES", "glTF _WIDTH at each tip (default 0.00002)" },
    };
    const CommandLine args(argc, argv, 2, options, 2);
    if (args.has("help")) {
        std::cout << "usage: wisp-cli convert IN OUT [options]\n\n"
                  << "Reads hair strands (" << joined(io::hairReadExtensions()) << ") and writes them ("
                  << joined(io::hairWriteExtensions()) << "); the extensions pick the formats.\n"
                  << "Coordinates are kept as stored.\n\n"
                  << describeOptions(options);
        return kSuccess;
    }
    if (args.positional().size() != 2)
        throw CliError{ kUsage, "needs IN and OUT files (see --help)" };
    const std::string& in = args.positional()[0];
    const std::string& out = args.positional()[1];
    checkOutputPath(out, "OUT", io::hairWriteExtensions());

    io::Result<io::HairReadResult> hair = io::readHair(in);
    if (!hair)
        throw CliError{ kBadInput, hair.error().toString() };
    for (const std::string& warning : hair.value().warnings)
        std::cerr << "wisp-cli convert: " << in << ": " << warning << "\n";
    io::HairExportOptions export_;
    export_.rootWidthMetres = static_cast<float>(args.real("root-width", export_.rootWidthMetres));
    export_.tipWidthMetres = static_cast<float>(args.real("tip-width", export_.tipWidthMetres));
    const double scale = args.real("scale", 1.0);
    if (!(scale > 0.0 && scale < 1e6))
        throw CliError{ kBadInput, "--scale: " + *args.text("scale") + " must be a positive factor" };
    // The head is written as stored, like the strands: files made together stay together.
    std::optional<TriangleMesh> head;
    if (const auto path = args.text("head")) {
        io::Result<io::MeshReadResult> read = io::readMesh(*path);
        if (!read)
            throw CliError{ kBadInput, read.error().toString() };
        head = std::move(read).value().mesh;
        for (glm::vec3& p : head->positions)
            p *= static_cast<float>(scale);
        export_.head = &*head;
    }
    HairCurves strands = std::move(hair).value().strands;
    for (glm::vec3& p : strands.positions)
        p *= static_cast<float>(scale);
    if (const io::Result<void> written = io::writeHair(out, strands, export_); !written)
        throw CliError{ kBadInput, written.error().toString() };
    std::cout << "converted " << strands.strandCount() << " strands (" << strands.positions.size() << " points) from "
              << in << " to " << out << "\n";
    return kSuccess;
}

} // namespace wisp::cli
