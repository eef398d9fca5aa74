// Hair files: refusals of broken files, and writes that fail leave no file.
#include "HairFilesTestSupport.h"

using namespace wisp;
using namespace wisp::io;
using namespace wisp::test::hair;

// ---- refusals -------------------------------------------------------------------------------------

TEST_F(HairFiles, CyHairClaimingMorePointsThanItHoldsIsRefused)
{
    REQUIRE_ASSET(kBangsHair);
    const std::string bytes = slurp(kBangsHair);
    // Cut after 300 points: 128 + 2 x 100 + 12 x 300 = 3928 bytes.
    const fs::path cut = dir / "ct2hair_bangs100.hair";
    spit(cut, bytes.substr(0, 3928));
    EXPECT_EQ(cut.string() + ": byte 3928: the header claims 1165 points but the file holds only 300", errorText(cut));

    // A header claiming four billion points in a 14 KB file: refused by its size, at once.
    std::string huge = bytes;
    putU32(huge, 8, 0xffffffffu);
    spit(dir / "huge.hair", huge);
    // "At once" is shown by the message, not a stopwatch: it compares the header's claim with the
    // file's size, so nothing was allocated or read for the claimed points (under ASan a 4-billion-point
    // allocation would abort the test).
    const std::string message = errorText(dir / "huge.hair");
    EXPECT_NE(std::string::npos, message.find("huge.hair")) << message;
    EXPECT_NE(std::string::npos, message.find("4294967295 points but the file holds only 1165")) << message;

    // Four billion strands: the segments array cannot fit.
    std::string strands = bytes;
    putU32(strands, 4, 0xfffffff0u);
    putU32(strands, 8, 0xfffffff0u);
    spit(dir / "strands.hair", strands);
    EXPECT_NE(std::string::npos,
        errorText(dir / "strands.hair").find("4294967280 strands but the file holds segment counts for only"));

    // Segment counts that do not add up to the point count.
    std::string sum = bytes;
    sum[128] = static_cast<char>(sum[128] + 1);
    spit(dir / "sum.hair", sum);
    EXPECT_NE(std::string::npos,
        errorText(dir / "sum.hair").find("segment counts add up to 1166 points but the header claims 1165"));

    // Zero counts, no points array, not a cyHair file.
    std::string zero = bytes;
    putU32(zero, 4, 0);
    spit(dir / "zero.hair", zero);
    EXPECT_NE(std::string::npos, errorText(dir / "zero.hair").find("no strands"));
    std::string noPoints = bytes;
    putU32(noPoints, 12, 0x1);
    spit(dir / "nopoints.hair", noPoints);
    EXPECT_NE(std::string::npos, errorText(dir / "nopoints.hair").find("no points array"));
    std::string notHair = bytes;
    notHair[0] = 'X';
    spit(dir / "nothair.hair", notHair);
    EXPECT_NE(std::string::npos, errorText(dir / "nothair.hair").find("not a cyHair file"));
}

