#include "widgets/ScreenRect.h"

#include <glm/common.hpp>

#include <cmath>
#include <limits>

namespace wisp {

ClipRect widenClipRect(ClipRect rect, glm::vec2 viewportPixels, float pixels)
{
    if (clipRectEmpty(rect))
        return rect;
    // Clip space spans 2 units over the viewport.
    const glm::vec2 margin = 2.0f * glm::max(pixels, 0.0f) / glm::max(viewportPixels, glm::vec2(1.0f));
    return glm::clamp(ClipRect(rect.x - margin.x, rect.y - margin.y, rect.z + margin.x, rect.w + margin.y),
        kWholeViewport.x, kWholeViewport.z);
}

ClipRect clipRectOfBox(const Aabb& box, const glm::mat4& viewProjection, glm::vec2 viewportPixels, float marginPixels)
{
    glm::vec2 low(std::numeric_limits<float>::max());
    glm::vec2 high(-std::numeric_limits<float>::max());
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) != 0 ? box.max.x : box.min.x, (corner & 2) != 0 ? box.max.y : box.min.y,
            (corner & 4) != 0 ? box.max.z : box.min.z);
        const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
        // Near the camera's plane a corner's projection runs off to infinity (and flips sign
        // behind it): nothing tighter than the whole viewport is sure to hold the box then.
        if (!(clip.w > 1e-4f) || !std::isfinite(clip.x) || !std::isfinite(clip.y))
            return kWholeViewport;
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        low = glm::min(low, ndc);
        high = glm::max(high, ndc);
    }
    // Wholly outside: an empty rectangle (the clamp below would make a sliver of the edge).
    if (high.x < -1.0f || high.y < -1.0f || low.x > 1.0f || low.y > 1.0f)
        return ClipRect(0.0f);
    return widenClipRect(
        glm::clamp(ClipRect(low, high), kWholeViewport.x, kWholeViewport.z), viewportPixels, marginPixels);
}

} // namespace wisp
