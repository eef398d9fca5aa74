#include "sim/Parameters.h"

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
    EXPECT_TRUE(v.set(Param::Gravity, -2.8).empty());  // negative gravity is allowed: hair floats
    EXPECT_DOUBLE_EQ(v.get(Param::Gravity), -2.8);
}

TEST(Parameters, IntegerParametersAreRounded)
{
    ParameterValues v;
    EXPECT_TRUE(v.set(Param::WispSize, 7.6).empty());
    EXPECT_EQ(v.getInt(Param::WispSize), 8);
}
