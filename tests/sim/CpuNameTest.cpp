#include "sim/util/CpuName.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

// The CPU's name as its maker gives it: what the bench and the About box print beside their figures.
TEST(CpuName, IsTheMakersNameWithItsSpacesTidied)
{
    const std::string name = wisp::cpuModelName();
    ASSERT_FALSE(name.empty());
    EXPECT_NE(name.front(), ' ') << name;
    EXPECT_NE(name.back(), ' ') << name;
    EXPECT_EQ(name.find("  "), std::string::npos) << name;
    EXPECT_EQ(name.find('\0'), std::string::npos);
    // Where Linux names the CPU too, it is the same name (the kernel reads the same brand string;
    // it keeps a brand string's inner runs of spaces, which the name here makes one).
    std::ifstream info("/proc/cpuinfo");
    std::string line;
    while (std::getline(info, line)) {
        if (line.rfind("model name", 0) != 0)
            continue;
        std::string model;
        for (char c : line.substr(line.find(':') + 1))
            if (c != ' ' || (!model.empty() && model.back() != ' '))
                model += c;
        while (!model.empty() && model.back() == ' ')
            model.pop_back();
        EXPECT_EQ(name, model);
        break;
    }
}
