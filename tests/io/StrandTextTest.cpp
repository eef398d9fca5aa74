// wisp-strands text (io/StrandText): a strand's point count that is negative or past the header's
// total is refused with its line, before anything is allocated for it.

#include "io/StrandText.h"
#include "IoTestSupport.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

using namespace wisp;
using namespace wisp::io;

namespace {

Result<HairCurves> readText(const std::string& text)
{
    const auto path = test::freshTestFolder("wisp-strandtext") / "strands.txt";
    std::ofstream(path, std::ios::binary) << text;
    return readStrandText(path.string());
}

TEST(StrandText, ReadsWhatTheHeaderPromises)
{
    const Result<HairCurves> read = readText("wisp-strands 1\nstrands 2 points 3\n2 0 0 0 0 0.1 0\n1 0.5 0 0\n");
    ASSERT_TRUE(read) << read.error().toString();
    ASSERT_EQ(read.value().strandCount(), 2u);
    EXPECT_EQ(read.value().pointsIn(0), 2u);
    EXPECT_FLOAT_EQ(read.value().positions[2].x, 0.5f);
}

// "-2" reads as 2^64 - 2 into an unsigned count, and the check `points so far + n > total` wrapped
// around and passed: the reader then asked for 4 billion points (48 GB). Found by fuzz/fuzz_hair.
TEST(StrandText, RefusesANegativeOrOversizedPointCount)
{
    for (const char* count : { "-2", "-1", "18446744073709551615", "3" }) {
        const Result<HairCurves> read
            = readText(std::string("wisp-strands 1\nstrands 2 points 4\n2 0 0 0 0 0.1 0\n") + count + " 0 0 0 0 0 0\n");
        ASSERT_FALSE(read) << count;
        EXPECT_EQ(read.error().location, "line 4") << count;
        EXPECT_NE(read.error().message.find("point count"), std::string::npos) << read.error().toString();
    }
}

// Found by fuzz_hair in CI: a header on the last line, with no newline after it, left the stream
// at its end, its size read as the largest number, and a claim of a trillion points was reserved.
TEST(StrandText, AHeaderWithoutANewlineCannotClaimMorePointsThanTheFileHolds)
{
    for (const char* text :
        { "wisp-strands 1\nstrands 1 points 1000000000000", "wisp-strands 1\nstrands 1 points 1000000000000\n" }) {
        const Result<HairCurves> read = readText(text);
        ASSERT_FALSE(read);
        EXPECT_EQ(read.error().location, "line 2");
        EXPECT_NE(read.error().message.find("more than a file of"), std::string::npos) << read.error().toString();
    }
}

} // namespace
