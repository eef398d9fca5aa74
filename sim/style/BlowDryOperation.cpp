#include "sim/style/BlowDryOperation.h"

#include <cmath>

namespace wisp {

StyleEffects BlowDryOperation::begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits)
{
    m_wetBefore.clear();
    for (const auto& [id, style] : edits)
        if (style.wetness > 0.0f)
            m_wetBefore[id] = style.wetness;
    return step(context, sample, edits);
}

StyleEffects BlowDryOperation::step(const BrushContext& context, const BrushSample& sample, StyleEdits&)
{
    StyleEffects effects;
    effects.dryers = dryersFor(context, sample);
    return effects;
}

StyleEffects BlowDryOperation::end(const BrushContext& context, StyleEdits& edits)
{
    StyleEffects effects;
    effects.dryers.emplace();
    if (!hasStyledHair(context) || m_wetBefore.empty())
        return effects;
    const Frame& frame = *context.frame;
    const GroomShape& shape = *frame.groomShape;
    std::map<std::uint64_t, std::uint32_t> keyOf;
    for (std::uint32_t key : shape.keyOfWisp)
        keyOf.emplace(shape.identities[key], key);
    for (const auto& [id, applied] : m_wetBefore) {
        const auto key = keyOf.find(id);
        if (key == keyOf.end())
            continue;
        const float now = frame.wetness.empty() ? 0.0f : frame.wetness[key->second];
        if (now < applied - 0.005f) { // dried noticeably: kept to a thousandth
            edits[id].wetness = std::round(now * 1000.0f) / 1000.0f;
            effects.editsChanged = true;
        }
    }
    return effects;
}

} // namespace wisp
