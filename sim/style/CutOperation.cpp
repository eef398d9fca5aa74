#include "sim/style/CutOperation.h"

#include "sim/style/StrandPicking.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <map>
#include <set>

namespace wisp {

StyleEffects CutOperation::begin(const BrushContext&, const BrushSample& sample, StyleEdits&)
{
    m_last = sample;
    return {};
}

StyleEffects CutOperation::step(const BrushContext& context, const BrushSample& sample, StyleEdits& edits)
{
    const BrushSample previous = m_last;
    m_last = sample;
    if (!hasStyledHair(context))
        return {};
    const Frame& frame = *context.frame;
    const GroomShape& shape = *frame.groomShape;
    const std::vector<BrushRay> a = brushRays(context, previous);
    const std::vector<BrushRay> b = brushRays(context, sample);
    StyleEffects effects;
    const auto cutTo = [&](std::uint32_t strand, float lengthMetres) {
        const std::uint64_t id = shape.identities[strand];
        lengthMetres = std::max(lengthMetres, kStyleMinLengthMetres);
        if (lengthMetres >= strandLengthNow(context, edits, id, strand) - 1e-4f)
            return;
        StrandStyle& e = edits[id];
        e.lengthMetres = lengthMetres;
        if (!e.shape.empty())
            e.shape = shapeWithLength(e.shape, lengthMetres);
        effects.editsChanged = true;
    };
    for (std::size_t r = 0; r < a.size() && r < b.size(); ++r) {
        const glm::vec3 eye_ws = a[r].origin_ws;
        // The artist cuts what they see: a crossing behind the head (from this eye) is not cut. The
        // head is in head space: the line of sight is taken there.
        const glm::mat4 toHead = worldToHeadOf(context.frame);
        const glm::vec3 eye_hs = glm::vec3(toHead * glm::vec4(eye_ws, 1.0f));
        const auto visible = [&](const glm::vec3& x_ws) {
            if (!context.head)
                return true;
            const glm::vec3 toX_hs = glm::vec3(toHead * glm::vec4(x_ws, 1.0f)) - eye_hs;
            const float distance = glm::length(toX_hs);
            return !context.head->bvh().raycast(eye_hs, toX_hs / distance, distance - kSkinToleranceMetres).has_value();
        };
        std::map<std::uint32_t, float> keyLength; // wisp -> its cut key hair's new length
        std::set<std::uint32_t> cutNow;
        for (const StrandCut& cut :
            strandsCutBy(frame.strands, eye_ws, a[r].direction_ws, b[r].direction_ws, visible)) {
            // The cut's share of the strand as drawn, of its groomed length (a member's drawn length
            // differs a little from it; both blades of a mirrored stroke may cross it).
            const float drawn = strandLength(frame.strands.strand(cut.strand));
            const float share = drawn > 0.0f ? cut.lengthMetres / drawn : 1.0f;
            const float length = share * shape.lengths[cut.strand];
            cutTo(cut.strand, length);
            cutNow.insert(cut.strand);
            const std::uint32_t wisp = shape.wispOf[cut.strand];
            if (shape.keyOfWisp[wisp] == cut.strand)
                keyLength[wisp] = std::max(
                    std::min(length, keyLength.count(wisp) ? keyLength[wisp] : length), kStyleMinLengthMetres);
        }
        if (!keyLength.empty())
            for (std::uint32_t i = 0; i < shape.wispOf.size(); ++i)
                if (const auto found = keyLength.find(shape.wispOf[i]); found != keyLength.end() && !cutNow.count(i))
                    cutTo(i, found->second);
    }
    return effects;
}

} // namespace wisp
