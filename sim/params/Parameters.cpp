#include "sim/params/Parameters.h"
#include "sim/params/TableOrder.h"
#include "sim/util/NumberText.h"

#include "sim/groom/ScalpBrush.h"
#include "sim/style/StyleEdits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace wisp {
namespace {

using enum Param;
using G = ParamGroup;
using K = ParamKind;
using S = SliderScale;

// Ranges are what the solver and groom handle well, wide enough for stylised looks; the hostile
// test (gravity 50 m/s², wind 50 m/s, dt 1/15 s) sits inside them on purpose.
constexpr std::array<ParameterInfo, kParamCount> kParameters{ {
    { Density, "density", "Density", "strands/cm²", G::Wisp, K::Real, 0.05, 200.0, 8.0,
        "Drawn strands per square centimetre of scalp where the growth map is 1 (pore density, Lee et al.)", S::Log },
    { WispSize, "wisp_size", "Wisp size", "strands", G::Wisp, K::Integer, 1, 1024, 12,
        "Strands per wisp; each wisp has one simulated key hair that its members follow", S::Log },
    { ClumpDegree, "clump_degree", "Clump degree", "", G::Wisp, K::Real, -1.0, 1.0, 0.5,
        "How far members move toward the key hair: 1 onto it, 0 parallel, -1 spread to twice the wisp radius",
        S::Linear },
    { ClumpRate, "clump_rate", "Clump rate", "", G::Wisp, K::Real, 0.0, 1.0, 0.3,
        "Where along the strand clumping starts, as a fraction of its length (0 at the root)", S::Linear },
    { Length, "length", "Length", "m", G::Wisp, K::Real, 0.005, 2.0, 0.28,
        "Strand length along the hair (arc length), in metres", S::Log },
    { LengthVariation, "length_variation", "Length variation", "", G::Wisp, K::Real, 0.0, 0.9, 0.15,
        "Random variation of each strand's length, as a fraction of Length", S::Linear },
    { Segments, "segments", "Segments", "per strand", G::Groom, K::Integer, 2, 127, 15,
        "Segments per simulated strand (particles = segments + 1); curly hair needs more", S::Log },
    { CurlRadius, "curl_radius", "Curl radius", "m", G::Wisp, K::Real, 0.0, 0.05, 0.0,
        "Radius of the helix the hair curls around; 0 for straight hair", S::Log },
    { CurlTurns, "curl_turns", "Curl turns", "turns/m", G::Wisp, K::Real, 0.0, 200.0, 0.0,
        "Turns of the curl per metre of hair (along the hair, not its axis); waves are a few, ringlets 20 or more; at "
        "most 0.95 / (2π × Curl radius)",
        S::Log },
    { StiffnessScale, "stiffness_scale", "Stiffness scale", "×", G::Wisp, K::Real, 0.0, 4.0, 1.0,
        "Multiplies the solver's Stiffness for this region's hair (hairspray raises it); the product is capped at 1",
        S::Linear },
    { HairThickness, "hair_thickness", "Hair thickness", "m", G::Wisp, K::Real, 20e-6, 500e-6, 80e-6,
        "Thickness of one hair at its root (80 µm is typical; it tapers to a quarter at the tip); the viewport draws "
        "each strand as a lock of hairs, this many times wider",
        S::Log, "µm", 1e6 },
    { Seed, "seed", "Seed", "", G::Groom, K::Integer, 0, 2147483647, 1,
        "Random seed for root placement and variation; the same seed gives the same groom", S::Linear },

    { Gravity, "gravity", "Gravity", "m/s²", G::Forces, K::Real, -100.0, 100.0, 9.81,
        "Downward acceleration; negative makes hair float upward", S::Centred },
    { WindSpeed, "wind_speed", "Wind speed", "m/s", G::Forces, K::Real, 0.0, 100.0, 1.5,
        "Speed of the wind the hair is dragged toward", S::Log },
    { WindAzimuth, "wind_azimuth", "Wind azimuth", "°", G::Forces, K::Real, -360.0, 360.0, -90.0,
        "Direction the wind blows toward, around +Y: 0 toward +X, 90 toward +Z (the face), -90 toward the back",
        S::Linear },
    { WindElevation, "wind_elevation", "Wind elevation", "°", G::Forces, K::Real, -90.0, 90.0, 0.0,
        "Angle of the wind above the horizontal: 90 blows straight up", S::Linear },
    { Turbulence, "turbulence", "Turbulence", "", G::Forces, K::Real, 0.0, 2.0, 0.6,
        "Gusts: noise in space and time added to the wind at every particle, as a fraction of its speed", S::Linear },
    { Drag, "drag", "Drag", "1/s", G::Forces, K::Real, 0.0, 50.0, 0.8,
        "Air drag k of F = -k(v - wind) per unit mass; higher follows the wind more closely", S::Log },
    { Damping, "damping", "Damping", "1/s", G::Forces, K::Real, 0.0, 50.0, 1.0,
        "Velocity lost per second to internal friction, v *= exp(-damping dt)", S::Log },
    { DryingTime, "drying_time", "Drying half-life", "s", G::Forces, K::Real, 1.0, 3600.0, 120.0,
        "Wet hair (wet brush) loses half its water in this time in still air; the blow-dryer dries faster", S::Log },

    { Stiffness, "stiffness", "Stiffness", "", G::Solver, K::Real, 0.0, 1.0, 0.25,
        "Bending stiffness, 0 limp to 1 rigid (four decades of rigidity); the same look at any substep or "
        "segment count. 0.25 hangs; about 0.5 holds a combed lock; curls hold from about 0.3",
        S::Linear },
    { GlobalShape, "global_shape", "Global shape", "", G::Solver, K::Real, 0.0, 1.0, 0.0,
        "Pull toward the groomed rest pose as the head carries it: this share per 1/60 s at the root, fading "
        "to none at 3/4 of the strand (Han & Harada 2012, as AMD TressFX); 0 is off",
        S::Linear },
    { Friction, "friction", "Friction", "", G::Solver, K::Real, 0.0, 1.0, 0.3,
        "Coulomb friction coefficient of hair on skin and the body: sliding slows by this times the "
        "contact's push (static up to 1.25 times it)",
        S::Linear },
    { Volume, "volume", "Volume", "", G::Solver, K::Real, 0.0, 1.0, 0.5,
        "Hair-hair interaction: how much room the hair takes. 0 off (strands pass through each other); 0.5 "
        "stands about 2 cm off the scalp on top; 1 about twice as full",
        S::Linear },
    { HairFriction, "hair_friction", "Hair friction", "", G::Solver, K::Real, 0.0, 1.0, 0.2,
        "Friction between neighbouring hairs: the share of their difference in velocity lost every 1/60 s "
        "(0 slide freely, 1 move as one)",
        S::Linear },
    { HairOffset, "hair_offset", "Hair offset", "m", G::Groom, K::Real, 0.0, 0.02, 0.002,
        "Distance kept between the hair and the skin", S::Linear },
    { TimeStep, "time_step", "Time step", "s", G::Solver, K::Real, 1.0 / 1000.0, 1.0 / 10.0, 1.0 / 60.0,
        "Simulated time per step", S::Log },
    { Substeps, "substeps", "Substeps", "per step", G::Solver, K::Integer, 1, 32, 2,
        "Solver iterations per step; more is stiffer and steadier, and slower", S::Log },
    { SimulateAllStrands, "simulate_all_strands", "Simulate all strands", "", G::Solver, K::Toggle, 0, 1, 0,
        "Simulate every strand instead of only the key hair of each wisp (slower, no clumping by wisp)", S::Linear },
    { Body, "body", "Neck and shoulders", "", G::Solver, K::Toggle, 0, 1, 1,
        "Hair collides with a neck and shoulders under the head (capsules sized from the head), and rests on them",
        S::Linear },
} };

static_assert(rowsAreInEnumOrder(kParameters), "kParameters must list the parameters in the order of enum Param");

} // namespace

