#pragma once
// How wisp-cli brings a head in: read (OBJ, PLY, OFF, STL, glTF), then placed as the editor places
// it (io/HeadPlacement.h: unit from the skull's width unless --scale says, up axis from the shape
// unless --up says, centred). What was decided goes to stdout, the placement's warnings to stderr.

#include "io/HeadPlacement.h"
#include "sim/geometry/TriangleMesh.h"

#include <optional>
#include <string>

namespace wisp::cli {

struct LoadedHead {
    TriangleMesh mesh;
    io::HeadPlacement placement;
};

// Refuses a head the groom and solver cannot use (io::checkPlacedHead: flat, or absurdly large
// once placed). Throws CliError{kBadInput} naming the file and the problem; prints the reader's warnings to
// stderr prefixed with `command`.
// `up`: the file's up axis as given on the command line, or nullopt to find it from the shape.
LoadedHead loadHead(
    const std::string& path, std::optional<double> scale, std::optional<io::Axis> up, const std::string& command);

} // namespace wisp::cli
