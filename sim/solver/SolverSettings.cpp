#include "sim/solver/SolverSettings.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace wisp {

bool blowsGusts(float turbulence, const glm::vec3& wind)
{
    return turbulence > 0.0f && glm::length(wind) > 0.0f;
}

glm::vec3 windVelocity(float speed, float azimuthDegrees, float elevationDegrees)
{
    const float az = glm::radians(azimuthDegrees);
    const float el = glm::radians(elevationDegrees);
    return speed * glm::vec3(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az));
}

SolverSettings solverSettingsFrom(const ParameterValues& v)
{
    SolverSettings s;
    s.timeStepSeconds = v.getFloat(Param::TimeStep);
    s.substeps = v.getInt(Param::Substeps);
    s.gravity = glm::vec3(0.0f, -v.getFloat(Param::Gravity), 0.0f);
    s.wind
        = windVelocity(v.getFloat(Param::WindSpeed), v.getFloat(Param::WindAzimuth), v.getFloat(Param::WindElevation));
    s.turbulence = v.getFloat(Param::Turbulence);
    s.dragPerSecond = v.getFloat(Param::Drag);
    s.dampingPerSecond = v.getFloat(Param::Damping);
    s.stiffness = v.getFloat(Param::Stiffness);
    s.globalShape = v.getFloat(Param::GlobalShape);
    s.friction = v.getFloat(Param::Friction);
    s.hairOffsetMetres = v.getFloat(Param::HairOffset);
    s.volume = v.getFloat(Param::Volume);
    s.hairFriction = v.getFloat(Param::HairFriction);
    return s;
}

namespace {
bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
} // namespace

std::string validateSolverSettings(const SolverSettings& s)
{
    const std::string rangeError = checkParameterValues({
        { Param::TimeStep, s.timeStepSeconds },
        { Param::Substeps, s.substeps },
        { Param::Turbulence, s.turbulence },
        { Param::Drag, s.dragPerSecond },
        { Param::Damping, s.dampingPerSecond },
        { Param::Stiffness, s.stiffness },
        { Param::Friction, s.friction },
        { Param::HairOffset, s.hairOffsetMetres },
        { Param::GlobalShape, s.globalShape },
        { Param::Volume, s.volume },
        { Param::HairFriction, s.hairFriction },
    });
    if (!rangeError.empty())
        return rangeError;
    if (!finite(s.gravity) || glm::length(s.gravity) > 1000.0f)
        return "gravity: must be a finite vector shorter than 1000 m/s²";
    if (!finite(s.wind) || glm::length(s.wind) > 1000.0f)
        return "wind: must be a finite vector slower than 1000 m/s";
    if (!std::isfinite(s.velocityCorrection) || s.velocityCorrection < 0.0f || s.velocityCorrection > 1.0f)
        return "velocity correction: must be within 0..1";
    return {};
}

} // namespace wisp
