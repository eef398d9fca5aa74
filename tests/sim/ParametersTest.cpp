#include "sim/params/Parameters.h"
#include "sim/groom/Groom.h"
#include "sim/solver/SolverSettings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace wisp;

TEST(Parameters, EveryEntryIsCompleteAndConsistent)
{
    std::set<std::string_view> keys;
    for (const ParameterInfo& p : allParameters()) {
        EXPECT_FALSE(p.key.empty());
        EXPECT_FALSE(p.label.empty()) << p.key;
        EXPECT_FALSE(p.help.empty()) << p.key;
        EXPECT_LT(p.minimum, p.maximum) << p.key;
        EXPECT_GE(p.defaultValue, p.minimum) << p.key;
        EXPECT_LE(p.defaultValue, p.maximum) << p.key;
        EXPECT_TRUE(keys.insert(p.key).second) << "duplicate key " << p.key;
        EXPECT_EQ(findParameter(p.key), &p);
    }
    EXPECT_EQ(keys.size(), kParamCount);
    EXPECT_EQ(findParameter("no_such_thing"), nullptr);
}

TEST(Parameters, RefusesOutOfRangeAndNonFiniteValuesNamingTheKey)
{
    ParameterValues v;
    EXPECT_EQ(v.set(Param::ClumpDegree, 3.0), "clump_degree: 3 is outside -1..1");
    EXPECT_DOUBLE_EQ(v.get(Param::ClumpDegree), parameterInfo(Param::ClumpDegree).defaultValue);
    EXPECT_EQ(v.set(Param::Gravity, std::nan("")), "gravity: nan is not a finite number");
    EXPECT_EQ(v.set(Param::Gravity, INFINITY), "gravity: inf is not a finite number");
    EXPECT_EQ(v.set(Param::Segments, 1), "segments: 1 is outside 2..127");
    EXPECT_EQ(v.set(Param::Segments, 0), "segments: 0 is outside 2..127");
    EXPECT_TRUE(v.set(Param::Gravity, -2.8).empty()); // negative gravity is allowed: hair floats
    EXPECT_DOUBLE_EQ(v.get(Param::Gravity), -2.8);
}

TEST(Parameters, IntegerAndToggleParametersRefuseFractionsNamingThem)
{
    ParameterValues v;
    EXPECT_EQ(v.set(Param::Substeps, 2.5), "substeps: 2.5 is not a whole number");
    EXPECT_EQ(v.getInt(Param::Substeps), 2); // kept
    EXPECT_EQ(v.set(Param::WispSize, 7.6), "wisp_size: 7.6 is not a whole number");
    EXPECT_EQ(v.set(Param::SimulateAllStrands, 0.5), "simulate_all_strands: 0.5 is not 0 or 1");
    EXPECT_EQ(v.set(Param::Body, 2), "body: 2 is outside 0..1");
    EXPECT_TRUE(v.set(Param::WispSize, 8.0).empty());
    EXPECT_EQ(v.getInt(Param::WispSize), 8);
    EXPECT_TRUE(v.set(Param::Body, 0).empty());
}

// Real parameters are held as floats: each documented range end, as written and as the float the
// program holds (0.1f is a little more than the double 0.1), is accepted; one float step beyond is not.
TEST(Parameters, EveryRangeEndIsAcceptedAsWrittenAndAsAFloat)
{
    for (const ParameterInfo& p : allParameters()) {
        for (double end : { p.minimum, p.maximum }) {
            EXPECT_EQ(checkParameterValue(p.id, end), "") << p.key << " " << end;
            if (p.kind == ParamKind::Real) {
                EXPECT_EQ(checkParameterValue(p.id, static_cast<double>(static_cast<float>(end))), "") << p.key;
            }
        }
        if (p.kind == ParamKind::Real) {
            const float above = std::nextafter(static_cast<float>(p.maximum), INFINITY);
            const float below = std::nextafter(static_cast<float>(p.minimum), -INFINITY);
            EXPECT_NE(checkParameterValue(p.id, above), "") << p.key;
            EXPECT_NE(checkParameterValue(p.id, below), "") << p.key;
        }
    }
    EXPECT_GT(static_cast<double>(0.1f), 0.1); // why: the time step's upper end
    EXPECT_EQ(checkParameterValue(Param::TimeStep, static_cast<double>(0.1f)), "");
    EXPECT_EQ(checkParameterValue(Param::CurlRadius, static_cast<double>(0.05f)), "");
    EXPECT_EQ(checkParameterValue(Param::Length, static_cast<double>(0.005f)), "");
}

