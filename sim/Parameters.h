#pragma once
// The one definition of every artist-facing parameter: key, label, unit, range, default, help.
// Panels build their sliders from this table, preset files use its keys, and wisp-cli turns each
// entry into a --key option. Nothing else in the program states a parameter's range or default.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <utility>
#include <span>
#include <string>
#include <string_view>

namespace wisp {

enum class Param : int {
    // Wisp: per growth region (Lee et al.: pore density, wisp size, clump-degree, clump-rate; plus
    // length, curl and a stiffness scale)
    Density,
    WispSize,
    ClumpDegree,
    ClumpRate,
    Length,
    LengthVariation,
    Segments,
    CurlRadius,
    CurlTurns,
    StiffnessScale,
    // Groom: the whole groom
    Seed,
    // Forces
    Gravity,
    WindSpeed,
    WindAzimuth,
    WindElevation,
    Turbulence,
    Drag,
    Damping,
    DryingTime,
    // Hair material and solver
    Stiffness,
    Friction,
    HairOffset,
    TimeStep,
    Substeps,
    SimulateAllStrands,
    Body,
    Count
};

// Wisp: a growth region's own (GrowthRegion.h); Groom: shared by every region's groom (segments,
// seed, hair offset); Forces and Solver: the simulation's.
enum class ParamGroup { Wisp, Groom, Forces, Solver };
enum class ParamKind { Real, Integer, Toggle };

struct ParameterInfo {
    Param id;
    std::string_view key;    // snake_case; preset files and CLI options (--key) use it
    std::string_view label;  // shown in panels
    std::string_view unit;   // "m/s²", "m", "" for a plain number
    ParamGroup group;
    ParamKind kind;
    double minimum;
    double maximum;
    double defaultValue;
    std::string_view help;  // one line, shown as the tooltip and in --help
};

constexpr std::size_t kParamCount = static_cast<std::size_t>(Param::Count);

std::span<const ParameterInfo> allParameters();
const ParameterInfo& parameterInfo(Param id);
const ParameterInfo* findParameter(std::string_view key);  // nullptr if no such key

// Whether a finite value lies in the parameter's range. Real parameters are held as floats, so
// they are compared as floats: both range ends, as written, are inside.
bool isWithinRange(const ParameterInfo& info, double value);

// Empty when value is acceptable for the parameter; otherwise a message such as
// "clump_degree: 3 is outside -1..1", "gravity: nan is not a finite number", "substeps: 2.5 is not
// a whole number" (integer parameters) or "simulate_all_strands: 0.5 is not 0 or 1" (toggles).
std::string checkParameterValue(Param id, double value);

// The first refusal among (parameter, value) pairs, or empty when every value is acceptable.
std::string checkParameterValues(std::initializer_list<std::pair<Param, double>> values);

// One value for every parameter, starting at the registry's defaults.
class ParameterValues {
public:
    ParameterValues();
    double get(Param id) const { return m_values[static_cast<std::size_t>(id)]; }
    float getFloat(Param id) const { return static_cast<float>(get(id)); }
    int getInt(Param id) const { return static_cast<int>(get(id)); }
    // Refuses (returns the message, keeps the old value) what checkParameterValue refuses: a
    // non-finite or out-of-range value, or a fraction for an integer or toggle parameter.
    std::string set(Param id, double value);
    bool operator==(const ParameterValues&) const = default;

private:
    std::array<double, kParamCount> m_values{};
};

}  // namespace wisp
