#include "widgets/HairStripLayout.h"

#include <algorithm>

namespace wisp {
namespace {

// A fixed scramble of strand indices (an integer hash), so a prefix of the drawing order is spread
// evenly over the head whatever order the groom made its strands in (wisp after wisp).
std::uint32_t scramble(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

} // namespace

bool HairStripLayout::matches(std::span<const std::uint32_t> strandOffsets) const
{
    return std::ranges::equal(strandOffsets, offsets);
}

HairStripLayout buildHairStripLayout(std::span<const std::uint32_t> strandOffsets)
{
    using Layout = HairStripLayout;
    Layout layout;
    layout.offsets.assign(strandOffsets.begin(), strandOffsets.end());
    if (strandOffsets.size() < 2)
        return layout;

    // Which strands can be drawn, in scrambled order.
    std::vector<std::uint32_t> order;
    order.reserve(strandOffsets.size() - 1);
    std::size_t samples = 0;
    for (std::size_t s = 0; s + 1 < strandOffsets.size(); ++s) {
        // Offsets come from a frame that anyone may have built: refuse a decreasing pair instead
        // of reading wrapped-around indices.
        if (strandOffsets[s + 1] < strandOffsets[s])
            continue;
        const std::uint32_t points = strandOffsets[s + 1] - strandOffsets[s];
        if (points < 2 || points - 1 > Layout::kMaxSegments)
            continue;
        order.push_back(static_cast<std::uint32_t>(s));
        samples += (points - 1) * std::size_t{ Layout::kSamplesPerSegment } + 1;
    }
    std::ranges::sort(order, [](std::uint32_t a, std::uint32_t b) {
        const std::uint32_t ha = scramble(a), hb = scramble(b);
        return ha != hb ? ha < hb : a < b;
    });
    layout.drawnStrands = order.size();
    layout.strandOrder = order;
    layout.firstVertex.reserve(order.size());

    layout.vertices.reserve(2 * samples);
    for (std::size_t i = 0; i < Layout::kSampleSteps.size(); ++i) {
        const std::size_t perStep = samples / Layout::kSampleSteps[i] + 2 * order.size();
        layout.lines[i].indices.reserve(perStep);
        layout.ribbons[i].indices.reserve(2 * perStep);
        layout.lines[i].prefix.reserve(order.size() + 1);
        layout.ribbons[i].prefix.reserve(order.size() + 1);
    }
    for (const std::uint32_t s : order) {
        const std::uint32_t segments = strandOffsets[s + 1] - strandOffsets[s] - 1;
        const std::uint32_t segmentBits = segments << Layout::kSegmentBits;
        const auto first = static_cast<std::uint32_t>(layout.vertices.size());
        layout.firstVertex.push_back(first);
        for (std::uint32_t seg = 0; seg < segments; ++seg) {
            // The tip sample belongs to the last segment (sample == kSamplesPerSegment); elsewhere a
            // segment's end is the next one's start, so it is emitted once.
            const std::uint32_t samplesHere
                = seg + 1 == segments ? Layout::kSamplesPerSegment + 1 : Layout::kSamplesPerSegment;
            for (std::uint32_t k = 0; k < samplesHere; ++k) {
                const std::uint32_t bits = seg | segmentBits | k << Layout::kSampleShift;
                const std::uint32_t point = strandOffsets[s] + seg;
                layout.vertices.emplace_back(point, bits);
                layout.vertices.emplace_back(point, bits | Layout::kSideBit);
            }
        }
        // Sample j of this strand is vertices first + 2j (left) and first + 2j + 1 (right). The
        // last sample index is a multiple of every step, so every level of detail keeps the tip.
        const std::uint32_t lastSample = segments * Layout::kSamplesPerSegment;
        for (std::size_t i = 0; i < Layout::kSampleSteps.size(); ++i) {
            auto& line = layout.lines[i];
            auto& ribbon = layout.ribbons[i];
            for (std::uint32_t j = 0; j <= lastSample; j += Layout::kSampleSteps[i]) {
                line.indices.push_back(first + 2 * j);
                ribbon.indices.push_back(first + 2 * j);
                ribbon.indices.push_back(first + 2 * j + 1);
            }
            line.indices.push_back(Layout::kRestart);
            ribbon.indices.push_back(Layout::kRestart);
            line.prefix.push_back(static_cast<std::uint32_t>(line.indices.size()));
            ribbon.prefix.push_back(static_cast<std::uint32_t>(ribbon.indices.size()));
        }
    }
    return layout;
}

} // namespace wisp
