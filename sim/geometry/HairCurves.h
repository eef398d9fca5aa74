#pragma once
// Strands as flat arrays with offsets (as Blender's CurvesGeometry): strand i owns points
// offsets[i] .. offsets[i+1]-1. One array per attribute keeps the solver and the renderer
// streaming through memory instead of chasing per-strand allocations.

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace wisp {

struct HairCurves {
    std::vector<std::uint32_t> offsets{ 0 }; // strandCount() + 1 entries, offsets[0] == 0
    std::vector<glm::vec3> positions; // metres

    std::size_t strandCount() const { return offsets.empty() ? 0 : offsets.size() - 1; }
    std::size_t pointCount() const { return positions.size(); }
    std::uint32_t pointsIn(std::size_t strand) const { return offsets[strand + 1] - offsets[strand]; }

    std::span<const glm::vec3> strand(std::size_t i) const
    {
        return { positions.data() + offsets[i], positions.data() + offsets[i + 1] };
    }
    std::span<glm::vec3> strandForWrite(std::size_t i)
    {
        return { positions.data() + offsets[i], positions.data() + offsets[i + 1] };
    }

    // Appends a strand of `points` points (uninitialised positions) and returns its index.
    std::size_t addStrand(std::uint32_t points)
    {
        positions.resize(positions.size() + points);
        offsets.push_back(static_cast<std::uint32_t>(positions.size()));
        return offsets.size() - 2;
    }

    void clear()
    {
        offsets.assign(1, 0);
        positions.clear();
    }
};

// The same curves tagged with their space, so head-space curves cannot be stored where world-space
// ones belong (Blender names the space on every variable, `_wo`/`_cu`; here the type carries it).
// Both read as HairCurves anywhere (a function that works in any space takes HairCurves); going
// from plain or other-space curves to a tagged one is explicit, so it shows where it happens.
//
// World space: the head placed in the scene and moving with its motion (what the solver steps and
// the viewport draws).
struct WorldCurves : HairCurves {
    WorldCurves() = default;
    explicit WorldCurves(HairCurves curves)
        : HairCurves(std::move(curves))
    {
    }
    // The curves whatever their space, where one variable may hold either (a choice between the
    // rest pose and the moving frame); saying so is the point.
    const HairCurves& anySpace() const { return *this; }
};
// Head space: fixed to the head at rest, +Y up, metres (the groom, rest shapes, imported strands).
struct HeadCurves : HairCurves {
    HeadCurves() = default;
    explicit HeadCurves(HairCurves curves)
        : HairCurves(std::move(curves))
    {
    }
    const HairCurves& anySpace() const { return *this; }
};

// Polyline length of one strand, metres.
float strandLength(std::span<const glm::vec3> points);

} // namespace wisp
