#pragma once
// Welds corners at equal positions into one vertex: STL (whose triangles carry no indices) and
// glTF (which splits a vertex wherever its normal or texture coordinate changes) both need it.
// Positions are compared by their float bits after -0 is made +0, so equal coordinates are one
// vertex and the first position seen keeps its place in the vertex list.

#include "io/ReadFailure.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

namespace wisp::io::mesh {

class PositionWelder {
public:
    // The index in `positions` of the vertex at `p`, appended there the first time it is seen.
    std::uint32_t indexOf(glm::vec3 p, std::vector<glm::vec3>& positions)
    {
        p += 0.0f; // -0 + 0 is +0: one zero for the key
        Key key;
        std::memcpy(key.data(), &p.x, sizeof(float));
        std::memcpy(key.data() + 1, &p.y, sizeof(float));
        std::memcpy(key.data() + 2, &p.z, sizeof(float));
        const auto [it, added] = m_index.try_emplace(key, static_cast<std::uint32_t>(positions.size()));
        if (added) {
            if (positions.size() >= std::numeric_limits<std::uint32_t>::max())
                fail({}, "more vertices than 32-bit indices can number");
            positions.push_back(p);
        }
        return it->second;
    }

private:
    using Key = std::array<std::uint32_t, 3>; // the float bits of x, y, z
    struct KeyHash {
        std::size_t operator()(const Key& k) const
        {
            std::uint64_t h = 0x9E3779B97F4A7C15ull;
            for (std::uint32_t v : k)
                h = (h ^ v) * 0x100000001B3ull + (h >> 29);
            return static_cast<std::size_t>(h);
        }
    };
    std::unordered_map<Key, std::uint32_t, KeyHash> m_index;
};

} // namespace wisp::io::mesh
