#include "sim/params/MotionSettings.h"

#include "sim/params/TableOrder.h"
#include "sim/util/NumberText.h"

#include <array>
#include <cmath>
#include <cstddef>

namespace wisp {

namespace {

constexpr std::array<MotionSettingInfo, 5> kMotionSettings{ {
    { MotionSetting::TurnAmplitude, "degrees", 0.0, 90.0,
        "How far the head turns each way (turn, shake) or tilts (nod), degrees" },
    { MotionSetting::WalkAmplitude, "m", 0.0, 0.2,
        "How far the head bobs up when walking, metres (it sways half that)" },
    { MotionSetting::Frequency, "Hz", 0.01, 10.0, "Cycles per second (strides, for walk)" },
    { MotionSetting::Time, "s", -1.0e6, 1.0e6, "A key's time, or when a motion starts, seconds" },
    { MotionSetting::Translation, "m", -100.0, 100.0, "How far a key moves the head, each axis, metres" },
} };

static_assert(
    rowsAreInEnumOrder(kMotionSettings), "kMotionSettings must list the settings in the order of MotionSetting");

} // namespace

const MotionSettingInfo& motionSettingInfo(MotionSetting setting)
{
    return kMotionSettings[static_cast<std::size_t>(setting)];
}

std::string checkMotionSetting(MotionSetting setting, double value)
{
    const MotionSettingInfo& info = motionSettingInfo(setting);
    if (!std::isfinite(value))
        return formatNumber(value) + " is not a finite number";
    if (value < info.minimum || value > info.maximum)
        return formatNumber(value) + " is outside " + formatNumber(info.minimum) + ".." + formatNumber(info.maximum)
            + " " + std::string(info.unit);
    return {};
}

} // namespace wisp
