#include "sim/GrowthMap.h"

#include <algorithm>

namespace wisp {

namespace {
float smoothstep(float edge0, float edge1, float x)
{
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
}  // namespace

std::vector<float> upperHeadGrowth(const TriangleMesh& head)
{
    const Aabb box = boundsOf(head);
    const std::vector<glm::vec3> normals = vertexNormals(head);
    std::vector<float> weights(head.vertexCount());
    for (std::size_t i = 0; i < weights.size(); ++i) {
        const float height = (head.positions[i].y - box.min.y) / std::max(box.size().y, 1e-9f);
        weights[i] = smoothstep(0.55f, 0.65f, height) * smoothstep(-0.3f, 0.0f, normals[i].y);
    }
    return weights;
}

}  // namespace wisp
