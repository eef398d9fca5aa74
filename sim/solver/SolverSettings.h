#pragma once
// What the solver needs from the forces and material parameters, in SI units and as vectors.

#include "sim/params/Parameters.h"

#include <glm/vec3.hpp>

#include <string>

namespace wisp {

struct SolverSettings {
    float timeStepSeconds = 1.0f / 60.0f;
    int substeps = 1;
    glm::vec3 gravity{ 0.0f, -9.81f, 0.0f }; // m/s², world space
    glm::vec3 wind{ 0.0f }; // m/s, world space
    float turbulence = 0.0f; // gust amplitude as a fraction of the wind speed
    float dragPerSecond = 0.0f; // k of F = -k (v - wind), per unit mass
    float dampingPerSecond = 0.0f; // v *= exp(-damping dt)
    float stiffness = 0.0f; // 0..1: bending rigidity, see bending::rigidity (BendingModel.h)
    // 0..1: share of the way to the rest pose per 1/60 s at the root, fading along the strand (see
    // SolverBlockKernel.cpp, pullTowardGlobalShape); 0 is off and costs nothing.
    float globalShape = 0.0f;
    float friction = 0.0f; // Coulomb coefficient μ (kinetic; static 1.25 μ)
    float hairOffsetMetres = 0.0f; // kept between hair and skin
    float volume = 0.0f; // 0..1: hair-hair interaction through the volume grid; 0 off
    float hairFriction = 0.0f; // 0..1: share of the velocity difference between neighbouring hairs lost per 1/60 s
    // s_damping of Müller et al. 2012, eq. 9. 1 would conserve momentum exactly (the parent takes
    // back what follow-the-leader gave the child); below about 0.9 the energy follow-the-leader
    // adds makes curly strands with many segments and substeps shiver. Measured by the settling
    // tests (tests/sim/SettlingTest.cpp): 0.95 settles every case, 0.9 and 1 leave some moving.
    float velocityCorrection = 0.95f;
};

// The solver's substep, seconds: a step runs `substeps` of them (Solver::step). The rest-shape
// solve runs them one at a time (RestShapeSolve.cpp), so both take it from here.
inline float substepSeconds(const SolverSettings& settings)
{
    return settings.timeStepSeconds / static_cast<float>(settings.substeps > 1 ? settings.substeps : 1);
}

// Wind velocity from speed and angles (see the wind_azimuth and wind_elevation help texts).
glm::vec3 windVelocity(float speed, float azimuthDegrees, float elevationDegrees);

// Whether the wind blows in gusts: some turbulence and some wind (the block kernel then samples
// them along each strand; `wisp-cli bench` lists them among the physics a step runs).
bool blowsGusts(float turbulence, const glm::vec3& wind);

SolverSettings solverSettingsFrom(const ParameterValues& values);

// Empty when usable; otherwise names the setting and what is wrong with it.
[[nodiscard]] std::string validateSolverSettings(const SolverSettings& settings);

} // namespace wisp
