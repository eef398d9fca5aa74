#pragma once
// Drawn density independent of simulated density: render-time children interpolated from the
// frame's strands, as Blender's Interpolate Curves does. Each child belongs to a parent strand
// and blends it with its two nearest neighbours (by root, same look, same point count, closer
// than kMaxNeighbourSpacings typical spacings, so no child bridges a parting or a region's edge)
// by fixed barycentric weights: point j of the child is w0 P0[j] + w1 P1[j] + w2 P2[j]. Its root
// lies in the triangle of the three roots, and it moves with them frame by frame.
//
// The interpolation (neighbours and weights) is rebuilt only when the strands' layout changes;
// each frame only blends points (about 3 multiply-adds per point and child).
//
// Pure C++ (no GL, no Qt): tested without a context. Thread: any (one object per thread).

#include "sim/geometry/HairCurves.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace wisp {

class HairChildren {
public:
    static constexpr float kMinDensity = 0.25f;
    static constexpr float kMaxDensity = 4.0f;
    static constexpr float kMaxNeighbourSpacings = 3.0f;

    // Children for `density` times as many drawn strands as `strands` has (none below 1): made
    // anew when the layout (offsets), the looks or the density differ from the last call.
    // Returns the number of children.
    std::size_t prepare(const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand, float density);
    // `strands` followed by the children (positions of this frame), with each child's look and
    // wetness its parent's. `strands` must have the layout prepare() was given.
    void interpolate(const HairCurves& strands, std::span<const std::uint16_t> lookOfStrand,
        std::span<const float> wetness, HairCurves& out, std::vector<std::uint16_t>& outLooks,
        std::vector<float>& outWetness) const;
    std::size_t childCount() const { return m_children.size(); }

private:
    struct Child {
        std::array<std::uint32_t, 3> strands{}; // parent first
        std::array<float, 3> weights{};
    };
    std::vector<Child> m_children;
    std::vector<std::uint32_t> m_offsets; // the layout the children were made for
    std::vector<std::uint16_t> m_looks;
    float m_density = 1.0f;
};

} // namespace wisp
