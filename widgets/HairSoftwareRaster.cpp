#include "widgets/HairSoftwareRaster.h"

#include "sim/util/ThreadPool.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace wisp {
namespace {

// Four floats in one register (GCC's and Clang's vector extension): a premultiplied RGBA colour.
using Rgba = float __attribute__((vector_size(16)));

// A sample on the target: pixels (x, y), window depth z, half extent h, premultiplied colour c.
struct ScreenSample {
    float x, y, z, h;
    Rgba c;
};

bool finite(const glm::vec4& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

HairRasterSample mixSamples(const HairRasterSample& a, const HairRasterSample& b, float t)
{
    return { a.clip + t * (b.clip - a.clip), a.colour + t * (b.colour - a.colour), a.side + t * (b.side - a.side) };
}

ScreenSample onScreen(const HairRasterSample& s, float width, float height)
{
    const float inverseW = 1.0f / s.clip.w;
    // Premultiplied here, so a pixel's share is one multiplication (linear on screen either way).
    const float a = s.colour.w;
    return { (s.clip.x * inverseW * 0.5f + 0.5f) * width, (s.clip.y * inverseW * 0.5f + 0.5f) * height,
        s.clip.z * inverseW * 0.5f + 0.5f, s.side.z, Rgba{ s.colour.x * a, s.colour.y * a, s.colour.z * a, a } };
}

// Everything one run of strands draws into: its own premultiplied RGBA over the region.
struct RunTarget {
    Rgba* pixels; // region.width() * region.height(), rows bottom up
    const float* depth; // the backdrop's, as many; null: none
    const HairRasterInput* input;
    int x0, y0, rowPixels; // the region's corner and width
    std::size_t segments = 0;
};

// One fragment: coverage `cover` of premultiplied colour c at window depth z, "over".
inline void blend(RunTarget& target, int column, int row, float z, Rgba c, float cover)
{
    const std::size_t pixel = static_cast<std::size_t>(row - target.y0) * target.rowPixels + (column - target.x0);
    if (target.depth && !(z < target.depth[pixel]))
        return;
    Rgba source = c * cover;
    if (source[3] > 1.0f) // a slanted opaque line's share (up to sqrt 2 of its coverage): opaque
        source /= source[3];
    Rgba& p = target.pixels[pixel];
    p = source + p * (1.0f - source[3]);
}

inline int floorToInt(float x)
{
    const int i = static_cast<int>(x);
    return i - (static_cast<float>(i) > x ? 1 : 0);
}

inline int ceilToInt(float x)
{
    const int i = static_cast<int>(x);
    return i + (static_cast<float>(i) < x ? 1 : 0);
}

// A segment whose major axis is x (swapped: y, with the roles of x and y exchanged). Walks the pixel
// centres of that axis in [min, max) of the ends, stepping the centre line, depth, width and colour
// one pixel at a time; across, the pixels within h of the centre line measured perpendicular to it
// (hair.frag's distance), so a slanted strand is as wide as a level one. A line (h = 1 at both
// ends: a one-pixel box) covers the two pixels across whose centres straddle it, 1 - f and f of its
// coverage (f: how far past the first centre it runs), over the cosine of its slant: what the tent
// clamp(1 - d, 0, 1) leaves summed across, on two pixels where the tent would touch three (a thin
// hair's coverage is far below 1, so a share of up to sqrt 2 of it stays under 1).
template <bool kSwapped> void drawSegment(RunTarget& target, const ScreenSample& a, const ScreenSample& b)
{
    const PixelRect& region = target.input->region;
    const float au = kSwapped ? a.y : a.x;
    const float av = kSwapped ? a.x : a.y;
    const float du = (kSwapped ? b.y : b.x) - au;
    const float dv = (kSwapped ? b.x : b.y) - av;
    const int uLow = kSwapped ? region.y0 : region.x0;
    const int uHigh = kSwapped ? region.y1 : region.x1;
    const int vLow = kSwapped ? region.x0 : region.y0;
    const int vHigh = kSwapped ? region.x1 : region.y1;
    // Within a pixel of the region (so far-off ends convert to int safely).
    const float uMin = std::max(std::min(au, au + du), static_cast<float>(uLow) - 1.0f);
    const float uMax = std::min(std::max(au, au + du), static_cast<float>(uHigh) + 1.0f);
    // Pixel centres u + 0.5 in [uMin, uMax).
    const int begin = std::max(ceilToInt(uMin - 0.5f), uLow);
    const int end = std::min(ceilToInt(uMax - 0.5f), uHigh);
    if (begin >= end)
        return;
    const float length = std::sqrt(du * du + dv * dv);
    const float cosine = std::abs(du) / length; // of the angle to the major axis, >= 1/sqrt(2)
    const float inverseDu = 1.0f / du;
    // Everything at the first pixel centre, then its change per pixel.
    const float t0 = (static_cast<float>(begin) + 0.5f - au) * inverseDu;
    const float vStep = dv * inverseDu;
    const float zStep = (b.z - a.z) * inverseDu;
    const float hStep = (b.h - a.h) * inverseDu;
    const Rgba cStep = (b.c - a.c) * inverseDu;
    float v = av + t0 * dv;
    float z = a.z + t0 * (b.z - a.z);
    float h = a.h + t0 * (b.h - a.h);
    Rgba c = a.c + t0 * (b.c - a.c);
    ++target.segments;
    if (a.h == 1.0f && b.h == 1.0f) {
        const float perColumn = 1.0f / cosine;
        for (int u = begin; u < end; ++u, v += vStep, z += zStep, c += cStep) {
            const float below = v - 0.5f; // the centre line, in pixel centres
            if (!(below > static_cast<float>(vLow) - 2.0f && below < static_cast<float>(vHigh) + 1.0f))
                continue; // also keeps the conversion to int in range
            const int w = floorToInt(below);
            const float f = below - static_cast<float>(w);
            if (w >= vLow && w < vHigh) {
                if constexpr (kSwapped)
                    blend(target, w, u, z, c, (1.0f - f) * perColumn);
                else
                    blend(target, u, w, z, c, (1.0f - f) * perColumn);
            }
            if (w + 1 >= vLow && w + 1 < vHigh) {
                if constexpr (kSwapped)
                    blend(target, w + 1, u, z, c, f * perColumn);
                else
                    blend(target, u, w + 1, z, c, f * perColumn);
            }
        }
        return;
    }
    for (int u = begin; u < end; ++u, v += vStep, z += zStep, h += hStep, c += cStep) {
        if (!(h > 0.0f))
            continue;
        const float reach = h / cosine;
        if (!(v + reach > static_cast<float>(vLow) && v - reach < static_cast<float>(vHigh)))
            continue; // also keeps the conversions to int in range
        const int vBegin = ceilToInt(std::max(v - reach - 0.5f, static_cast<float>(vLow)));
        const int vEnd = floorToInt(std::min(v + reach - 0.5f, static_cast<float>(vHigh) - 0.5f)) + 1;
        for (int w = vBegin; w < vEnd; ++w) {
            const float distance = std::abs(static_cast<float>(w) + 0.5f - v) * cosine;
            const float cover = std::min(h - distance, 1.0f);
            if (cover <= 0.0f)
                continue;
            if constexpr (kSwapped)
                blend(target, w, u, z, c, cover);
            else
                blend(target, u, w, z, c, cover);
        }
    }
}

void drawStrandSegment(RunTarget& target, HairRasterSample a, HairRasterSample b, float width, float height)
{
    if (!finite(a.clip) || !finite(b.clip) || !finite(a.colour) || !finite(b.colour) || !std::isfinite(a.side.z)
        || !std::isfinite(b.side.z))
        return;
    // Clipped to the near plane (z >= -w), as GL clips it.
    const float da = a.clip.z + a.clip.w;
    const float db = b.clip.z + b.clip.w;
    if (da < 0.0f && db < 0.0f)
        return;
    if (da < 0.0f)
        a = mixSamples(a, b, da / (da - db));
    else if (db < 0.0f)
        b = mixSamples(a, b, da / (da - db));
    if (!(a.clip.w > 0.0f) || !(b.clip.w > 0.0f))
        return;
    const ScreenSample sa = onScreen(a, width, height);
    const ScreenSample sb = onScreen(b, width, height);
    // Wholly outside the region (far off screen too: a non-finite strand's samples lie there).
    const PixelRect& region = target.input->region;
    const float reach = std::max(sa.h, sb.h) + 1.0f;
    if (std::max(sa.x, sb.x) + reach < static_cast<float>(region.x0)
        || std::min(sa.x, sb.x) - reach > static_cast<float>(region.x1)
        || std::max(sa.y, sb.y) + reach < static_cast<float>(region.y0)
        || std::min(sa.y, sb.y) - reach > static_cast<float>(region.y1))
        return;
    if (!std::isfinite(sa.x) || !std::isfinite(sa.y) || !std::isfinite(sb.x) || !std::isfinite(sb.y))
        return;
    if (std::abs(sb.x - sa.x) >= std::abs(sb.y - sa.y))
        drawSegment<false>(target, sa, sb);
    else
        drawSegment<true>(target, sa, sb);
}

} // namespace

PixelRect pixelRectOfClipRect(const glm::vec4& clipRect, int width, int height)
{
    // Pixel centres c + 0.5 inside [X0, X1): c in [ceil(X0 - 0.5), ceil(X1 - 0.5)).
    const auto edge = [](float clip, int pixels) {
        const float at = std::ceil((clip * 0.5f + 0.5f) * static_cast<float>(pixels) - 0.5f);
        return static_cast<int>(std::clamp(std::isfinite(at) ? at : 0.0f, 0.0f, static_cast<float>(pixels)));
    };
    PixelRect rect{ edge(clipRect.x, width), edge(clipRect.y, height), edge(clipRect.z, width),
        edge(clipRect.w, height) };
    if (rect.x1 < rect.x0)
        rect.x1 = rect.x0;
    if (rect.y1 < rect.y0)
        rect.y1 = rect.y0;
    return rect;
}

std::span<const std::uint8_t> HairSoftwareRaster::draw(const HairRasterInput& input, ThreadPool* pool)
{
    HairRasterInput in = input;
    in.region.x0 = std::clamp(in.region.x0, 0, std::max(in.width, 0));
    in.region.x1 = std::clamp(in.region.x1, in.region.x0, std::max(in.width, 0));
    in.region.y0 = std::clamp(in.region.y0, 0, std::max(in.height, 0));
    in.region.y1 = std::clamp(in.region.y1, in.region.y0, std::max(in.height, 0));
    const std::size_t pixels = static_cast<std::size_t>(in.region.width()) * in.region.height();
    if (in.depth.size() != pixels)
        in.depth = {}; // not this region's: nothing hides the hair rather than the wrong thing
    m_rgba.assign(4 * pixels, 0);
    m_lastSegments = 0;
    if (pixels == 0)
        return m_rgba;

    // Runs of consecutive strands with about the same number of samples, one per thread.
    const std::size_t strands = in.strandEnds.size();
    const std::size_t samples = strands > 0 ? std::min<std::size_t>(in.strandEnds.back(), in.samples.size()) : 0;
    const std::size_t runCount
        = std::clamp<std::size_t>(pool ? pool->threadCount() : 1, 1, std::max<std::size_t>(strands, 1));
    std::vector<std::size_t> runStart(runCount + 1, strands);
    runStart[0] = 0;
    for (std::size_t r = 1; r < runCount; ++r) {
        const std::size_t wanted = samples * r / runCount;
        runStart[r] = static_cast<std::size_t>(
            std::upper_bound(in.strandEnds.begin(), in.strandEnds.end(), static_cast<std::uint32_t>(wanted))
            - in.strandEnds.begin());
        runStart[r] = std::max(runStart[r], runStart[r - 1]);
    }
    m_runs.resize(runCount);
    std::vector<std::size_t> runSegments(runCount, 0);
    std::vector<const float*> runPixels(runCount, nullptr);
    const float width = static_cast<float>(in.width);
    const float height = static_cast<float>(in.height);
    const auto drawRun = [&](std::size_t run) {
        std::vector<float>& buffer = m_runs[run];
        buffer.assign(4 * pixels + 4, 0.0f);
        // Aligned by hand to the 16 bytes a vector of four floats wants.
        auto* aligned = reinterpret_cast<Rgba*>(
            (reinterpret_cast<std::uintptr_t>(buffer.data()) + 15) & ~static_cast<std::uintptr_t>(15));
        RunTarget target{ aligned, in.depth.empty() ? nullptr : in.depth.data(), &in, in.region.x0, in.region.y0,
            in.region.width() };
        runPixels[run] = reinterpret_cast<const float*>(aligned);
        for (std::size_t s = runStart[run]; s < runStart[run + 1]; ++s) {
            const std::size_t begin = s > 0 ? in.strandEnds[s - 1] : 0;
            const std::size_t end = std::min<std::size_t>(in.strandEnds[s], samples);
            for (std::size_t i = begin; i + 1 < end; ++i)
                drawStrandSegment(target, in.samples[i], in.samples[i + 1], width, height);
        }
        runSegments[run] = target.segments;
    };
    const auto body = [&](std::size_t first, std::size_t last) {
        for (std::size_t run = first; run < last; ++run)
            drawRun(run);
    };
    forRange(pool, runCount, 1, body);
    for (const std::size_t n : runSegments)
        m_lastSegments += n;

    // Later runs over earlier ones, rounded once to 8 bits.
    const auto merge = [&](std::size_t firstRow, std::size_t lastRow) {
        const std::size_t rowFloats = 4 * static_cast<std::size_t>(in.region.width());
        for (std::size_t i = firstRow * rowFloats; i < lastRow * rowFloats; i += 4) {
            float r = runPixels[0][i], g = runPixels[0][i + 1], b = runPixels[0][i + 2], a = runPixels[0][i + 3];
            for (std::size_t run = 1; run < runCount; ++run) {
                const float* p = &runPixels[run][i];
                const float keep = 1.0f - p[3];
                r = p[0] + r * keep;
                g = p[1] + g * keep;
                b = p[2] + b * keep;
                a = p[3] + a * keep;
            }
            const auto byte
                = [](float v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
            m_rgba[i] = byte(r);
            m_rgba[i + 1] = byte(g);
            m_rgba[i + 2] = byte(b);
            m_rgba[i + 3] = byte(a);
        }
    };
    const auto rows = static_cast<std::size_t>(in.region.height());
    forRange(pool, rows, 16, merge);
    return m_rgba;
}

} // namespace wisp
