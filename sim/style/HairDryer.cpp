#include "sim/style/HairDryer.h"

#include "sim/geometry/SignedDistanceField.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {
// A round jet keeps its speed for about six nozzle diameters and then slows as 1/distance
// (Rajaratnam, "Turbulent Jets", 1976); a 4-5 cm nozzle gives this length scale.
constexpr float kJetCoreMetres = 0.3f;
} // namespace

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

glm::vec3 dryerAirAt(const HairDryer& dryer, const glm::vec3& p, const SignedDistanceField* head)
{
    const glm::vec3 air = dryerAirAt(dryer, p);
    if (!head || air == glm::vec3(0.0f))
        return air;
    constexpr float kSkinGap = 0.01f; // metres left untraced before p
    constexpr float kHit = 0.001f; // closer than this to the skin: the head is in the way
    constexpr float kMinStep = 0.003f; // sphere tracing creeps no slower than this
    constexpr int kMaxSteps = 64; // a grazing ray that is still going counts as clear
    const glm::vec3 offset = p - dryer.nozzle;
    const float length = glm::length(offset);
    const glm::vec3 direction = offset / length;
    float t = 0.0f;
    for (int i = 0; i < kMaxSteps && t < length - kSkinGap; ++i) {
        const float d = head->distance(dryer.nozzle + direction * t);
        if (d < kHit)
            return glm::vec3(0.0f);
        t += std::max(d, kMinStep);
    }
    return air;
}

float dryingRate(float wetness, float airSpeed, float halfLifeSeconds)
{
    if (wetness <= 0.0f)
        return 0.0f;
    const float still = wetness * std::log(2.0f) / std::max(halfLifeSeconds, 1e-3f);
    return -(still + 0.25f * std::max(airSpeed, 0.0f));
}

float wetStiffnessFactor(float wetness)
{
    return 1.0f - 0.75f * std::clamp(wetness, 0.0f, 1.0f);
}
float wetDragFactor(float wetness)
{
    return 1.0f / (1.0f + 1.5f * std::clamp(wetness, 0.0f, 1.0f));
}
float wetVolumeFactor(float wetness)
{
    return 1.0f + 2.0f * std::clamp(wetness, 0.0f, 1.0f);
}
float wetClumping(float wetness)
{
    return std::clamp(wetness, 0.0f, 1.0f);
}

} // namespace wisp
