#pragma once
// Numbers in messages: the one formatter sim/ and io/ share, so that a value reads the same in a
// parameter error, a brush error and an import note.

#include <string>

namespace wisp {

// Six significant digits ("%.6g"): 0.0025, 1e+06, 12.5; a NaN is "nan" whatever its sign bit
// (glibc would print "-nan").
std::string formatNumber(double value);

} // namespace wisp
