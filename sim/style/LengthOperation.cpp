#include "sim/style/LengthOperation.h"

#include "sim/style/StrandPicking.h"

#include <algorithm>
#include <cmath>

namespace wisp {

StyleEffects LengthOperation::step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits)
{
    StyleEffects effects;
    if (!hasStyledHair(context))
        return effects;
    const Frame& frame = *context.frame;
    const BrushSettings& s = context.brush;
    for (const BrushRay& ray : brushRays(context, sample))
        for (const StrandPick& pick : strandsNearRay(
                 frame.strands, {}, ray.origin_ws, ray.direction_ws, s.radiusMetres, s.falloff, ray.maxDepthMetres)) {
            const std::uint64_t id = frame.groomShape->identities[pick.strand];
            const float now = strandLengthNow(context, edits, id, pick.strand);
            const float share = kStepShare * s.strength * pick.weight;
            const float length = std::clamp(
                now * (sample.inverted ? 1.0f - share : 1.0f + share), kStyleMinLengthMetres, kStyleMaxLengthMetres);
            if (std::abs(length - now) < 1e-5f)
                continue;
            StrandStyle& e = edits[id];
            e.lengthMetres = length;
            if (!e.shape.empty())
                e.shape = shapeWithLength(e.shape, length);
            effects.editsChanged = true;
        }
    return effects;
}

} // namespace wisp
