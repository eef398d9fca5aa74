#include "sim/GrowthRegion.h"

#include <cmath>

namespace wisp {

std::vector<const GrowthRegion*> growingRegions(const std::vector<GrowthRegion>& regions, std::uint32_t soloId)
{
    std::vector<const GrowthRegion*> growing;
    for (const GrowthRegion& r : regions)
        if (r.id == soloId)
            return {&r};
    for (const GrowthRegion& r : regions)
        if (r.visible)
            growing.push_back(&r);
    return growing;
}

std::string validateRegion(const GrowthRegion& region, std::size_t vertexCount)
{
    const std::string where = "region '" + region.name + "': ";
    if (region.weights.size() != vertexCount)
        return where + std::to_string(region.weights.size()) + " weights for " + std::to_string(vertexCount) + " vertices";
    for (std::size_t i = 0; i < region.weights.size(); ++i)
        if (!std::isfinite(region.weights[i]))
            return where + "weight " + std::to_string(i) + " is not a finite number";
    for (const ParameterInfo& p : allParameters())
        if (p.group == ParamGroup::Wisp)
            if (std::string error = checkParameterValue(p.id, region.values.get(p.id)); !error.empty())
                return where + error;
    for (const glm::vec3& c : {region.rootColour, region.tipColour})
        for (int k = 0; k < 3; ++k)
            if (!(c[k] >= 0.0f && c[k] <= 1.0f))
                return where + "colour component " + std::to_string(c[k]) + " is outside 0..1";
    return {};
}

}  // namespace wisp
