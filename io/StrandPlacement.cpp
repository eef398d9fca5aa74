#include "io/StrandPlacement.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace wisp::io {

namespace {

// The widest span of a scalp's roots, in metres (from the minimum up to but not including the
// maximum): a full groom's roots span about 0.15 m across and 0.2 m front to back.
constexpr double kRootsMinSpanMetres = 0.10;
constexpr double kRootsMaxSpanMetres = 0.30;

std::string number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

} // namespace

StrandPlacement placeStrands(HairCurves& strands, const HeadPlacement* head, float explicitScale)
{
    StrandPlacement placed;
    if (explicitScale > 0.0f && std::isfinite(explicitScale)) {
        placed.scale = explicitScale;
        placed.unit = LengthUnit::Auto;
        for (glm::vec3& p : strands.positions)
            p *= explicitScale;
        placed.description = "strands scaled by the chosen \u00D7" + number(explicitScale);
        return placed;
    }
    if (head) {
        applyPlacement(std::span<glm::vec3>(strands.positions), *head);
        placed.scale = head->scale;
        placed.unit = head->unit;
        placed.followedHead = true;
        placed.description = "strands placed with their head (" + describePlacement(*head) + ")";
        return placed;
    }

    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        if (strands.pointsIn(s) > 0) {
            lo = glm::min(lo, strands.positions[strands.offsets[s]]);
            hi = glm::max(hi, strands.positions[strands.offsets[s]]);
        }
    const glm::vec3 size = hi - lo;
    const double span = lo.x <= hi.x ? double(std::max({ size.x, size.y, size.z })) : 0.0;
    for (LengthUnit unit : { LengthUnit::Millimetres, LengthUnit::Centimetres, LengthUnit::Metres }) {
        const double metres = span
            * (unit == LengthUnit::Millimetres        ? 0.001
                    : unit == LengthUnit::Centimetres ? 0.01
                                                      : 1.0);
        if (metres >= kRootsMinSpanMetres && metres < kRootsMaxSpanMetres) {
            placed.unit = unit;
            placed.scale = metresPerUnit(unit);
            for (glm::vec3& p : strands.positions)
                p *= placed.scale;
            placed.description = "strands in " + std::string(unitName(unit)) + " (their roots span " + number(span)
                + " units), \u00D7" + number(placed.scale);
            return placed;
        }
    }
    placed.unit = LengthUnit::Auto;
    placed.description = "strands left as stored";
    placed.note = "the roots span " + number(span) + " units, which is no scalp (" + number(kRootsMinSpanMetres)
        + " m to under " + number(kRootsMaxSpanMetres)
        + " m) in millimetres, centimetres or metres; left as stored (give a scale if they are not metres)";
    return placed;
}

} // namespace wisp::io