// The solver's and the groom's own checks take the floats they hold: the range ends pass there too.
TEST(Parameters, SolverAndGroomSettingsAcceptTheRangeEnds)
{
    ParameterValues v;
    for (Param id : { Param::TimeStep, Param::Drag, Param::Damping, Param::Stiffness, Param::Friction,
             Param::HairOffset, Param::Turbulence, Param::Substeps }) {
        for (double end : { parameterInfo(id).minimum, parameterInfo(id).maximum }) {
            ParameterValues w = v;
            ASSERT_EQ(w.set(id, end), "");
            EXPECT_EQ(validateSolverSettings(solverSettingsFrom(w)), "") << parameterInfo(id).key << " " << end;
        }
    }
    for (Param id : { Param::Density, Param::WispSize, Param::ClumpDegree, Param::ClumpRate, Param::Length,
             Param::LengthVariation, Param::Segments, Param::CurlRadius, Param::CurlTurns, Param::HairOffset }) {
        for (double end : { parameterInfo(id).minimum, parameterInfo(id).maximum }) {
            ParameterValues w = v;
            ASSERT_EQ(w.set(id, end), "");
            EXPECT_EQ(validateGroomSettings(groomSettingsFrom(w)), "") << parameterInfo(id).key << " " << end;
        }
    }
}

TEST(Parameters, SliderScalesRoundTripAndMapTheEndsToTheEnds)
{
    for (const ParameterInfo& p : allParameters()) {
        if (p.kind == ParamKind::Toggle)
            continue;
        const SliderRange r = sliderRangeOf(p);
        EXPECT_EQ(sliderValueAt(r, 0.0), p.minimum) << p.key;
        EXPECT_EQ(sliderValueAt(r, 1.0), p.maximum) << p.key;
        EXPECT_DOUBLE_EQ(sliderFractionOf(r, p.minimum), 0.0) << p.key;
        EXPECT_DOUBLE_EQ(sliderFractionOf(r, p.maximum), 1.0) << p.key;
        const double f = sliderFractionOf(r, p.defaultValue);
        EXPECT_GE(f, 0.0) << p.key;
        EXPECT_LE(f, 1.0) << p.key;
        const double back = sliderValueAt(r, f);
        EXPECT_NEAR(back, p.defaultValue, p.kind == ParamKind::Real ? 1e-9 * (p.maximum - p.minimum) : 0.5) << p.key;
        // Monotonic: more travel, never less value.
        double last = sliderValueAt(r, 0.0);
        for (int i = 1; i <= 100; ++i) {
            const double v = sliderValueAt(r, i / 100.0);
            EXPECT_GE(v, last) << p.key << " at " << i;
            last = v;
        }
    }
}

