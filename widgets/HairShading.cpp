#include "widgets/HairShading.h"

#include "sim/util/ThreadPool.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {
namespace {

float smoothStep(float edge0, float edge1, float x)
{
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// x^y for x in [0, 1], y > 0: exp2(y log2 x), as GLSL's pow.
float powUnit(float x, float y)
{
    if (!(x > 0.0f))
        return 0.0f;
    return std::exp2(y * std::log2(x));
}

// pow(x, 1 / 2.2) for x in [0, 1] from a table, linear between its entries: within 1e-5 of the
// function from 1/256 up (the interpolation's error, h^2/8 |f''|), far under the 8-bit step (3.9e-3)
// the colour ends in, and a fraction of the cost of the three pows a sample it replaces. Below
// 1/256, where the curve is too steep for the table, the pow itself.
class GammaTable {
public:
    GammaTable()
    {
        for (int i = 0; i <= kEntries; ++i)
            m_values[i] = powUnit(static_cast<float>(i) / kEntries, 1.0f / 2.2f);
        m_values[kEntries + 1] = m_values[kEntries];
    }
    float operator()(float x) const
    {
        if (x < 1.0f / 256.0f)
            return powUnit(x, 1.0f / 2.2f);
        const float at = std::min(x, 1.0f) * kEntries;
        const int i = static_cast<int>(at);
        return m_values[i] + (at - static_cast<float>(i)) * (m_values[i + 1] - m_values[i]);
    }

private:
    static constexpr int kEntries = 4096;
    float m_values[kEntries + 2];
};

const GammaTable& gammaTable()
{
    static const GammaTable table;
    return table;
}

// hair_strand.glsl's kajiyaKaySpecular, for the two highlights at once (one log2 for both powers).
float sinToHalf(const glm::vec3& tangent, const glm::vec3& halfVector, float& th)
{
    th = glm::dot(tangent, halfVector);
    return std::sqrt(std::max(1.0f - th * th, 0.0f));
}

// hair_strand.glsl's shadeHair (Kajiya-Kay with Scheuermann's two shifted highlights); sRGB out.
glm::vec3 shadeHair(const HairShadingView& view, const glm::vec3& positionView, const glm::vec3& T, float along,
    const glm::vec3& rootColour, const glm::vec3& tipColour, float keyShadow, float ambient)
{
    const glm::vec3 V = glm::normalize(-positionView);
    const glm::vec3& L = view.keyLightView;
    glm::vec3 N = V - T * glm::dot(T, V);
    N = glm::dot(N, N) > 1e-8f ? glm::normalize(N) : V;

    const glm::vec3 base = glm::mix(rootColour, tipColour, smoothStep(0.0f, 1.0f, along));
    const float tl = glm::dot(T, L);
    const float diffuse = std::sqrt(std::max(1.0f - tl * tl, 0.0f));
    const glm::vec3 volumeNormal = glm::normalize(positionView - view.headCentreView + glm::vec3(1e-6f));
    const float keyWrap = std::clamp((glm::dot(volumeNormal, L) + 0.5f) / 1.5f, 0.0f, 1.0f);
    const float fillWrap = std::clamp((glm::dot(volumeNormal, view.fillLightView) + 0.5f) / 1.5f, 0.0f, 1.0f);
    const float occlusion
        = view.shadows ? glm::mix(0.3f, 1.0f, ambient) : glm::mix(0.45f, 1.0f, smoothStep(0.0f, 0.4f, along));

    const glm::vec3 H = glm::normalize(L + V);
    float thPrimary = 0.0f;
    float thSecondary = 0.0f;
    const float sinPrimary = sinToHalf(glm::normalize(T + 0.08f * N), H, thPrimary);
    const float sinSecondary = sinToHalf(glm::normalize(T - 0.12f * N), H, thSecondary);
    const float primary = powUnit(sinPrimary, 90.0f) * smoothStep(-1.0f, 0.0f, thPrimary);
    const float secondary = powUnit(sinSecondary, 22.0f) * smoothStep(-1.0f, 0.0f, thSecondary);

    const float key = keyWrap * keyShadow;
    glm::vec3 colour = base * ((0.18f + 0.25f * fillWrap) * occlusion + 0.95f * diffuse * key);
    colour += key * (0.28f * primary * glm::vec3(1.0f, 0.97f, 0.92f) + 0.35f * secondary * base);
    const GammaTable& gamma = gammaTable();
    return { gamma(colour.x), gamma(colour.y), gamma(colour.z) };
}

// hair_strand.glsl's strandSample, less the ribbon's edges.
HairRasterSample shadeSample(const HairWorldSample& w, const HairShadingView& view, const glm::mat3& viewTurn)
{
    HairRasterSample result;
    if (!(w.tip.w >= 0.0f)) {
        // A strand with a non-finite point: outside the clip volume, as the shader puts it.
        result.clip = glm::vec4(2.0f, 2.0f, 2.0f, 1.0f);
        result.colour = glm::vec4(0.0f);
        result.side = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
        return result;
    }
    const glm::vec4 positionView = view.view * glm::vec4(glm::vec3(w.position), 1.0f);
    glm::vec3 tangentView = viewTurn * glm::vec3(w.derivative);
    const float tangentLength = glm::length(tangentView);
    tangentView = tangentLength > 1e-12f ? tangentView / tangentLength : glm::vec3(0.0f, 1.0f, 0.0f);

    const float along = w.position.w;
    const float depth = std::max(-positionView.z, 1e-4f);
    const float rootWidthMetres = w.tip.w * view.widthScale;
    const float widthMetres = rootWidthMetres * glm::mix(1.0f, view.tipThicknessRatio, along);
    const float widthPixels = widthMetres * view.projection[1][1] * 0.5f * view.viewportPixels.y / depth;
    const float drawnPixels = std::max(widthPixels, view.minWidthPixels);

    result.clip = view.projection * positionView;
    result.side = glm::vec4(0.0f, 0.0f, view.ribbon ? 0.5f * (drawnPixels + 1.0f) : 1.0f, 0.0f);
    const float coverage = std::min(widthPixels / drawnPixels, 1.0f);
    const float alpha = coverage * (1.0f - view.tipFade * smoothStep(0.55f, 1.0f, along));
    result.colour = glm::vec4(shadeHair(view, glm::vec3(positionView), tangentView, along, glm::vec3(w.root),
                                  glm::vec3(w.tip), w.derivative.w, w.root.w),
        alpha);
    return result;
}

} // namespace

void shadeHairSamples(
    std::span<const HairWorldSample> in, const HairShadingView& view, std::span<HairRasterSample> out, ThreadPool* pool)
{
    const std::size_t count = std::min(in.size(), out.size());
    const glm::mat3 viewTurn(view.view);
    const auto body = [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i)
            out[i] = shadeSample(in[i], view, viewTurn);
    };
    forRange(pool, count, 4096, body);
}

} // namespace wisp
