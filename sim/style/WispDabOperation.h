#pragma once
// What the perm, the wet brush and hairspray share: each dab finds the strands under the ring and
// changes their wisps, on the wisp's key hair (whose edit the members follow), once per stroke.
// Each brush says what it does to one wisp.

#include "sim/style/StyleOperation.h"

#include <set>

namespace wisp {

class WispDabOperation : public StyleOperation {
public:
    StyleEffects begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    StyleEffects step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits) override;
    bool dabs() const override { return true; }

protected:
    // Changes the edit of the wisp whose key hair is `key` (picked with `weight`, the falloff there).
    virtual void applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key, float weight,
        StrandStyle& edit, StyleEffects& effects)
        = 0;

private:
    std::set<std::uint64_t> m_touched; // key hairs this stroke already changed
};

// Perm: the touched wisps take the context's curl radius and turns (inverted: the region's again).
// A perm re-forms the hair: a combed shape gives way to the curl.
class CurlOperation : public WispDabOperation {
protected:
    void applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key, float weight,
        StrandStyle& edit, StyleEffects& effects) override;
};

// Wet: the touched wisps become at least as wet as the brush's strength, at once in the simulation
// too (inverted: towel-dried).
class WetOperation : public WispDabOperation {
protected:
    void applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key, float weight,
        StrandStyle& edit, StyleEffects& effects) override;
};

// Hairspray: the touched wisps hold the shape they have now, stiffer by the strength (inverted:
// washed out).
class HairsprayOperation : public WispDabOperation {
public:
    // At full strength a stroke multiplies the stiffness by 1 + this.
    static constexpr float kStiffening = 9.0f;

protected:
    void applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key, float weight,
        StrandStyle& edit, StyleEffects& effects) override;
};

} // namespace wisp
