#pragma once
// The blow-dryer (Ward et al.): while the stroke lasts, a cone of air from the eye's side toward the
// hair under the cursor pushes and dries the hair (the simulation blows it); when it ends, the
// edits keep how wet the dried wisps are now, so drying is undone with the stroke.

#include "sim/style/StyleOperation.h"

#include <map>

namespace wisp {

class BlowDryOperation : public StyleOperation {
public:
    StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    // Reads the wetness from the context's frame: the caller gives it the newest.
    StyleEffects end(const BrushContext& context, StyleEdits& edits) override;

private:
    std::map<std::uint64_t, float> m_wetBefore; // key identity -> wetness applied as the stroke began
};

} // namespace wisp