TEST_F(HairFiles, CyHairExtraArraysAreSkippedButTheirSizesChecked)
{
    REQUIRE_ASSET(kBangsHair);
    const HairCurves bangs = readOk(kBangsHair);
    std::string bytes = slurp(kBangsHair);
    putU32(bytes, 12, 0x3 | 0x4 | 0x10); // + thickness, colour
    const std::string full = bytes + std::string(1165 * 4 + 1165 * 12, '\0');
    spit(dir / "extras.hair", full);
    Result<HairReadResult> r = readHair((dir / "extras.hair").string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    expectBitIdentical(bangs, r.value().strands);
    ASSERT_EQ(1u, r.value().warnings.size());
    EXPECT_NE(std::string::npos, r.value().warnings[0].find("thickness and colour")) << r.value().warnings[0];

    spit(dir / "short.hair", full.substr(0, full.size() - 1));
    EXPECT_NE(std::string::npos, errorText(dir / "short.hair").find("thickness, colour arrays"));
}

TEST_F(HairFiles, CyHairWithoutSegmentsArrayUsesTheDefault)
{
    std::string bytes(128, '\0');
    std::memcpy(bytes.data(), "HAIR", 4);
    putU32(bytes, 4, 2); // strands
    putU32(bytes, 8, 8); // points
    putU32(bytes, 12, 0x2); // points only
    putU32(bytes, 16, 3); // default segments
    for (int i = 0; i < 24; ++i)
        appendF32(bytes, float(i));
    spit(dir / "default.hair", bytes);
    const HairCurves c = readOk(dir / "default.hair");
    ASSERT_EQ(2u, c.strandCount());
    EXPECT_EQ(4u, c.pointsIn(1));
    EXPECT_EQ(glm::vec3(12, 13, 14), c.positions[4]);

    putU32(bytes, 16, 2);
    spit(dir / "mismatch.hair", bytes);
    EXPECT_NE(
        std::string::npos, errorText(dir / "mismatch.hair").find("2 strands of 2 segments (6 points) but 8 points"));
}

TEST_F(HairFiles, UscDataClaimingTwoBillionStrandsIsRefusedAtOnce)
{
    std::string tiny;
    appendI32(tiny, std::numeric_limits<std::int32_t>::max());
    appendI32(tiny, 2);
    appendF32(tiny, 0.0f);
    spit(dir / "tiny.data", tiny);
    // Refused from the header and the file's size (the message says so), before any allocation.
    const std::string message = errorText(dir / "tiny.data");
    EXPECT_EQ((dir / "tiny.data").string()
            + ": byte 0: the header claims 2147483647 strands but the 12-byte file can hold at most 2",
        message);

    // One strand claiming a billion points.
    std::string greedy;
    appendI32(greedy, 1);
    appendI32(greedy, 1'000'000'000);
    for (int i = 0; i < 6; ++i)
        appendF32(greedy, 1.0f);
    spit(dir / "greedy.data", greedy);
    EXPECT_EQ(
        (dir / "greedy.data").string() + ": byte 4: strand 0 claims 1000000000 points but the file holds only 2 more",
        errorText(dir / "greedy.data"));

    std::string negative;
    appendI32(negative, -5);
    spit(dir / "negative.data", negative);
    EXPECT_NE(std::string::npos, errorText(dir / "negative.data").find("negative (-5)"));
    std::string negativePoints;
    appendI32(negativePoints, 1);
    appendI32(negativePoints, -2);
    spit(dir / "negpoints.data", negativePoints);
    EXPECT_NE(std::string::npos, errorText(dir / "negpoints.data").find("strand 0 claims a negative point count (-2)"));
}

TEST_F(HairFiles, UscSinglePointStrandsAreSkippedWithAWarning)
{
    std::string bytes;
    appendI32(bytes, 4);
    const int counts[] = { 1, 3, 1, 2 };
    for (int n : counts) {
        appendI32(bytes, n);
        for (int i = 0; i < 3 * n; ++i)
            appendF32(bytes, float(n * 10 + i));
    }
    bytes += "junk";
    spit(dir / "single.data", bytes);
    Result<HairReadResult> r = readHair((dir / "single.data").string());
    ASSERT_TRUE(r.ok()) << r.error().toString();
    EXPECT_EQ(2u, r.value().strands.strandCount());
    EXPECT_EQ(5u, r.value().strands.pointCount());
    EXPECT_EQ(glm::vec3(20, 21, 22), r.value().strands.positions[3]);
    ASSERT_EQ(2u, r.value().warnings.size());
    EXPECT_EQ("skipped 2 strands of fewer than two points (strands 0, 2)", r.value().warnings[0]);
    EXPECT_NE(std::string::npos, r.value().warnings[1].find("4 bytes after the last strand"));

    std::string onlySingles;
    appendI32(onlySingles, 1);
    appendI32(onlySingles, 1);
    for (int i = 0; i < 3; ++i)
        appendF32(onlySingles, 0.0f);
    spit(dir / "singles.data", onlySingles);
    EXPECT_NE(std::string::npos, errorText(dir / "singles.data").find("no strands of two or more points"));
}

TEST_F(HairFiles, NonFinitePointIsRefusedWithItsIndex)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    const HairCurves bangs = readOk(kBangsHair);
    std::size_t strand17 = 0;
    while (bangs.offsets[strand17 + 1] <= 17)
        ++strand17;

    std::string hair = slurp(kBangsHair);
    const std::size_t hairAt = 128 + 200 + 17 * 12 + 4;
    putF32(hair, hairAt, std::numeric_limits<float>::quiet_NaN());
    spit(dir / "nan.hair", hair);
    EXPECT_EQ((dir / "nan.hair").string() + ": byte " + std::to_string(hairAt - 4) + ": point 17 (strand "
            + std::to_string(strand17) + ") is not finite",
        errorText(dir / "nan.hair"));

    // In the .data file point 17 sits after one point count per strand up to its own.
    std::string data = slurp(kBangsData);
    const std::size_t dataAt = 4 + 4 * (strand17 + 1) + 17 * 12 + 8;
    putF32(data, dataAt, std::numeric_limits<float>::infinity());
    spit(dir / "inf.data", data);
    EXPECT_NE(std::string::npos,
        errorText(dir / "inf.data").find("point 17 (strand " + std::to_string(strand17) + ") is not finite"));

    // Writers refuse them too, and write nothing.
    HairCurves broken = smallGroom();
    broken.positions[3].y = -std::numeric_limits<float>::infinity();
    for (const char* name : { "w.hair", "w.data", "w.obj", "w.gltf", "w.glb" }) {
        const Result<void> error = writeHair((dir / name).string(), broken);
        ASSERT_FALSE(error.ok()) << name;
        EXPECT_NE(std::string::npos, error.error().message.find("point 3 (strand 1) is not finite"))
            << error.error().toString();
        EXPECT_FALSE(fs::exists(dir / name));
    }
}

TEST_F(HairFiles, TruncatedAndCorruptedCopiesNeverCrash)
{
    REQUIRE_ASSET(kBangsHair);
    REQUIRE_ASSET(kBangsData);
    for (const fs::path& sample : { kBangsHair, kBangsData }) {
        const std::string bytes = slurp(sample);
        const fs::path copy = dir / ("copy" + sample.extension().string());
        // Every length through the header, the segment counts and the first strands, then every 7th
        // and the last few: each is refused (the counts promise more than is there), none crashes.
        for (std::size_t length = 0; length < bytes.size();
             length += (length < 600 || length + 16 >= bytes.size()) ? 1 : 7) {
            spit(copy, bytes.substr(0, length));
            Result<HairReadResult> r = readHair(copy.string());
            ASSERT_FALSE(r.ok()) << sample << " cut to " << length << " bytes was read";
            ASSERT_NE(std::string::npos, r.error().toString().find(copy.string())) << r.error().toString();
        }
        // Random bytes overwritten: refused or read, never a crash or inconsistent strands.
        std::mt19937 random(1234);
        for (int trial = 0; trial < 1000; ++trial) {
            std::string corrupt = bytes;
            const int flips = 1 + trial % 4;
            for (int f = 0; f < flips; ++f) {
                const std::size_t at
                    = trial % 2 ? random() % 160 : random() % corrupt.size(); // the header half the time
                corrupt[at] = static_cast<char>(random());
            }
            spit(copy, corrupt);
            Result<HairReadResult> r = readHair(copy.string());
            if (r.ok()) {
                const HairCurves& c = r.value().strands;
                ASSERT_EQ(c.offsets.back(), c.positions.size());
                for (const glm::vec3& p : c.positions)
                    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            }
        }
    }
}

TEST_F(HairFiles, UnknownExtensionsListTheSupportedOnes)
{
    EXPECT_EQ((std::vector<std::string>{ "hair", "data", "obj", "gltf", "glb" }), hairReadExtensions());
    EXPECT_EQ((std::vector<std::string>{ "hair", "data", "obj", "gltf", "glb" }), hairWriteExtensions());
    EXPECT_EQ(HairFormat::CyHair, hairFormatForPath("a/b.HaIr"));
    EXPECT_EQ(HairFormat::Glb, hairFormatForPath("x.GLB"));
    EXPECT_FALSE(hairFormatForPath("x.abc").has_value());
    EXPECT_FALSE(hairFormatForPath("hair").has_value());

    Result<HairReadResult> r = readHair((dir / "groom.abc").string());
    ASSERT_FALSE(r.ok());
    EXPECT_EQ((dir / "groom.abc").string()
            + ": '.abc' is not a hair file extension Wisp knows; Wisp reads hair from .hair (cyHair), .data "
              "(USC-HairSalon), "
              ".obj (OBJ polylines), .gltf (glTF), .glb (binary glTF)",
        r.error().toString());
    r = readHair((dir / "groom.glb").string()); // a readable format, but no such file
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().file, (dir / "groom.glb").string());

    const Result<void> error = writeHair((dir / "groom").string(), smallGroom());
    ASSERT_FALSE(error.ok());
    EXPECT_EQ(
        "the file name has no extension to tell its format; Wisp writes hair as .hair (cyHair), .data (USC-HairSalon), "
        ".obj (OBJ polylines), .gltf (glTF), .glb (binary glTF)",
        error.error().message);
    EXPECT_TRUE(filesInDir().empty());
}

