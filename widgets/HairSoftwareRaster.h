#pragma once
// The hair's strands drawn by our own code on the CPU, into the half-resolution target, while the
// camera or the hair moves on a software OpenGL (Mesa's llvmpipe). Why: llvmpipe draws a thin line
// as a triangle of its own, set up and binned on the GUI thread, then shaded in 4x4-pixel blocks of
// which a one-pixel line covers one or two pixels; a paused orbit at 4x display density spent
// 230 ms a paint there (README, "The hair's look"). Here a segment costs what its pixels cost, and
// the strands are split across the threads of a pool.
//
// The same picture as the GL path (HairRenderer::draw with hair.frag): the samples are the ones the
// vertex shader makes (captured by transform feedback: clip position, sRGB colour with the
// coverage in alpha, half the drawn extent in pixels), a pixel at distance d from the strand's
// centre line gets clamp(halfExtent - d, 0, 1) of it (the analytic coverage of hair.frag; lines
// have halfExtent 1, a one-pixel box), the backdrop's depth hides what is behind it, and strands
// are laid premultiplied "over" in drawing order. Each thread draws a run of strands into its own
// buffer; "over" is associative, so the runs laid over one another in order give the same image.
// Differences: colours are summed in float and rounded once (the GL target rounds every blend to
// 8 bits), and colour and depth are interpolated linearly on screen (GL interpolates the colour
// perspective-correctly; on segments a few pixels long the two agree to rounding).
//
// Rasterisation: a segment walks its major axis one pixel centre at a time, over [min, max) of its
// ends' coordinates on that axis, so a strand's consecutive segments meet without a gap or a pixel
// drawn twice; across, every pixel whose centre lies within halfExtent of the centre line.
//
// Pure C++ (no GL): tested without a context. Thread: the caller's, with the pool's workers.

#include <glm/vec4.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace wisp {

class ThreadPool;

// One captured sample (hair_samples.vert's three outputs, interleaved).
struct HairRasterSample {
    glm::vec4 clip; // clip-space position of the centre line
    glm::vec4 colour; // sRGB, alpha: coverage (0..1)
    glm::vec4 side; // z: half the drawn extent across the strand, pixels (its antialiasing skirt included)
};

// Pixels [x0, x1) x [y0, y1) of the target, y up (GL's window coordinates).
struct PixelRect {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
    int width() const { return x1 > x0 ? x1 - x0 : 0; }
    int height() const { return y1 > y0 ? y1 - y0 : 0; }
};

struct HairRasterInput {
    std::span<const HairRasterSample> samples; // every drawn strand's samples, in drawing order
    std::span<const std::uint32_t> strandEnds; // per strand, one past its last sample (ascending)
    int width = 0; // the target, pixels
    int height = 0;
    PixelRect region; // only pixels inside are drawn (and output)
    // The backdrop's window depth (0..1) per pixel of the region, region.width() * region.height(),
    // rows bottom up (what glReadPixels gives); a fragment is drawn where its depth is less. Empty:
    // nothing hides the hair.
    std::span<const float> depth;
};

class HairSoftwareRaster {
public:
    // Draws input and returns the target's pixels inside input.region, premultiplied RGBA8, rows
    // bottom up, region.width() pixels a row (what glTexSubImage2D takes). `pool` may be null (the
    // calling thread alone). The returned span lives until the next draw.
    std::span<const std::uint8_t> draw(const HairRasterInput& input, ThreadPool* pool);

    std::size_t lastSegments() const { return m_lastSegments; } // drawn segments, after clipping

private:
    std::vector<std::vector<float>> m_runs; // per run of strands: the region's premultiplied RGBA
    std::vector<std::uint8_t> m_rgba;
    std::size_t m_lastSegments = 0;
};

// The pixels whose centres lie inside a clip-space rectangle (x0, y0, x1, y1) of a target
// width x height big: the ones a GL pass over that rectangle covers.
PixelRect pixelRectOfClipRect(const glm::vec4& clipRect, int width, int height);

} // namespace wisp
