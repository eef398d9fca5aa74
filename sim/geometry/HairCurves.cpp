#include "sim/geometry/HairCurves.h"

#include <glm/geometric.hpp>

namespace wisp {

float strandLength(std::span<const glm::vec3> points)
{
    float length = 0.0f;
    for (std::size_t i = 1; i < points.size(); ++i)
        length += glm::distance(points[i - 1], points[i]);
    return length;
}

} // namespace wisp