TEST_F(HairFiles, MissingFolderOrBlockedTargetLeavesNoFile)
{
    const HairCurves groom = smallGroom();
    for (const char* name : { "g.hair", "g.data", "g.obj", "g.gltf", "g.glb" }) {
        SCOPED_TRACE(name);
        const fs::path missing = dir / "no-such-folder" / name;
        const Result<void> error = writeHair(missing.string(), groom);
        ASSERT_FALSE(error.ok());
        EXPECT_EQ(missing.string(), error.error().file);
        EXPECT_NE(std::string::npos, error.error().message.find("cannot write there")) << error.error().toString();
        EXPECT_FALSE(fs::exists(dir / "no-such-folder"));

        // A folder where the file should go: the rename fails and the temporary file is removed.
        fs::create_directory(dir / name);
        const Result<void> blocked = writeHair((dir / name).string(), groom);
        ASSERT_FALSE(blocked.ok());
        EXPECT_NE(std::string::npos, blocked.error().toString().find(name)) << blocked.error().toString();
        EXPECT_TRUE(fs::is_directory(dir / name));
    }
    EXPECT_EQ((std::vector<std::string>{ "g.data", "g.glb", "g.gltf", "g.hair", "g.obj" }), filesInDir());

    // Reading a folder, or a file that is not there.
    EXPECT_NE(std::string::npos, errorText(dir / "g.hair").find("folder"));
    EXPECT_NE(std::string::npos, errorText(dir / "absent.data").find("does not exist"));

    // Nothing to write.
    const Result<void> empty = writeHair((dir / "empty.hair").string(), HairCurves{});
    ASSERT_FALSE(empty.ok());
    EXPECT_NE(std::string::npos, empty.error().message.find("no strands"));
    EXPECT_FALSE(fs::exists(dir / "empty.hair"));
}

