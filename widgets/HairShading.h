#pragma once
// The hair's samples shaded for a view on the CPU: the software path's half of the vertex shader
// (resources/shaders/hair_strand.glsl, strandSample and shadeHair, followed line for line). What a
// sample is whatever the view (its world position, tangent, colours, thickness and the key light
// reaching it through the deep opacity map) is captured from GL once per frame and shadow map
// (hair_sample_world.vert); a paused orbit then costs the view's part only, on the pool's threads,
// instead of the whole shader on llvmpipe's one vertex thread (measured: 330 ns a sample there).
// HairLowResTest.TheSoftwarePathShadesAndDrawsWhatGlDoes checks that both give the same samples.
//
// Pure C++ (no GL): tested without a context. Thread: any.

#include "widgets/HairSoftwareRaster.h"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <span>

namespace wisp {

class ThreadPool;

// hair_sample_world.vert's four outputs, interleaved.
struct HairWorldSample {
    glm::vec4 position; // xyz world metres, w: along the strand (0 root .. 1 tip)
    glm::vec4 derivative; // xyz world d position / d u, w: the key light reaching it (0..1)
    glm::vec4 root; // rgb linear root colour, wetness applied; a: ambient (0..1)
    glm::vec4 tip; // rgb linear tip colour; a: one hair's thickness at the root, metres (< 0: not drawn)
};

// The uniforms strandSample reads (HairRenderer::setStrandUniforms sets them for GL).
struct HairShadingView {
    glm::mat4 view{ 1.0f };
    glm::mat4 projection{ 1.0f };
    glm::vec2 viewportPixels{ 1.0f };
    bool ribbon = false; // camera-facing ribbons: halfExtent from the width; lines: 1
    float widthScale = 1.0f; // u_widthScale: a drawn strand stands for a lock
    float tipThicknessRatio = 1.0f;
    float minWidthPixels = 1.0f;
    float tipFade = 0.0f;
    bool shadows = false; // the deep opacity map's ambient term, not the guess along the strand
    glm::vec3 keyLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 fillLightView{ 0.0f, 0.0f, 1.0f };
    glm::vec3 headCentreView{ 0.0f };
};

// out[i] = sample i shaded for `view` (clip position, sRGB colour with the coverage in alpha,
// side.z half the drawn extent in pixels; side.xy is left zero: the software rasteriser needs no
// ribbon edges). `out` as long as `in`. `pool` may be null.
void shadeHairSamples(std::span<const HairWorldSample> in, const HairShadingView& view, std::span<HairRasterSample> out,
    ThreadPool* pool = nullptr);

} // namespace wisp
