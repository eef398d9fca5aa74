#include "sim/style/CombOperation.h"

#include "sim/style/StrandPicking.h"

#include <glm/geometric.hpp>

#include <map>

namespace wisp {

StyleEffects CombOperation::begin(const BrushContext& context, const BrushSample& sample, StyleEdits&)
{
    m_caught.clear();
    m_movedStrands = 0;
    m_last = sample;
    if (!hasStyledHair(context))
        return {};
    const Frame& frame = *context.frame;
    const GroomShape& shape = *frame.groomShape;
    const BrushSettings& s = context.brush;
    const std::vector<BrushRay> rays = brushRays(context, sample);
    std::map<std::uint32_t, std::size_t> caughtOf; // simulated strand -> its entry in m_caught
    for (std::size_t r = 0; r < rays.size(); ++r) {
        const BrushRay& ray = rays[r];
        for (const StrandPick& pick : strandsNearRay(
                 frame.strands, {}, ray.origin_ws, ray.direction_ws, s.radiusMetres, s.falloff, ray.maxDepthMetres)) {
            const std::uint32_t held = heldStrandOf(context, pick.strand);
            const float weight = pick.weight * (0.5f + 0.5f * s.strength);
            if (const auto found = caughtOf.find(held); found != caughtOf.end()) {
                Caught& c = m_caught[found->second];
                if (c.mirrored == (r == 1) && weight > c.weight) { // under both rings: the first one's
                    c.weight = weight;
                    c.depthMetres = pick.depth;
                }
                continue;
            }
            Caught c;
            c.identity = shape.identities[held];
            c.weight = weight;
            c.depthMetres = pick.depth;
            c.mirrored = r == 1;
            const auto points = frame.strands.strand(held);
            c.positions_ws.assign(points.begin(), points.end());
            for (std::size_t j = 1; j < points.size(); ++j)
                c.segmentLengthsMetres.push_back(glm::distance(points[j], points[j - 1]));
            caughtOf.emplace(held, m_caught.size());
            m_caught.push_back(std::move(c));
        }
    }
    // What the stroke moves: the caught strands and, through their key hairs, their wisps.
    for (std::uint32_t i = 0; i < shape.identities.size(); ++i)
        m_movedStrands += caughtOf.count(heldStrandOf(context, i)) ? 1 : 0;
    StyleEffects effects;
    if (m_caught.empty())
        return effects;
    effects.held.emplace();
    for (const Caught& c : m_caught)
        effects.held->push_back({ c.identity, c.positions_ws });
    return effects;
}

StyleEffects CombOperation::step(const BrushContext& context, const BrushSample& sample, StyleEdits&)
{
    const BrushSample previous = m_last;
    m_last = sample;
    if (m_caught.empty())
        return {};
    const std::vector<BrushRay> before = brushRays(context, previous);
    const std::vector<BrushRay> after = brushRays(context, sample);
    StyleEffects effects;
    effects.held.emplace();
    for (Caught& c : m_caught) {
        const std::size_t r = c.mirrored && before.size() > 1 && after.size() > 1 ? 1 : 0;
        // The point of the strand under the comb follows the cursor at the depth it was caught.
        const glm::vec3 delta_ws = (after[r].origin_ws + after[r].direction_ws * c.depthMetres)
            - (before[r].origin_ws + before[r].direction_ws * c.depthMetres);
        combStrand(c.positions_ws, c.segmentLengthsMetres, delta_ws, c.weight);
        effects.held->push_back({ c.identity, c.positions_ws });
    }
    return effects;
}

StyleEffects CombOperation::end(const BrushContext& context, StyleEdits& edits)
{
    // The combed shape becomes where the strands rest; the simulation solves the rest shape that
    // sags onto it, and lets go of them. Edits are head space: the head may have moved.
    StyleEffects effects;
    const glm::mat4 toHead = worldToHeadOf(context.frame);
    for (const Caught& c : m_caught) {
        std::vector<glm::vec3>& shape_hs = edits[c.identity].shape;
        shape_hs.clear();
        for (const glm::vec3& p_ws : c.positions_ws)
            shape_hs.push_back(glm::vec3(toHead * glm::vec4(p_ws, 1.0f)));
    }
    effects.editsChanged = true;
    effects.held.emplace();
    m_caught.clear();
    return effects;
}

std::optional<float> CombOperation::catchDepthMetres() const
{
    if (m_caught.empty())
        return std::nullopt;
    return m_caught.front().depthMetres;
}

} // namespace wisp