TEST_F(HairFiles, OverwritingReplacesTheOldFileWhole)
{
    const fs::path path = dir / "g.hair";
    HairCurves big = smallGroom();
    big.addStrand(40);
    for (glm::vec3& p : big.strandForWrite(3))
        p = glm::vec3(0.5f);
    ASSERT_TRUE(writeHair(path.string(), big));
    ASSERT_TRUE(writeHair(path.string(), smallGroom()));
    expectBitIdentical(smallGroom(), readOk(path));
    EXPECT_EQ(std::vector<std::string>{ "g.hair" }, filesInDir());
}

TEST_F(HairFiles, CyHairRefusesStrandsItCannotHold)
{
    HairCurves longStrand;
    longStrand.addStrand(70000);
    for (std::size_t i = 0; i < longStrand.positions.size(); ++i)
        longStrand.positions[i] = { 0.0f, float(i) * 1e-4f, 0.0f };
    const Result<void> error = writeHair((dir / "long.hair").string(), longStrand);
    ASSERT_FALSE(error.ok());
    EXPECT_NE(std::string::npos, error.error().message.find("strand 0 has 70000 points; cyHair holds at most 65,536"))
        << error.error().toString();
    EXPECT_FALSE(fs::exists(dir / "long.hair"));
    // USC has no such limit.
    ASSERT_TRUE(writeHair((dir / "long.data").string(), longStrand));
    expectBitIdentical(longStrand, readOk(dir / "long.data"));
}

// Issue 12: a non-finite point in a strand the reader skips (a single point) was never looked
// at, so a file with infinite coordinates was accepted. Any non-finite point refuses the file.
TEST_F(HairFiles, NonFinitePointInASkippedStrandIsRefused)
{
    std::string data;
    appendI32(data, 2);
    appendI32(data, 1);
    appendF32(data, std::numeric_limits<float>::infinity());
    appendF32(data, 0.0f);
    appendF32(data, 0.0f);
    appendI32(data, 2);
    for (int i = 0; i < 6; ++i)
        appendF32(data, 0.1f * static_cast<float>(i));
    spit(dir / "single-inf.data", data);
    EXPECT_EQ((dir / "single-inf.data").string() + ": byte 8: point 0 (strand 0) is not finite",
        errorText(dir / "single-inf.data"));

    std::string hair("HAIR", 4);
    appendI32(hair, 2); // strands
    appendI32(hair, 4); // points
    appendI32(hair, 3); // flags: segments and points arrays
    appendI32(hair, 0); // default segments
    for (int i = 0; i < 5; ++i)
        appendF32(hair, 1.0f); // default thickness, transparency, colour
    hair.append(88, '\0');
    ASSERT_EQ(hair.size(), 128u);
    hair.append("\0\0\x02\0", 4); // strand 0: 0 segments (1 point), strand 1: 2 segments
    appendF32(hair, 0.0f);
    appendF32(hair, -std::numeric_limits<float>::infinity());
    appendF32(hair, 0.0f);
    for (int i = 0; i < 9; ++i)
        appendF32(hair, 0.1f * static_cast<float>(i));
    spit(dir / "single-inf.hair", hair);
    EXPECT_EQ((dir / "single-inf.hair").string() + ": byte 132: point 0 (strand 0) is not finite",
        errorText(dir / "single-inf.hair"));
}
