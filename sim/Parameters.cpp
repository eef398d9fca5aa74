#include "sim/Parameters.h"

#include <cmath>
#include <cstdio>

namespace wisp {
namespace {

using enum Param;
using G = ParamGroup;
using K = ParamKind;

// Ranges are what the solver and groom handle well, wide enough for stylised looks; the hostile
// test (gravity 50 m/s², wind 50 m/s, dt 1/15 s) sits inside them on purpose.
constexpr std::array<ParameterInfo, kParamCount> kParameters{{
    {Density, "density", "Density", "strands/cm²", G::Wisp, K::Real, 0.05, 200.0, 8.0,
     "Drawn strands per square centimetre of scalp where the growth map is 1 (pore density, Lee et al.)"},
    {WispSize, "wisp_size", "Wisp size", "strands", G::Wisp, K::Integer, 1, 1024, 12,
     "Strands per wisp; each wisp has one simulated key hair that its members follow"},
    {ClumpDegree, "clump_degree", "Clump degree", "", G::Wisp, K::Real, -1.0, 1.0, 0.5,
     "How far members move toward the key hair: 1 onto it, 0 parallel, -1 spread to twice the wisp radius"},
    {ClumpRate, "clump_rate", "Clump rate", "", G::Wisp, K::Real, 0.0, 1.0, 0.3,
     "Where along the strand clumping starts, as a fraction of its length (0 at the root)"},
    {Length, "length", "Length", "m", G::Wisp, K::Real, 0.005, 2.0, 0.28,
     "Strand length along the hair (arc length), in metres"},
    {LengthVariation, "length_variation", "Length variation", "", G::Wisp, K::Real, 0.0, 0.9, 0.15,
     "Random variation of each strand's length, as a fraction of Length"},
    {Segments, "segments", "Segments", "per strand", G::Groom, K::Integer, 2, 127, 15,
     "Segments per simulated strand (particles = segments + 1); curly hair needs more"},
    {CurlRadius, "curl_radius", "Curl radius", "m", G::Wisp, K::Real, 0.0, 0.05, 0.0,
     "Radius of the helix the hair curls around; 0 for straight hair"},
    {CurlTurns, "curl_turns", "Curl turns", "turns/m", G::Wisp, K::Real, 0.0, 200.0, 0.0,
     "Turns of the curl per metre of hair (along the hair, not its axis); waves are a few, ringlets 20 or more; at most 0.95 / (2π × Curl radius)"},
    {StiffnessScale, "stiffness_scale", "Stiffness scale", "×", G::Wisp, K::Real, 0.0, 4.0, 1.0,
     "Multiplies the solver's Stiffness for this region's hair (hairspray raises it); the product is capped at 1"},
    {Seed, "seed", "Seed", "", G::Groom, K::Integer, 0, 2147483647, 1,
     "Random seed for root placement and variation; the same seed gives the same groom"},

    {Gravity, "gravity", "Gravity", "m/s²", G::Forces, K::Real, -100.0, 100.0, 9.81,
     "Downward acceleration; negative makes hair float upward"},
    {WindSpeed, "wind_speed", "Wind speed", "m/s", G::Forces, K::Real, 0.0, 100.0, 1.5,
     "Speed of the wind the hair is dragged toward"},
    {WindAzimuth, "wind_azimuth", "Wind azimuth", "°", G::Forces, K::Real, -360.0, 360.0, -90.0,
     "Direction the wind blows toward, around +Y: 0 toward +X, 90 toward +Z (the face), -90 toward the back"},
    {WindElevation, "wind_elevation", "Wind elevation", "°", G::Forces, K::Real, -90.0, 90.0, 0.0,
     "Angle of the wind above the horizontal: 90 blows straight up"},
    {Turbulence, "turbulence", "Turbulence", "", G::Forces, K::Real, 0.0, 2.0, 0.6,
     "Gusts: noise in space and time added to the wind at every particle, as a fraction of its speed"},
    {Drag, "drag", "Drag", "1/s", G::Forces, K::Real, 0.0, 50.0, 0.8,
     "Air drag k of F = -k(v - wind) per unit mass; higher follows the wind more closely"},
    {Damping, "damping", "Damping", "1/s", G::Forces, K::Real, 0.0, 50.0, 1.0,
     "Velocity lost per second to internal friction, v *= exp(-damping dt)"},
    {DryingTime, "drying_time", "Drying half-life", "s", G::Forces, K::Real, 1.0, 3600.0, 120.0,
     "Wet hair (wet brush) loses half its water in this time in still air; the blow-dryer dries faster"},

    {Stiffness, "stiffness", "Stiffness", "", G::Solver, K::Real, 0.0, 1.0, 0.25,
     "Bending stiffness, 0 limp to 1 rigid (four decades of rigidity); the same look at any substep or "
     "segment count. 0.25 hangs; about 0.5 holds a combed lock; curls hold from about 0.3"},
    {Friction, "friction", "Friction", "", G::Solver, K::Real, 0.0, 1.0, 0.3,
     "Coulomb friction coefficient of hair on skin and the body: sliding slows by this times the "
     "contact's push (static up to 1.25 times it)"},
    {HairOffset, "hair_offset", "Hair offset", "m", G::Groom, K::Real, 0.0, 0.02, 0.002,
     "Distance kept between the hair and the skin"},
    {TimeStep, "time_step", "Time step", "s", G::Solver, K::Real, 1.0 / 1000.0, 1.0 / 10.0, 1.0 / 60.0,
     "Simulated time per step"},
    {Substeps, "substeps", "Substeps", "per step", G::Solver, K::Integer, 1, 32, 2,
     "Solver iterations per step; more is stiffer and steadier, and slower"},
    {SimulateAllStrands, "simulate_all_strands", "Simulate all strands", "", G::Solver, K::Toggle, 0, 1, 0,
     "Simulate every strand instead of only the key hair of each wisp (slower, no clumping by wisp)"},
    {Body, "body", "Neck and shoulders", "", G::Solver, K::Toggle, 0, 1, 1,
     "Hair collides with a neck and shoulders under the head (capsules sized from the head), and rests on them"},
}};

constexpr bool tableIsInOrder()
{
    for (std::size_t i = 0; i < kParameters.size(); ++i)
        if (static_cast<std::size_t>(kParameters[i].id) != i)
            return false;
    return true;
}
static_assert(tableIsInOrder(), "kParameters must list the parameters in the order of enum Param");

std::string formatNumber(double v)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6g", v);
    return buffer;
}

}  // namespace

