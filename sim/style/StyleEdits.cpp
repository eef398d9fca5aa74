#include "sim/style/StyleEdits.h"

#include "sim/util/ByteHash.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <sstream>

namespace wisp {

namespace {

std::string describe(float v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

} // namespace

std::string validateStrandStyle(std::uint64_t identity, const StrandStyle& s)
{
    const std::string where = "strand " + std::to_string(identity) + ": ";
    auto outside = [&](const char* what, float v, const std::string& range) {
        return where + what + " " + describe(v) + " is outside " + range;
    };
    if (!std::isfinite(s.lengthMetres)
        || (s.lengthMetres != 0.0f
            && (s.lengthMetres < kStyleMinLengthMetres || s.lengthMetres > kStyleMaxLengthMetres)))
        return outside("length", s.lengthMetres, "0.005..2 m (or 0 for the region's)");
    if (!std::isfinite(s.curlRadiusMetres) || s.curlRadiusMetres > kStyleMaxCurlRadiusMetres)
        return outside("curl radius", s.curlRadiusMetres, "0..0.05 m (or negative for the region's)");
    if (!std::isfinite(s.curlTurnsPerMetre) || s.curlTurnsPerMetre > kStyleMaxCurlTurnsPerMetre)
        return outside("curl turns", s.curlTurnsPerMetre, "0..200 turns/m (or negative for the region's)");
    if (!std::isfinite(s.stiffnessScale) || s.stiffnessScale < 1.0f || s.stiffnessScale > kStyleMaxStiffnessScale)
        return outside("stiffness scale", s.stiffnessScale, "1..50");
    if (!std::isfinite(s.wetness) || s.wetness < 0.0f || s.wetness > 1.0f)
        return outside("wetness", s.wetness, "0..1");
    if (s.shape.size() == 1 || s.shape.size() > kStyleMaxShapePoints)
        return where + "shape has " + std::to_string(s.shape.size()) + " points (needs 2.."
            + std::to_string(kStyleMaxShapePoints) + ")";
    for (std::size_t j = 0; j < s.shape.size(); ++j) {
        const glm::vec3& p = s.shape[j];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || std::abs(p.x) > 100.0f
            || std::abs(p.y) > 100.0f || std::abs(p.z) > 100.0f)
            return where + "shape point " + std::to_string(j) + " is not a finite position within 100 m";
        if (j > 0 && glm::distance(p, s.shape[j - 1]) < 1e-7f)
            return where + "shape points " + std::to_string(j - 1) + " and " + std::to_string(j) + " coincide";
    }
    return {};
}

std::uint64_t restShapeHash(const StrandStyle& s)
{
    if (s.lengthMetres == 0.0f && s.curlRadiusMetres < 0.0f && s.curlTurnsPerMetre < 0.0f && s.shape.empty())
        return 0;
    ByteHash h;
    h.add(s.lengthMetres);
    h.add(s.curlRadiusMetres);
    h.add(s.curlTurnsPerMetre);
    if (!s.shape.empty())
        h.add(s.shape.data(), s.shape.size() * sizeof(glm::vec3));
    return h.value == 0 ? 1 : h.value;
}

std::vector<glm::vec3> shapeWithLength(std::span<const glm::vec3> shape, float lengthMetres)
{
    std::vector<glm::vec3> out;
    if (shape.size() < 2)
        return { shape.begin(), shape.end() };
    out.push_back(shape[0]);
    float along = 0.0f;
    for (std::size_t j = 1; j < shape.size(); ++j) {
        const float segment = glm::distance(shape[j - 1], shape[j]);
        if (along + segment >= lengthMetres) {
            const float t = segment > 0.0f ? (lengthMetres - along) / segment : 0.0f;
            if (t > 1e-4f)
                out.push_back(glm::mix(shape[j - 1], shape[j], t));
            if (out.size() < 2) // cut within the first 0.01% of a segment: keep a sliver
                out.push_back(glm::mix(shape[j - 1], shape[j], 1e-3f));
            return out;
        }
        along += segment;
        out.push_back(shape[j]);
    }
    // Longer than the shape: continue along the last segment (as long already: nothing to add).
    if (lengthMetres - along > 1e-6f) {
        const glm::vec3 direction = glm::normalize(shape.back() - shape[shape.size() - 2]);
        out.push_back(shape.back() + direction * (lengthMetres - along));
    }
    return out;
}

} // namespace wisp
