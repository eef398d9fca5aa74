#pragma once
// The deep opacity map's two hair passes (HairShadowMap.h) drawn on the CPU, for a software OpenGL:
// on llvmpipe the strands' ~70,000 one-texel lines, drawn twice, were most of the shadow map's
// 45-60 ms, which a simulating view pays every third paint. The head's pass stays in GL (triangles);
// its result is read back, the hair is added here, and both maps are handed back to GL.
//
// The same rules as the GL passes (resources/shaders/shadow_hair.*): each strand is a line strip
// through its points, one texel wide (one texel a column of its major axis, over the texel centres
// in [min, max) of its ends, the texel the line passes through there); its depth from the light is
// interpolated linearly (the light's projection is orthographic). Pass 1 keeps the nearest depth
// per texel (min: order does not matter); pass 2 adds the strand's opacity to every layer whose far
// end lies behind the fragment, measured from pass 1's nearest depth (a sum: order does not matter
// either, so threads split the strands and their sums are added).
//
// Pure C++ (no GL): tested without a context. Thread: the caller's, with the pool's workers.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace wisp {

class ThreadPool;

struct ShadowRasterInput {
    std::span<const glm::vec4> points; // xyz world metres; w < 0.5: the strand is not drawn
    std::span<const std::uint32_t> strandOffsets; // strand s: points [offsets[s], offsets[s + 1])
    glm::mat4 lightViewProjection{ 1.0f }; // world -> clip (orthographic)
    glm::mat4 worldToShadow{ 1.0f }; // world -> (u, v, metres from the light)
    int pixels = 0; // the maps are pixels x pixels
    glm::vec4 layerMetres{ 0.0f }; // where the four layers end, behind the nearest depth
    float strandOpacity = 0.0f; // what one strand crossing a texel adds to a layer
};

// `depth`: pixels^2 texels, rows bottom up, as the head's pass left them (r: nearest head, g:
// nearest head); r is lowered to the nearest hair. `opacity`: pixels^2 texels, set to the four
// layers' opacity. Wrong-sized maps are left alone.
void drawShadowHair(
    const ShadowRasterInput& input, std::vector<glm::vec2>& depth, std::vector<glm::vec4>& opacity, ThreadPool* pool);

} // namespace wisp
