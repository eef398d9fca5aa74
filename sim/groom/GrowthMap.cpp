#include "sim/groom/GrowthMap.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wisp {

namespace {

float smoothstep(float edge0, float edge1, float x)
{
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Where the hairline lies (fractions of the nose-to-top height above the nose tip), and how far
// down the nose may be looked for below the top, in metres.
constexpr float kFrontHairline = 0.67f;
constexpr float kEarHairline = 0.45f;
constexpr float kNapeHairline = -0.10f;
constexpr float kEarDepth = 0.55f; // where the ear sits, as a fraction from the back to the nose
constexpr float kFade = 0.10f;
constexpr float kNoseSearchMetres = 0.30f;

} // namespace

std::vector<float> scalpGrowth(const TriangleMesh& head)
{
    std::vector<float> weights(head.vertexCount(), 0.0f);
    if (head.positions.empty())
        return weights;
    const Aabb box = boundsOf(head);
    const float top = box.max.y;
    const float width = std::max(box.size().x, 1e-9f);
    const float middle = box.center().x;

    // The nose tip: the front-most vertex near the middle, not far below the top.
    glm::vec3 nose(middle, top - 0.15f, box.max.z);
    float front = std::numeric_limits<float>::lowest();
    for (const glm::vec3& p : head.positions)
        if (p.y > top - kNoseSearchMetres && std::abs(p.x - middle) < 0.1f * width && p.z > front) {
            front = p.z;
            nose = p;
        }
    const float height = std::max(top - nose.y, 1e-6f);
    // The back of the skull: the rear-most vertex above the nose tip.
    float back = nose.z;
    for (const glm::vec3& p : head.positions)
        if (p.y > nose.y)
            back = std::min(back, p.z);
    const float depth = std::max(nose.z - back, 1e-6f);

    const std::vector<glm::vec3> normals = vertexNormals(head);
    for (std::size_t i = 0; i < weights.size(); ++i) {
        const glm::vec3& p = head.positions[i];
        const float s = std::clamp((p.z - back) / depth, 0.0f, 1.0f); // 0 at the back, 1 at the nose
        const float line = s < kEarDepth
            ? kNapeHairline + (kEarHairline - kNapeHairline) * (s / kEarDepth)
            : kEarHairline + (kFrontHairline - kEarHairline) * ((s - kEarDepth) / (1.0f - kEarDepth));
        const float lineY = nose.y + line * height;
        weights[i] = smoothstep(lineY, lineY + kFade * height, p.y) * smoothstep(-0.6f, -0.3f, normals[i].y);
    }
    return weights;
}

} // namespace wisp
