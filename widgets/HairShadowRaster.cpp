#include "widgets/HairShadowRaster.h"

#include "sim/util/ThreadPool.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <glm/vector_relational.hpp>

namespace wisp {
namespace {

// A point as the passes see it: texel coordinates (x, y), clip depth z (-1..1), metres from the light.
struct LightPoint {
    float x, y, z, metres;
};

LightPoint fromLight(const ShadowRasterInput& in, const glm::vec4& point)
{
    const glm::vec4 p(glm::vec3(point), 1.0f);
    const glm::vec4 clip = in.lightViewProjection * p;
    const float inverseW = 1.0f / clip.w;
    const auto n = static_cast<float>(in.pixels);
    return { (clip.x * inverseW * 0.5f + 0.5f) * n, (clip.y * inverseW * 0.5f + 0.5f) * n, clip.z * inverseW,
        (in.worldToShadow * p).z };
}

// Calls fragment(texel index, metres) for each texel the one-texel line a-b covers (see the header).
template <typename Fragment> void walkLine(const LightPoint& a, const LightPoint& b, int pixels, Fragment&& fragment)
{
    if (!(std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(b.x) && std::isfinite(b.y)
            && std::isfinite(a.metres) && std::isfinite(b.metres)))
        return;
    const bool swapped = std::abs(b.y - a.y) > std::abs(b.x - a.x);
    const float au = swapped ? a.y : a.x;
    const float av = swapped ? a.x : a.y;
    const float du = (swapped ? b.y : b.x) - au;
    const float dv = (swapped ? b.x : b.y) - av;
    const auto n = static_cast<float>(pixels);
    const float uMin = std::max(std::min(au, au + du), -1.0f);
    const float uMax = std::min(std::max(au, au + du), n + 1.0f);
    const int begin = std::max(static_cast<int>(std::ceil(uMin - 0.5f)), 0);
    const int end = std::min(static_cast<int>(std::ceil(uMax - 0.5f)), pixels);
    if (begin >= end)
        return;
    const float inverseDu = 1.0f / du;
    for (int u = begin; u < end; ++u) {
        const float t = (static_cast<float>(u) + 0.5f - au) * inverseDu;
        const float v = av + t * dv;
        if (!(v >= 0.0f && v < n))
            continue;
        const float z = a.z + t * (b.z - a.z);
        if (!(z >= -1.0f && z <= 1.0f)) // GL clips to the light's near and far planes
            continue;
        const int w = static_cast<int>(v);
        const int x = swapped ? w : u;
        const int y = swapped ? u : w;
        fragment(static_cast<std::size_t>(y) * static_cast<std::size_t>(pixels) + static_cast<std::size_t>(x),
            a.metres + t * (b.metres - a.metres));
    }
}

// Every drawn strand's segments among strands [first, last), as lines.
template <typename Fragment>
void walkStrands(const ShadowRasterInput& in, std::size_t first, std::size_t last, Fragment&& fragment)
{
    for (std::size_t s = first; s < last; ++s) {
        const std::size_t begin = in.strandOffsets[s];
        const std::size_t end = std::min<std::size_t>(in.strandOffsets[s + 1], in.points.size());
        if (end < begin + 2 || !(in.points[begin].w >= 0.5f))
            continue;
        LightPoint previous = fromLight(in, in.points[begin]);
        for (std::size_t i = begin + 1; i < end; ++i) {
            const LightPoint next = fromLight(in, in.points[i]);
            walkLine(previous, next, in.pixels, fragment);
            previous = next;
        }
    }
}

} // namespace

void drawShadowHair(
    const ShadowRasterInput& in, std::vector<glm::vec2>& depth, std::vector<glm::vec4>& opacity, ThreadPool* pool)
{
    const std::size_t texels
        = static_cast<std::size_t>(std::max(in.pixels, 0)) * static_cast<std::size_t>(std::max(in.pixels, 0));
    if (texels == 0 || depth.size() != texels || opacity.size() != texels)
        return;
    const std::size_t strands = in.strandOffsets.size() > 0 ? in.strandOffsets.size() - 1 : 0;
    const std::size_t runs
        = std::clamp<std::size_t>(pool ? pool->threadCount() : 1, 1, std::max<std::size_t>(strands, 1));
    const auto runBegin = [&](std::size_t run) { return strands * run / runs; };
    const auto forEachRun = [&](const std::function<void(std::size_t)>& body) {
        forRange(pool, runs, 1, [&](std::size_t a, std::size_t b) {
            for (std::size_t run = a; run < b; ++run)
                body(run);
        });
    };

    // Pass 1: the nearest depth, per run, then the least of them.
    std::vector<std::vector<float>> nearest(runs);
    forEachRun([&](std::size_t run) {
        std::vector<float>& mine = nearest[run];
        mine.resize(texels);
        for (std::size_t i = 0; i < texels; ++i)
            mine[i] = depth[i].x;
        walkStrands(in, runBegin(run), runBegin(run + 1),
            [&](std::size_t texel, float metres) { mine[texel] = std::min(mine[texel], metres); });
    });
    for (std::size_t i = 0; i < texels; ++i) {
        float least = nearest[0][i];
        for (std::size_t run = 1; run < runs; ++run)
            least = std::min(least, nearest[run][i]);
        depth[i].x = least;
    }

    // Pass 2: each layer whose far end lies behind the fragment takes its opacity; per run, summed.
    std::vector<std::vector<glm::vec4>> layers(runs);
    forEachRun([&](std::size_t run) {
        std::vector<glm::vec4>& mine = layers[run];
        mine.assign(texels, glm::vec4(0.0f));
        walkStrands(in, runBegin(run), runBegin(run + 1), [&](std::size_t texel, float metres) {
            const float behind = metres - depth[texel].x;
            mine[texel] += in.strandOpacity * glm::vec4(glm::lessThan(glm::vec4(behind), in.layerMetres));
        });
    });
    for (std::size_t i = 0; i < texels; ++i) {
        glm::vec4 sum = layers[0][i];
        for (std::size_t run = 1; run < runs; ++run)
            sum += layers[run][i];
        opacity[i] = sum;
    }
}

} // namespace wisp
