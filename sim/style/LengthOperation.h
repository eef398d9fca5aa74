#pragma once
// Grow / shrink: each dab lengthens every strand under the ring by a share of its length (inverted:
// shortens it), weighted by the brush's falloff, within the Length parameter's limits.

#include "sim/style/StyleOperation.h"

namespace wisp {

class LengthOperation : public StyleOperation {
public:
    StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override
    {
        return step(context, sample, edits);
    }
    StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    bool dabs() const override { return true; }

    // A dab at full strength and full weight changes a strand by this share of its length.
    static constexpr float kStepShare = 0.06f;
};

} // namespace wisp
