#include "widgets/HairLineDecimation.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>

namespace wisp {

static_assert(HairStripLayout::kSampleSteps[kOneSampleStep] == HairStripLayout::kSamplesPerSegment,
    "kOneSampleStep is one sample a segment");

std::vector<float> chordDeviations(const HairCurves& strands)
{
    constexpr float kKeep = std::numeric_limits<float>::infinity();
    std::vector<float> out(strands.positions.size(), kKeep);
    const glm::vec3* p = strands.positions.data();
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t begin = strands.offsets[s], end = strands.offsets[s + 1];
        if (end > strands.positions.size() || end < begin + 3)
            continue;
        for (std::uint32_t i = begin + 1; i + 1 < end; ++i) {
            // |(b - a) x (q - a)| / |b - a|: the point's distance from the line through the chord
            // (within the chord for the gentle bends that come near the tolerance).
            const glm::vec3 sum = p[i - 1] + p[i] + p[i + 1];
            if (!std::isfinite(sum.x) || !std::isfinite(sum.y) || !std::isfinite(sum.z))
                continue; // a non-finite point, or one next to it: kept
            const glm::vec3 chord = p[i + 1] - p[i - 1];
            const float chordLength2 = glm::dot(chord, chord);
            const glm::vec3 across = glm::cross(chord, p[i] - p[i - 1]);
            const float deviation = chordLength2 > 0.0f ? std::sqrt(glm::dot(across, across) / chordLength2)
                                                        : glm::length(p[i] - p[i - 1]);
            out[i] = std::isfinite(deviation) ? deviation : kKeep;
        }
    }
    return out;
}

HairStripLayout::IndexList decimatedLines(
    const HairStripLayout& layout, std::span<const float> deviations, float toleranceMetres)
{
    HairStripLayout::IndexList out;
    const bool usable = deviations.size() >= (layout.offsets.empty() ? 0 : layout.offsets.back())
        && layout.firstVertex.size() == layout.strandOrder.size();
    const float tolerance = usable && std::isfinite(toleranceMetres) ? toleranceMetres : -1.0f;
    const std::uint32_t samplesPer = HairStripLayout::kSamplesPerSegment;
    out.indices.reserve(layout.lines[kOneSampleStep].indices.size());
    out.prefix.reserve(layout.strandOrder.size() + 1);
    for (std::size_t d = 0; d < layout.strandOrder.size(); ++d) {
        const std::uint32_t s = layout.strandOrder[d];
        const std::uint32_t begin = layout.offsets[s], points = layout.offsets[s + 1] - begin;
        const std::uint32_t first = layout.firstVertex[d];
        bool previousKept = true;
        for (std::uint32_t k = 0; k < points; ++k) {
            const bool end = k == 0 || k + 1 == points;
            if (!end && previousKept && deviations.size() > begin + k && deviations[begin + k] <= tolerance) {
                previousKept = false;
                continue;
            }
            out.indices.push_back(first + 2 * k * samplesPer);
            previousKept = true;
        }
        out.indices.push_back(HairStripLayout::kRestart);
        out.prefix.push_back(static_cast<std::uint32_t>(out.indices.size()));
    }
    return out;
}

} // namespace wisp
