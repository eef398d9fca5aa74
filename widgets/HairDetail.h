#pragma once
// Level of detail for the hair while it moves: Ward et al.'s answer to interactive hair (less
// detail while things change, all of it when they stop), applied to drawing. A software rasteriser
// (Mesa llvmpipe, as under Xvfb and in CI) spends a good fraction of a microsecond on every strand
// segment in single-threaded vertex and setup work, so a full head of ~70k segments, finely
// sampled, cannot reach 30 fps on two cores. A graphics card draws everything; this never engages.
//
// The viewport reports how long each paint's GL work took. Over budget, paints switch to preview:
// first the curves drop to one sample per segment, then, if still over, an even sample of the
// strands is drawn (HairStripLayout keeps them scrambled, so any prefix covers the head), each
// widened to make up for the others. Under budget, the fraction grows back, and preview ends when
// even the full preview costs under half the budget. When painting stops, the viewport draws one
// full-detail frame (refinement), which is not reported here.
//
// Thread: GUI. Pure C++: tested without a context.

#include <cstddef>

namespace wisp {

class HairDetail {
public:
    // GL work of one paint, leaving room for composing the window within a 30 fps frame.
    static constexpr double kBudgetMilliseconds = 20.0;
    // Grooms this small are always drawn whole, and previews never draw fewer strands than this.
    static constexpr std::size_t kMinimumStrands = 800;
    // A preview's strands are widened by the share they stand for (HairRenderer::draw), so the
    // coverage stays; below a third they become few wide flat bands (issue 14: "a few wide flat
    // ribbons" at a tenth), and the look is no longer the paused one. Slower, rather.
    static constexpr float kMinimumFraction = 1.0f / 3.0f;

    bool previewing() const { return m_previewing; }
    // The fraction of `strands` to draw in the next interactive paint, 0..1 (1 unless previewing).
    float fraction(std::size_t strands) const;
    // A paint drew `fractionDrawn` of `strands` strands, in preview or not, in `milliseconds`.
    void paintTook(double milliseconds, bool previewed, float fractionDrawn, std::size_t strands);
    void reset();

private:
    bool m_previewing = false;
    float m_fraction = 1.0f;
};

} // namespace wisp
