#pragma once
// How wisp-cli brings a head in: read (OBJ, PLY, OFF, STL, glTF), then placed as the editor places
// it (io/HeadPlacement.h: unit guessed from the size unless --scale says, centred, +Y up).

#include "io/HeadPlacement.h"
#include "sim/TriangleMesh.h"

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
LoadedHead loadHead(const std::string& path, std::optional<double> scale, bool zUp, const std::string& command);

}  // namespace wisp::cli
