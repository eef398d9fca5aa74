#pragma once
// Where imported strands land: the one function the editor (File ▸ Import Hair) and wisp-cli
// (simulate --hair) both call, so that a groom sits on its head the same way in both.
//
// Strands come in the frame of the tool that made them, usually beside the head they were made
// on (CT2Hair's heads and strands share millimetres and +X up). So:
//   - with the head they came with (an imported head's placement): the head's placement moves the
//     strands too: the same turn, scale and centring (io/HeadPlacement.h), so roots stay on the scalp;
//   - without one (the built-in head): only the unit is guessed, as for heads, from the span of the
//     roots (a scalp's roots span 0.1 to under 0.3 m at their widest; the factors of ten are
//     millimetres, centimetres and metres); when no unit fits they are left as they are, and
//     `note` says so (a groom of a few roots gives no measure).
// A factor the artist gives overrides both (the strands are taken as Wisp's frame times it).
//
// Thread safety: pure function, callable from any thread.

#include "io/HeadPlacement.h"
#include "sim/geometry/HairCurves.h"

#include <string>

namespace wisp::io {

struct StrandPlacement {
    float scale = 1.0f; // metres per file unit
    LengthUnit unit = LengthUnit::Metres; // Auto: a chosen factor, or nothing fitted
    bool followedHead = false; // the head's placement was applied
    std::string description; // one line: "placed with the head (×0.001, ...)"
    std::string note; // a warning, or empty
};

// `head`: the placement of the head the strands were made on, or nullptr. `explicitScale` > 0:
// the artist's factor.
StrandPlacement placeStrands(HairCurves& strands, const HeadPlacement* head, float explicitScale = 0.0f);

} // namespace wisp::io
