#include "app/cli/HeadLoading.h"

#include "app/cli/CommandLine.h"
#include "io/MeshReader.h"

#include <iostream>

namespace wisp::cli {

LoadedHead loadHead(
    const std::string& path, std::optional<double> scale, std::optional<io::Axis> up, const std::string& command)
{
    io::Result<io::MeshReadResult> read = io::readMesh(path);
    if (!read)
        throw CliError{ kBadInput, read.error().toString() };
    for (const std::string& warning : read.value().warnings)
        std::cerr << "wisp-cli " << command << ": " << path << ": " << warning << "\n";
    if (scale && !(*scale > 0.0 && *scale < 1e6))
        throw CliError{ kBadInput, "--scale: " + std::to_string(*scale) + " must be a positive factor" };
    LoadedHead head{ std::move(read).value().mesh, {} };
    io::HeadPlacementSettings settings;
    settings.explicitScale = scale ? static_cast<float>(*scale) : 0.0f;
    settings.up = io::formatFixesUpAxis(path) ? std::optional(io::Axis::PosY) : up;
    head.placement = io::placeHead(head.mesh, settings);
    std::cout << path << ": " << io::describePlacement(head.placement) << "; " << head.placement.orientation << "\n";
    if (!head.placement.note.empty())
        std::cerr << "wisp-cli " << command << ": " << path << ": warning: " << head.placement.note << "\n";
    if (std::string problem = io::checkPlacedHead(head.mesh); !problem.empty())
        throw CliError{ kBadInput, path + ": " + problem };
    return head;
}

} // namespace wisp::cli
