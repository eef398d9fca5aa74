#pragma once
// A salon brush's stroke as an operation (after Blender's curves_sculpt_* operations): begin at
// the first sample, step at each later one, end when the stroke ends. The operation keeps what
// lasts the stroke (the comb's caught strands, the wisps already permed); each call reads the
// context afresh (the caller refreshes its frame) and writes the stroke's edits, head space, into
// `edits`. The caller turns those into one undoable step and passes on the live effects it
// returns (strands to hold, wisps to wet, dryers to blow).
//
// Thread: any, one stroke on one thread. Never throws, never logs.

#include "sim/style/BrushContext.h"
#include "sim/style/HairDryer.h"
#include "sim/style/StyleEdits.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace wisp {

// A simulated strand held where the comb drags it: identity (Groom::strandIdentity) and positions,
// world space, root first.
struct HeldStrand {
    std::uint64_t identity = 0;
    std::vector<glm::vec3> positions_ws;
};

// What one call did, beyond the edits.
struct StyleEffects {
    bool editsChanged = false; // `edits` changed: the hair should follow
    std::optional<std::vector<HeldStrand>> held; // hold these now (an empty list lets go)
    std::vector<std::uint64_t> wettedKeys; // wet these wisps' key hairs now, at `wetness`
    float wetness = 0.0f;
    std::optional<std::vector<HairDryer>> dryers; // blow these now (an empty list puts them down)
};

class StyleOperation {
public:
    virtual ~StyleOperation() = default;
    virtual StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) = 0;
    virtual StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) = 0;
    // The stroke's end (the button released, or the stroke cut short).
    virtual StyleEffects end(const BrushContext& context, StyleEdits& edits)
    {
        (void)context;
        (void)edits;
        return {};
    }
    // Dab brushes want samples spaced along the stroke (the caller spaces them); the others take
    // every sample.
    virtual bool dabs() const { return false; }
    // How many strands the stroke changed, to tell the artist, given how many edits it left.
    virtual int changedStrands(int editedStrands) const { return editedStrands; }
};

[[nodiscard]] std::unique_ptr<StyleOperation> makeStyleOperation(StyleBrush brush);

} // namespace wisp