std::span<const ParameterInfo> allParameters()
{
    return kParameters;
}

SliderRange sliderRangeOf(const ParameterInfo& info)
{
    return { info.minimum, info.maximum, info.slider, info.kind != ParamKind::Real };
}

namespace {

// A range from 0 (or below) cannot be spread by ratio all the way down: below this "soft zero" the
// Log scale is about linear (log(1 + x / knee)); a thousandth of the range keeps three decades.
double logKnee(const SliderRange& r)
{
    return std::max((r.maximum - r.minimum) * 1e-3, 1e-12);
}
// Centred: the same both ways from the middle, with the soft zero at a hundredth of the half range
// (gravity: 1 m/s², so 9.81 sits about half way out).
double centredKnee(const SliderRange& r)
{
    return std::max(0.5 * (r.maximum - r.minimum) * 1e-2, 1e-12);
}

double clampTo(const SliderRange& r, double v)
{
    if (!std::isfinite(v))
        return r.minimum;
    v = std::clamp(v, r.minimum, r.maximum);
    return r.wholeNumbers ? std::clamp(std::round(v), std::ceil(r.minimum), std::floor(r.maximum)) : v;
}

} // namespace

double sliderFractionOf(const SliderRange& r, double value)
{
    if (!(r.maximum > r.minimum) || !std::isfinite(value))
        return 0.0;
    const double v = std::clamp(value, r.minimum, r.maximum);
    double f = 0.0;
    switch (r.scale) {
    case SliderScale::Linear:
        f = (v - r.minimum) / (r.maximum - r.minimum);
        break;
    case SliderScale::Log:
        if (r.minimum > 0.0)
            f = std::log(v / r.minimum) / std::log(r.maximum / r.minimum);
        else {
            const double k = logKnee(r);
            f = std::log1p((v - r.minimum) / k) / std::log1p((r.maximum - r.minimum) / k);
        }
        break;
    case SliderScale::Centred: {
        const double middle = 0.5 * (r.minimum + r.maximum), half = 0.5 * (r.maximum - r.minimum);
        const double k = centredKnee(r);
        const double u = std::log1p(std::abs(v - middle) / k) / std::log1p(half / k); // 0..1 out from the middle
        f = 0.5 + 0.5 * std::copysign(u, v - middle);
        break;
    }
    }
    return std::clamp(f, 0.0, 1.0);
}

