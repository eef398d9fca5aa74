#pragma once
// Part of the parameter registry (sim/params): the ranges of the head motion's settings.
// Thread safety: any thread; constant data.

#include <string>
#include <string_view>

namespace wisp {

// The head motion's settings (sim/motion/HeadMotion.h: a procedural motion's amplitude and
// frequency, a key's time and translation), beside the parameters in the registry
// (Parameters.h): not document parameters (no preset key or CLI --key of their own, no slider), but
// artist-facing, so their ranges are stated here once. The Motion panel's spin boxes,
// HeadMotion::validate, the project and preset readers and wisp-cli bake read them.
enum class MotionSetting { TurnAmplitude, WalkAmplitude, Frequency, Time, Translation };
struct MotionSettingInfo {
    MotionSetting id;
    std::string_view unit; // "degrees", "m", "Hz", "s"
    double minimum;
    double maximum;
    std::string_view help; // one line, the panel's tooltip
};
const MotionSettingInfo& motionSettingInfo(MotionSetting setting);
// Empty when `value` is finite and inside the setting's range; otherwise what is wrong with it,
// for the caller to prefix with the field: "120 is outside 0..90 degrees", "nan is not a finite
// number".
[[nodiscard]] std::string checkMotionSetting(MotionSetting setting, double value);

} // namespace wisp
