#pragma once
// Wisp's plain-text strand format ("wisp-strands 1"), written by `wisp-cli simulate --out`.
// Human-readable and trivial to parse from any language:
//
//   wisp-strands 1
//   strands <S> points <P>
//   <n> x0 y0 z0 x1 y1 z1 ... (one line per strand: its point count, then its points in metres)
//
// Lines starting with '#' are comments. Real interchange formats (cyHair .hair, glTF) come with the files work.

#include "io/IoError.h"
#include "sim/geometry/HairCurves.h"

#include <string>

namespace wisp::io {

// Writes atomically: to a temporary file beside `path`, then renamed over it.
Result<void> writeStrandText(const std::string& path, const HairCurves& curves);
Result<HairCurves> readStrandText(const std::string& path);

} // namespace wisp::io
