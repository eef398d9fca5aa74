#pragma once
// The static half of the hair's vertex data: which spline sample each vertex is. It depends only on
// the strands' layout (their point counts), so it is built once per groom and reused for every
// frame, while the points themselves stream in each frame (see HairRenderer).
//
// Every strand gets two vertices (left and right edge) per Catmull-Rom sample, kSamplesPerSegment
// samples per segment plus the tip. Index lists then pick what to draw:
//  - ribbons: a camera-facing triangle strip through both edges of each sample;
//  - lines: a line strip through the left vertices. Where strands are at most a pixel wide, a
//    ribbon and a line cover the same pixels, and a line is half the primitives;
// each at three levels of detail along the strand: every sample, every second, every fourth (the
// segment ends only, 4 / 2 / 1 samples per segment). Strips end with a restart index.
//
// Strands are listed in a scrambled order, so the first k strands are an even sample of the whole
// head: drawing a prefix is a level of detail across the strands (see HairDetail).
//
// Pure C++ (no GL): tested without a context. Thread: any.

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace wisp {

struct HairStripLayout {
    static constexpr std::uint32_t kSamplesPerSegment = 4;
    // Packing of a vertex's second word (must match resources/shaders/hair.vert).
    static constexpr std::uint32_t kSegmentBits = 12; // segment index within its strand
    static constexpr std::uint32_t kMaxSegments = (1u << kSegmentBits) - 1; // longer strands are not drawn
    static constexpr std::uint32_t kSampleShift = 24; // sample within the segment, 0..kSamplesPerSegment
    static constexpr std::uint32_t kSideBit = 1u << 31; // set: the ribbon's right edge
    static constexpr std::uint32_t kRestart = 0xFFFFFFFFu; // ends a strip

    enum class Primitive { Lines, Ribbons };
    static constexpr std::array<std::uint32_t, 3> kSampleSteps{ 1, 2, 4 }; // every n-th sample

    struct IndexList {
        std::vector<std::uint32_t> indices;
        // Drawing the first k strands takes prefix[k] indices; k = 0 .. drawnStrands.
        std::vector<std::uint32_t> prefix{ 0 };
    };

    // Per vertex: x = index (into the frame's point array) of the first point of the segment the
    // sample lies on; y = segment | segmentCount << 12 | sample << 24 | side << 31.
    std::vector<glm::uvec2> vertices;
    std::array<IndexList, 3> lines; // by step: kSampleSteps[i]
    std::array<IndexList, 3> ribbons; // by step
    std::vector<std::uint32_t> offsets{ 0 }; // the strand layout this was built for
    std::size_t drawnStrands = 0; // strands with at least one segment and at most kMaxSegments
    // Per drawn strand, in drawing order: its index in `offsets`, and its first vertex (sample j of
    // the strand is vertices[firstVertex + 2 j], its point k's sample is j = k kSamplesPerSegment).
    std::vector<std::uint32_t> strandOrder;
    std::vector<std::uint32_t> firstVertex;

    const IndexList& indices(Primitive primitive, std::size_t stepIndex) const
    {
        return primitive == Primitive::Lines ? lines[stepIndex] : ribbons[stepIndex];
    }
    bool matches(std::span<const std::uint32_t> strandOffsets) const;
};

// Strands with fewer than two points, or with decreasing offsets, get no vertices.
HairStripLayout buildHairStripLayout(std::span<const std::uint32_t> strandOffsets);

} // namespace wisp
