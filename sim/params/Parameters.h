#pragma once
// The one definition of every artist-facing parameter: key, label, unit, range, default, help.
// Panels build their sliders from this table, preset files use its keys, and wisp-cli turns each
// entry into a --key option. Nothing else in the program states a parameter's range or default.

#include <array>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>

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
    HairThickness,
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
    GlobalShape,
    Friction,
    Volume,
    HairFriction,
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

// How a slider spreads a parameter's range along its travel (the spin box always gives the exact
// value). Linear: evenly. Log: by ratio, so 1 -> 2 is as far as 100 -> 200 (a range over decades,
// such as wisp size or wind speed; a range from 0 gets a soft zero, see sliderValueAt). Centred:
// logarithmic both ways from the middle of a symmetric range, so values near the middle (gravity
// near 0 and 9.81) get most of the travel and the extremes stay reachable.
enum class SliderScale { Linear, Log, Centred };

struct ParameterInfo {
    Param id;
    std::string_view key; // snake_case; preset files and CLI options (--key) use it
    std::string_view label; // shown in panels
    std::string_view unit; // "m/s²", "m", "" for a plain number
    ParamGroup group;
    ParamKind kind;
    double minimum;
    double maximum;
    double defaultValue;
    std::string_view help; // one line, shown as the tooltip and in --help
    SliderScale slider = SliderScale::Linear;
    // How panels show it, when not in `unit`: a panel shows value × displayScale in displayUnit
    // (hair thickness: µm, 1e6). Files and the CLI keep `unit`.
    std::string_view displayUnit = {};
    double displayScale = 1.0;
};

// A slider's range and how it spreads it (parameters, and the tools' own settings: brush, perm).
struct SliderRange {
    double minimum = 0.0;
    double maximum = 1.0;
    SliderScale scale = SliderScale::Linear;
    bool wholeNumbers = false; // integer parameters: values are rounded
};
SliderRange sliderRangeOf(const ParameterInfo& info);

// The slider's fraction of travel (0..1) that shows `value`, and the value at a fraction; inverse
// to each other within rounding (whole numbers) and clamped to the range.
double sliderFractionOf(const SliderRange& range, double value);
double sliderValueAt(const SliderRange& range, double fraction);
// Ctrl-drag snapping: the nearest "round" value, 1, 2 or 5 times a power of ten, on a grid of about
// 1/20 of the range (Linear, Centred) or of about a tenth of the value (Log); clamped to the range.
double snappedSliderValue(const SliderRange& range, double value);

// The tools' own settings, which are not document parameters (no preset key, no CLI option, no
// undo): their ranges and slider scales, in SI units, stated here beside the parameters'. The
// limits themselves are ScalpBrush.h's and StyleEdits.h's, which check them.
enum class ToolSetting { BrushRadius, BrushStrength, BrushFalloff, PermRadius, PermTurns };
SliderRange toolSettingRange(ToolSetting setting);
// `value` clamped to the setting's range (what the tools keep when given more or less).
double clampToToolSetting(ToolSetting setting, double value);
// Empty when `value` is finite and inside the setting's range; otherwise "<what>: <value> is
// outside <min>..<max>" (or "is not a finite number").
[[nodiscard]] std::string checkToolSetting(ToolSetting setting, double value, std::string_view what);

constexpr std::size_t kParamCount = static_cast<std::size_t>(Param::Count);

std::span<const ParameterInfo> allParameters();
const ParameterInfo& parameterInfo(Param id);
const ParameterInfo* findParameter(std::string_view key); // nullptr if no such key

// Whether a finite value lies in the parameter's range. Real parameters are held as floats, so
// they are compared as floats: both range ends, as written, are inside.
bool isWithinRange(const ParameterInfo& info, double value);

// Empty when value is acceptable for the parameter; otherwise a message such as
// "clump_degree: 3 is outside -1..1", "gravity: nan is not a finite number", "substeps: 2.5 is not
// a whole number" (integer parameters) or "simulate_all_strands: 0.5 is not 0 or 1" (toggles).
[[nodiscard]] std::string checkParameterValue(Param id, double value);

// The first refusal among (parameter, value) pairs, or empty when every value is acceptable.
[[nodiscard]] std::string checkParameterValues(std::initializer_list<std::pair<Param, double>> values);

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

} // namespace wisp