double sliderValueAt(const SliderRange& r, double fraction)
{
    const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
    double v = r.minimum;
    switch (r.scale) {
    case SliderScale::Linear:
        v = r.minimum + (r.maximum - r.minimum) * f;
        break;
    case SliderScale::Log:
        if (r.minimum > 0.0)
            v = r.minimum * std::exp(f * std::log(r.maximum / r.minimum));
        else {
            const double k = logKnee(r);
            v = r.minimum + k * std::expm1(f * std::log1p((r.maximum - r.minimum) / k));
        }
        break;
    case SliderScale::Centred: {
        const double middle = 0.5 * (r.minimum + r.maximum), half = 0.5 * (r.maximum - r.minimum);
        const double k = centredKnee(r);
        const double u = 2.0 * f - 1.0;
        v = middle + std::copysign(k * std::expm1(std::abs(u) * std::log1p(half / k)), u);
        break;
    }
    }
    // The ends are exact (exp and log do not quite give them back).
    if (f <= 0.0)
        v = r.minimum;
    else if (f >= 1.0)
        v = r.maximum;
    return clampTo(r, v);
}

double snappedSliderValue(const SliderRange& r, double value)
{
    if (!std::isfinite(value))
        return clampTo(r, value);
    // The 1-2-5 step nearest `about`.
    const auto niceStep = [](double about) {
        const double decade = std::pow(10.0, std::floor(std::log10(about)));
        const double m = about / decade;
        return decade * (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0);
    };
    double step = 0.0;
    if (r.scale == SliderScale::Log) {
        const double magnitude = std::abs(value) > 0.0 ? std::abs(value) : logKnee(r);
        step = niceStep(std::max(magnitude * 0.1, r.minimum > 0.0 ? r.minimum * 0.1 : logKnee(r)));
    } else {
        step = niceStep((r.maximum - r.minimum) / 20.0);
    }
    if (r.wholeNumbers)
        step = std::max(1.0, std::round(step));
    if (!(step > 0.0) || !std::isfinite(step))
        return clampTo(r, value);
    return clampTo(r, std::round(value / step) * step);
}

const ParameterInfo& parameterInfo(Param id)
{
    return kParameters[static_cast<std::size_t>(id)];
}

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
        return std::string(p.key) + ": " + formatNumber(value)
            + (p.kind == ParamKind::Toggle ? " is not 0 or 1" : " is not a whole number");
    if (!isWithinRange(p, value))
        return std::string(p.key) + ": " + formatNumber(value) + " is outside " + formatNumber(p.minimum) + ".."
            + formatNumber(p.maximum);
    return {};
}

std::string checkParameterValues(std::initializer_list<std::pair<Param, double>> values)
{
    for (const auto& [id, value] : values)
        if (std::string error = checkParameterValue(id, value); !error.empty())
            return error;
    return {};
}

SliderRange toolSettingRange(ToolSetting setting)
{
    switch (setting) {
    case ToolSetting::BrushRadius:
        return { kBrushRadiusMinMetres, kBrushRadiusMaxMetres, SliderScale::Log, false };
    case ToolSetting::BrushStrength:
        return { 0.0, 1.0, SliderScale::Linear, false };
    case ToolSetting::BrushFalloff:
        return { 0.0, 1.0, SliderScale::Linear, false };
    case ToolSetting::PermRadius:
        return { 0.0, kStyleMaxCurlRadiusMetres, SliderScale::Log, false };
    case ToolSetting::PermTurns:
        return { 0.0, kStyleMaxCurlTurnsPerMetre, SliderScale::Log, false };
    }
    return {};
}

double clampToToolSetting(ToolSetting setting, double value)
{
    const SliderRange range = toolSettingRange(setting);
    return std::clamp(value, range.minimum, range.maximum);
}

std::string checkToolSetting(ToolSetting setting, double value, std::string_view what)
{
    const SliderRange range = toolSettingRange(setting);
    std::ostringstream message;
    message << what << ": " << value;
    if (!std::isfinite(value))
        return message.str() + " is not a finite number";
    if (value < range.minimum || value > range.maximum) {
        message << " is outside " << range.minimum << ".." << range.maximum;
        return message.str();
    }
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

} // namespace wisp
