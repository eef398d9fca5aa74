#include "sim/groom/GrowthRegion.h"

#include <algorithm>
#include <cmath>

namespace wisp {

std::vector<const GrowthRegion*> growingRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId)
{
    std::vector<const GrowthRegion*> growing;
    for (const GrowthRegion& r : regions)
        if (r.id == soloId)
            return { &r };
    for (const GrowthRegion& r : regions)
        if (r.visible)
            growing.push_back(&r);
    return growing;
}

std::string validateRegion(const GrowthRegion& region, std::size_t vertexCount)
{
    const std::string where = "region '" + region.name + "': ";
    if (region.weights.size() != vertexCount)
        return where + std::to_string(region.weights.size()) + " weights for " + std::to_string(vertexCount)
            + " vertices";
    for (std::size_t i = 0; i < region.weights.size(); ++i)
        if (!std::isfinite(region.weights[i]))
            return where + "weight " + std::to_string(i) + " is not a finite number";
    for (const ParameterInfo& p : allParameters())
        if (p.group == ParamGroup::Wisp)
            if (std::string error = checkParameterValue(p.id, region.values.get(p.id)); !error.empty())
                return where + error;
    if (region.importedStrands) {
        const HairCurves& c = *region.importedStrands;
        if (c.offsets.empty() || c.offsets.front() != 0 || c.offsets.back() != c.positions.size())
            return where + "imported strands: the offsets do not match the points";
        for (std::size_t i = 0; i < c.positions.size(); ++i)
            if (!std::isfinite(c.positions[i].x + c.positions[i].y + c.positions[i].z))
                return where + "imported point " + std::to_string(i) + " is not finite";
    }
    for (const glm::vec3& c : { region.rootColour, region.tipColour })
        for (int k = 0; k < 3; ++k)
            if (!(c[k] >= 0.0f && c[k] <= 1.0f))
                return where + "colour component " + std::to_string(c[k]) + " is outside 0..1";
    return {};
}

std::vector<glm::vec4> scalpCoverage(
    const std::vector<GrowthRegion>& regions, std::uint32_t soloId, std::size_t vertexCount)
{
    std::vector<glm::vec4> out(vertexCount, glm::vec4(0.0f));
    for (const GrowthRegion* region : growingRegions(regions, soloId)) {
        if (region->weights.size() != vertexCount)
            continue;
        for (std::size_t i = 0; i < vertexCount; ++i) {
            const float w = region->weights[i];
            if (std::isfinite(w) && w > out[i].w)
                out[i] = glm::vec4(region->rootColour, std::min(w, 1.0f));
        }
    }
    return out;
}

} // namespace wisp
