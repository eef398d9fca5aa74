#include "sim/util/CpuName.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

// A brand string is padded (spaces before, NULs after, runs of spaces inside on older CPUs).
TEST(CpuName, TidiesABrandStringsSpaces)
{
    EXPECT_EQ(wisp::collapsedSpaces(std::string("  Intel(R) Core(TM)2 Duo CPU     E8400  @ 3.00GHz\0\0junk", 54)),
        "Intel(R) Core(TM)2 Duo CPU E8400 @ 3.00GHz");
    EXPECT_EQ(wisp::collapsedSpaces("AMD\tEPYC 7B13 \t"), "AMD EPYC 7B13");
    EXPECT_EQ(wisp::collapsedSpaces("   "), "");
    EXPECT_EQ(wisp::collapsedSpaces(""), "");
}

// What /proc/cpuinfo calls the CPU where CPUID cannot say (ARM, MIPS ...): the first named line.
TEST(CpuName, ReadsTheCpusNameFromCpuinfo)
{
    EXPECT_EQ(wisp::cpuModelFromCpuinfo("processor\t: 0\nvendor_id\t: GenuineIntel\nmodel\t\t: 106\n"
                                        "model name\t: Intel(R) Xeon(R) Processor @ 2.80GHz\nflags\t\t: fpu sse\n"
                                        "processor\t: 1\nmodel name\t: something else\n"),
        "Intel(R) Xeon(R) Processor @ 2.80GHz");
    // A Raspberry Pi names its board; an empty value is passed over for the next.
    EXPECT_EQ(wisp::cpuModelFromCpuinfo("processor\t: 0\nBogoMIPS\t: 108.00\nHardware\t:\n"
                                        "Model\t\t: Raspberry Pi 4 Model B Rev 1.4\n"),
        "Raspberry Pi 4 Model B Rev 1.4");
    EXPECT_EQ(wisp::cpuModelFromCpuinfo("cpu model\t\t: MIPS 24Kc V7.4\n"), "MIPS 24Kc V7.4");
    // (An "model" line is the family's number, not a name; a line without a colon is skipped.)
    EXPECT_EQ(wisp::cpuModelFromCpuinfo("model\t\t: 106\nno colon here\nCPU part\t: 0xd08\n"), "");
    EXPECT_EQ(wisp::cpuModelFromCpuinfo(""), "");
}

// This machine's: tidy, and where Linux names the CPU, that name (the kernel reads the same brand
// string on x86).
TEST(CpuName, IsThisMachinesNameAsItsMakerGivesIt)
{
    const std::string name = wisp::cpuModelName();
    ASSERT_FALSE(name.empty());
    EXPECT_EQ(name, wisp::collapsedSpaces(name));
    std::ifstream info("/proc/cpuinfo");
    std::ostringstream text;
    text << info.rdbuf();
    const std::string fromLinux = wisp::cpuModelFromCpuinfo(text.str());
    if (!fromLinux.empty())
        EXPECT_EQ(name, fromLinux);
    else
        EXPECT_EQ(name, "unknown CPU");
}
