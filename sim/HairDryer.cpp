#include "sim/HairDryer.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {
// A round jet keeps its speed for about six nozzle diameters and then slows as 1/distance
// (Rajaratnam, "Turbulent Jets", 1976); a 4-5 cm nozzle gives this length scale.
constexpr float kJetCoreMetres = 0.3f;
}  // namespace

glm::vec3 dryerAirAt(const HairDryer& dryer, const glm::vec3& p)
{
    const glm::vec3 offset = p - dryer.nozzle;
    const float along = glm::dot(offset, dryer.direction);
    if (!(along > 0.0f) || along > dryer.reachMetres)
        return glm::vec3(0.0f);
    const float distance = glm::length(offset);
    const float angle = std::acos(std::clamp(along / std::max(distance, 1e-9f), -1.0f, 1.0f));
    if (angle >= dryer.halfAngleRadians)
        return glm::vec3(0.0f);
    const float across = std::cos(angle / dryer.halfAngleRadians * glm::half_pi<float>());
    const float speed = dryer.speedMetresPerSecond * across * across / (1.0f + along / kJetCoreMetres);
    return dryer.direction * speed;
}

float dryingRate(float wetness, float airSpeed, float halfLifeSeconds)
{
    if (wetness <= 0.0f)
        return 0.0f;
    const float still = wetness * std::log(2.0f) / std::max(halfLifeSeconds, 1e-3f);
    return -(still + 0.25f * std::max(airSpeed, 0.0f));
}

float wetStiffnessFactor(float wetness) { return 1.0f - 0.75f * std::clamp(wetness, 0.0f, 1.0f); }
float wetDragFactor(float wetness) { return 1.0f / (1.0f + 1.5f * std::clamp(wetness, 0.0f, 1.0f)); }
float wetClumping(float wetness) { return std::clamp(wetness, 0.0f, 1.0f); }

}  // namespace wisp