TEST(Parameters, GravityIsCentredAndWispSizeLogarithmic)
{
    const SliderRange gravity = sliderRangeOf(parameterInfo(Param::Gravity));
    EXPECT_EQ(gravity.scale, SliderScale::Centred);
    EXPECT_DOUBLE_EQ(sliderFractionOf(gravity, 0.0), 0.5);
    EXPECT_NEAR(sliderFractionOf(gravity, -9.81), 1.0 - sliderFractionOf(gravity, 9.81), 1e-12);
    // Earth's gravity about half way out from the middle: the everyday values get most of the travel.
    EXPECT_GT(sliderFractionOf(gravity, 9.81), 0.70);
    EXPECT_LT(sliderFractionOf(gravity, 9.81), 0.80);
    // 4 % of the travel (24 pixels of a 600-pixel drag) from 9.81 m/s² moves it by less than 5.
    EXPECT_NEAR(sliderValueAt(gravity, sliderFractionOf(gravity, 9.81) - 0.04), 9.81, 5.0);

    const SliderRange size = sliderRangeOf(parameterInfo(Param::WispSize));
    EXPECT_EQ(size.scale, SliderScale::Log);
    EXPECT_NEAR(sliderFractionOf(size, 32.0), 0.5, 1e-12); // 1..1024: the middle is sqrt(1024)
    EXPECT_EQ(sliderValueAt(size, 0.5), 32.0);
    // A range from 0 has a soft zero: wind 0..100 m/s puts 1.5 m/s well inside the travel.
    const SliderRange wind = sliderRangeOf(parameterInfo(Param::WindSpeed));
    EXPECT_GT(sliderFractionOf(wind, 1.5), 0.3);
    EXPECT_LT(sliderFractionOf(wind, 1.5), 0.5);
    EXPECT_EQ(sliderValueAt(wind, 0.0), 0.0);
}

TEST(Parameters, CtrlSnapGoesToRoundValuesInsideTheRange)
{
    const SliderRange gravity = sliderRangeOf(parameterInfo(Param::Gravity));
    EXPECT_DOUBLE_EQ(snappedSliderValue(gravity, 9.81), 10.0);
    EXPECT_DOUBLE_EQ(snappedSliderValue(gravity, -3.2), 0.0);
    EXPECT_DOUBLE_EQ(snappedSliderValue(gravity, 99.0), 100.0);
    const SliderRange size = sliderRangeOf(parameterInfo(Param::WispSize));
    EXPECT_DOUBLE_EQ(snappedSliderValue(size, 19.0), 20.0);
    EXPECT_DOUBLE_EQ(snappedSliderValue(size, 12.0), 12.0);
    EXPECT_DOUBLE_EQ(snappedSliderValue(size, 1.4), 1.0);
    const SliderRange length = sliderRangeOf(parameterInfo(Param::Length));
    EXPECT_NEAR(snappedSliderValue(length, 0.283), 0.28, 1e-12);
    EXPECT_NEAR(snappedSliderValue(length, 1.93), 2.0, 1e-12);
    EXPECT_EQ(snappedSliderValue(length, 1.99), 2.0);
    const SliderRange radius = toolSettingRange(ToolSetting::BrushRadius);
    EXPECT_EQ(radius.scale, SliderScale::Log);
    EXPECT_GE(snappedSliderValue(radius, 0.0001), radius.minimum);
}

TEST(Parameters, ToolSettingsAreClampedAndCheckedAgainstTheirOneRange)
{
    // The brush radius's range is ScalpBrush.h's limits, 0.0005..0.5 m.
    EXPECT_DOUBLE_EQ(clampToToolSetting(ToolSetting::BrushRadius, 3.0), 0.5);
    EXPECT_NEAR(clampToToolSetting(ToolSetting::BrushRadius, 0.0), 0.0005, 1e-9);
    EXPECT_DOUBLE_EQ(clampToToolSetting(ToolSetting::BrushStrength, 0.25), 0.25);
    EXPECT_DOUBLE_EQ(clampToToolSetting(ToolSetting::PermTurns, 500.0), 200.0);
    EXPECT_EQ(checkToolSetting(ToolSetting::PermRadius, 0.01, "--curl-radius"), "");
    EXPECT_EQ(checkToolSetting(ToolSetting::PermRadius, 0.2, "--curl-radius"), "--curl-radius: 0.2 is outside 0..0.05");
    EXPECT_EQ(
        checkToolSetting(ToolSetting::BrushFalloff, std::nan(""), "falloff"), "falloff: nan is not a finite number");
}
