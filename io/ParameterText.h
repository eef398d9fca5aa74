#pragma once
// Parameter files for wisp-cli: one "key = value" a line, keys from the parameter registry,
// '#' starts a comment. (Versioned JSON presets come with the files work; they use the same keys.)
//
//   # windy afternoon
//   gravity = 9.81
//   wind_speed = 12

#include "io/IoError.h"
#include "sim/params/Parameters.h"

#include <string>
#include <vector>

namespace wisp::io {

struct ParameterFile {
    std::vector<std::pair<Param, double>> values; // in file order
};

// Unknown keys, malformed lines and out-of-range values are errors naming the line and the key.
Result<ParameterFile> readParameterText(const std::string& path);

} // namespace wisp::io
