#pragma once
// The scissors (Lee et al.): each move of the stroke sweeps a blade, the wedge between the last
// view ray and this one; every strand it crosses, where the artist can see the crossing, is cut
// there. A wisp's members ride beside its key hair point for point: where the key is cut, members
// the blade missed are cut to its length too, or they would stick out past its tip.

#include "sim/style/StyleOperation.h"

namespace wisp {

class CutOperation : public StyleOperation {
public:
    StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;

    // Hair lying on the skin may sit a little inside the mesh (the collider is a sampled field): a
    // surface within this distance before a crossing does not hide it.
    static constexpr float kSkinToleranceMetres = 0.01f;

private:
    BrushSample m_last;
};

} // namespace wisp
