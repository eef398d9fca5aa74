#pragma once
// The comb (Lee et al.): catches the strands under the brush ring as the stroke begins, drags them
// along the stroke (at the depth each was caught) and, when it ends, makes the dragged shape where
// they rest (the simulation solves the rest shape that sags onto it). Members are not simulated
// unless every strand is: a wisp is caught by its key hair when any of its strands is under the
// ring, as firmly as its strand nearest the ring's centre.

#include "sim/style/StyleOperation.h"

namespace wisp {

class CombOperation : public StyleOperation {
public:
    StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    StyleEffects end(const BrushContext& context, StyleEdits& edits) override;
    // The drawn strands the stroke moves (a key hair's wisp follows it), not only the key hairs.
    int changedStrands(int editedStrands) const override { return editedStrands > 0 ? m_movedStrands : 0; }

    std::size_t caughtStrands() const { return m_caught.size(); }
    // Along the view ray, where the first caught strand was caught (the ring follows it off the head).
    std::optional<float> catchDepthMetres() const;

private:
    struct Caught {
        std::uint64_t identity = 0;
        float weight = 0.0f;
        float depthMetres = 0.0f;
        bool mirrored = false;
        std::vector<glm::vec3> positions_ws;
        std::vector<float> segmentLengthsMetres;
    };
    std::vector<Caught> m_caught;
    int m_movedStrands = 0;
    BrushSample m_last;
};

} // namespace wisp
