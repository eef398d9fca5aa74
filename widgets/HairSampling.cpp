#include "widgets/HairSampling.h"

#include "widgets/HairStripLayout.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace wisp {

float typicalTurnRadians(const HairCurves& strands, std::size_t maxStrands)
{
    const std::size_t count = strands.strandCount();
    if (count == 0 || maxStrands == 0)
        return 0.0f;
    std::vector<float> turns;
    const std::size_t stride = std::max<std::size_t>(1, count / maxStrands);
    for (std::size_t s = 0; s < count; s += stride) {
        const std::uint32_t begin = strands.offsets[s];
        const std::uint32_t end = strands.offsets[s + 1];
        if (end < begin + 3 || end > strands.positions.size()) // too short, or offsets nobody should trust
            continue;
        for (std::uint32_t i = begin; i + 2 < end; ++i) {
            const glm::vec3 a = strands.positions[i + 1] - strands.positions[i];
            const glm::vec3 b = strands.positions[i + 2] - strands.positions[i + 1];
            const float lengths = glm::length(a) * glm::length(b);
            if (!(lengths > 0.0f) || !std::isfinite(lengths))
                continue;
            turns.push_back(std::acos(std::clamp(glm::dot(a, b) / lengths, -1.0f, 1.0f)));
        }
    }
    if (turns.empty())
        return 0.0f;
    const auto at = turns.begin() + static_cast<std::ptrdiff_t>(9 * (turns.size() - 1) / 10);
    std::nth_element(turns.begin(), at, turns.end());
    return *at;
}

std::size_t sampleStepIndex(float segmentPixels, float turnRadians, float maxDeviationPixels)
{
    const float bow = std::max(segmentPixels, 0.0f) * std::max(turnRadians, 0.0f) / 8.0f; // one chord a segment
    const float allowed = std::max(maxDeviationPixels, 1e-3f);
    // kSampleSteps {1, 2, 4} of kSamplesPerSegment (4): 4, 2 and 1 samples a segment.
    for (std::size_t i = HairStripLayout::kSampleSteps.size(); i-- > 1;) {
        const float samples
            = static_cast<float>(HairStripLayout::kSamplesPerSegment / HairStripLayout::kSampleSteps[i]);
        if (bow / (samples * samples) <= allowed)
            return i;
    }
    return 0; // NaN lands here too: every sample
}

} // namespace wisp
