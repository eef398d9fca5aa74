#include "sim/style/WispDabOperation.h"

#include "sim/style/StrandPicking.h"

#include <algorithm>

namespace wisp {

StyleEffects WispDabOperation::begin(const BrushContext& context, const BrushSample& sample, StyleEdits& edits)
{
    m_touched.clear();
    return step(context, sample, edits);
}

StyleEffects WispDabOperation::step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits)
{
    StyleEffects effects;
    if (!hasStyledHair(context))
        return effects;
    const Frame& frame = *context.frame;
    const GroomShape& shape = *frame.groomShape;
    const BrushSettings& s = context.brush;
    for (const BrushRay& ray : brushRays(context, sample))
        for (const StrandPick& pick : strandsNearRay(
                 frame.strands, {}, ray.origin_ws, ray.direction_ws, s.radiusMetres, s.falloff, ray.maxDepthMetres)) {
            if (pick.strand >= shape.wispOf.size())
                continue;
            const std::uint32_t key = shape.keyOfWisp[shape.wispOf[pick.strand]];
            const std::uint64_t id = shape.identities[key];
            if (!m_touched.insert(id).second)
                continue;
            applyToWisp(context, sample, key, pick.weight, edits[id], effects);
            effects.editsChanged = true;
        }
    return effects;
}

void CurlOperation::applyToWisp(
    const BrushContext& context, const BrushSample& sample, std::uint32_t, float, StrandStyle& edit, StyleEffects&)
{
    edit.curlRadiusMetres = sample.inverted ? -1.0f : context.curlRadiusMetres;
    edit.curlTurnsPerMetre = sample.inverted ? -1.0f : context.curlTurnsPerMetre;
    edit.shape.clear();
}

void WetOperation::applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key, float,
    StrandStyle& edit, StyleEffects& effects)
{
    const float strength = context.brush.strength;
    edit.wetness = sample.inverted ? 0.0f : std::max(edit.wetness, strength);
    if (sample.inverted)
        return;
    // The simulation gets wet at once, even where the edit was already as wet (it may have dried).
    effects.wettedKeys.push_back(context.frame->groomShape->identities[key]);
    effects.wetness = strength;
}

void HairsprayOperation::applyToWisp(const BrushContext& context, const BrushSample& sample, std::uint32_t key,
    float weight, StrandStyle& edit, StyleEffects&)
{
    if (sample.inverted) {
        edit.stiffnessScale = 1.0f;
        edit.shape.clear();
        return;
    }
    // A spray covers its cone about evenly: the falloff softens only the rim.
    const float cover = std::max(weight, 0.5f);
    edit.stiffnessScale = std::clamp(
        edit.stiffnessScale * (1.0f + kStiffening * context.brush.strength * cover), 1.0f, kStyleMaxStiffnessScale);
    // The shape it has now is the one to hold, head space (the head may have moved).
    const glm::mat4 toHead = worldToHeadOf(context.frame);
    edit.shape.clear();
    for (const glm::vec3& p_ws : context.frame->strands.strand(key))
        edit.shape.push_back(glm::vec3(toHead * glm::vec4(p_ws, 1.0f)));
}

} // namespace wisp