std::span<const ParameterInfo> allParameters() { return kParameters; }

const ParameterInfo& parameterInfo(Param id) { return kParameters[static_cast<std::size_t>(id)]; }

const ParameterInfo* findParameter(std::string_view key)
{
    for (const ParameterInfo& p : kParameters)
        if (p.key == key)
            return &p;
    return nullptr;
}

bool isWithinRange(const ParameterInfo& p, double value)
{
    if (p.kind == ParamKind::Real) {
        // The program holds real parameters as floats: compare as floats, so that a range end
        // written in a file or on the command line (0.1, stored as the float just above the
        // double 0.1) is inside, and a value that only differs beyond float precision is too.
        const float v = static_cast<float>(value);
        return v >= static_cast<float>(p.minimum) && v <= static_cast<float>(p.maximum);
    }
    return value >= p.minimum && value <= p.maximum;
}

std::string checkParameterValue(Param id, double value)
{
    const ParameterInfo& p = parameterInfo(id);
    if (!std::isfinite(value))
        return std::string(p.key) + ": " + formatNumber(value) + " is not a finite number";
    if (p.kind != ParamKind::Real && std::floor(value) != value)
        return std::string(p.key) + ": " + formatNumber(value) +
               (p.kind == ParamKind::Toggle ? " is not 0 or 1" : " is not a whole number");
    if (!isWithinRange(p, value))
        return std::string(p.key) + ": " + formatNumber(value) + " is outside " + formatNumber(p.minimum) + ".." +
               formatNumber(p.maximum);
    return {};
}

std::string checkParameterValues(std::initializer_list<std::pair<Param, double>> values)
{
    for (const auto& [id, value] : values)
        if (std::string error = checkParameterValue(id, value); !error.empty())
            return error;
    return {};
}

ParameterValues::ParameterValues()
{
    for (const ParameterInfo& p : kParameters)
        m_values[static_cast<std::size_t>(p.id)] = p.defaultValue;
}

std::string ParameterValues::set(Param id, double value)
{
    std::string error = checkParameterValue(id, value);
    if (error.empty())
        m_values[static_cast<std::size_t>(id)] = value;
    return error;
}

}  // namespace wisp
