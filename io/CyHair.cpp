// cyHair .hair (Cem Yuksel, www.cemyuksel.com/research/hairmodels): a 128-byte header, then the
// arrays its flags name, each whole before the next:
//
//   offset  type        field
//   0       char[4]     "HAIR"
//   4       uint32      strand count H
//   8       uint32      point count P
//   12      uint32      flags: bit0 segments array, bit1 points, bit2 thickness, bit3 transparency, bit4 colour
//   16      uint32      default segments a strand (when there is no segments array)
//   20      float       default thickness, 24 float default transparency, 28 float[3] default colour
//   40      char[88]    info
//   128     uint16[H]   segments a strand (a strand has segments + 1 points)
//           float[3P]   points; then float[P] thickness, float[P] transparency, float[3P] colour

#include "io/HairFilesInternal.h"

#include <array>
#include <cstdio>

namespace wisp::io::hair_detail {

namespace {

constexpr std::size_t kHeaderBytes = 128;
constexpr std::uint32_t kSegmentsArray = 1u << 0;
constexpr std::uint32_t kPointsArray = 1u << 1;
constexpr std::uint32_t kThicknessArray = 1u << 2;
constexpr std::uint32_t kTransparencyArray = 1u << 3;
constexpr std::uint32_t kColourArray = 1u << 4;
constexpr std::uint32_t kKnownFlags = 0x1f;

std::string hex(std::uint32_t v)
{
    char s[16];
    std::snprintf(s, sizeof s, "0x%x", v);
    return s;
}

} // namespace

Result<HairReadResult> readCyHair(const std::string& path)
{
    Result<std::string> file = readRegularFile(path, kHairFileRules);
    if (!file)
        return file.error();
    const std::string& bytes = file.value();
    const std::uint64_t size = bytes.size();
    const char* data = bytes.data();

    if (size < kHeaderBytes)
        return IoError{ path, byteAt(size),
            "the file is " + std::to_string(size) + " bytes, shorter than the 128-byte cyHair header" };
    if (std::memcmp(data, "HAIR", 4) != 0)
        return IoError{ path, byteAt(0), "not a cyHair file (it does not start with 'HAIR')" };
    const std::uint64_t strandCount = loadU32(data + 4);
    const std::uint64_t pointCount = loadU32(data + 8);
    const std::uint32_t flags = loadU32(data + 12);
    const std::uint64_t defaultSegments = loadU32(data + 16);

    if (!(flags & kPointsArray))
        return IoError{ path, byteAt(12), "the file has no points array (flags " + hex(flags) + ")" };
    if (strandCount == 0)
        return IoError{ path, byteAt(4), "the header says the file holds no strands" };
    if (pointCount == 0)
        return IoError{ path, byteAt(8), "the header says the file holds no points" };
    if (strandCount > pointCount)
        return IoError{ path, byteAt(4),
            "the header claims " + std::to_string(strandCount) + " strands but only " + std::to_string(pointCount)
                + " points; every strand needs at least one" };

    // Everything the header promises, against what the file holds, before allocating anything.
    const std::uint64_t segmentsBytes = (flags & kSegmentsArray) ? 2 * strandCount : 0;
    const std::uint64_t pointsStart = kHeaderBytes + segmentsBytes;
    const std::uint64_t pointsEnd = pointsStart + 12 * pointCount;
    std::uint64_t expected = pointsEnd;
    std::vector<std::string> extras;
    if (flags & kThicknessArray) {
        expected += 4 * pointCount;
        extras.push_back("thickness");
    }
    if (flags & kTransparencyArray) {
        expected += 4 * pointCount;
        extras.push_back("transparency");
    }
    if (flags & kColourArray) {
        expected += 12 * pointCount;
        extras.push_back("colour");
    }
    if (size < pointsStart)
        return IoError{ path, byteAt(size),
            "the header claims " + std::to_string(strandCount) + " strands but the file holds segment counts for only "
                + std::to_string((size - kHeaderBytes) / 2) };
    if (size < pointsEnd)
        return IoError{ path, byteAt(size),
            "the header claims " + std::to_string(pointCount) + " points but the file holds only "
                + std::to_string((size - pointsStart) / 12) };
    if (size < expected) {
        std::string names;
        for (const std::string& e : extras)
            names += (names.empty() ? "" : ", ") + e;
        return IoError{ path, byteAt(size),
            "the file ends inside its per-point " + names + " arrays: the header asks for " + std::to_string(expected)
                + " bytes, the file has " + std::to_string(size) };
    }

    // Segment counts must add up to the point count, again before allocating.
    const char* segments = data + kHeaderBytes;
    std::uint64_t pointsFromSegments = 0;
    if (flags & kSegmentsArray) {
        for (std::uint64_t s = 0; s < strandCount; ++s)
            pointsFromSegments += std::uint64_t(loadU16(segments + 2 * s)) + 1;
        if (pointsFromSegments != pointCount)
            return IoError{ path, byteAt(kHeaderBytes),
                "the strands' segment counts add up to " + std::to_string(pointsFromSegments)
                    + " points but the header claims " + std::to_string(pointCount) };
    } else {
        pointsFromSegments = strandCount * (defaultSegments + 1);
        if (pointsFromSegments != pointCount)
            return IoError{ path, byteAt(16),
                "the header claims " + std::to_string(strandCount) + " strands of " + std::to_string(defaultSegments)
                    + " segments (" + std::to_string(pointsFromSegments) + " points) but " + std::to_string(pointCount)
                    + " points" };
    }

    HairReadResult result;
    HairCurves& curves = result.strands;
    curves.offsets.reserve(strandCount + 1);
    curves.positions.reserve(pointCount);
    std::vector<std::uint64_t> skipped;
    std::uint64_t point = 0;
    for (std::uint64_t s = 0; s < strandCount; ++s) {
        const std::uint32_t n
            = static_cast<std::uint32_t>(((flags & kSegmentsArray) ? loadU16(segments + 2 * s) : defaultSegments) + 1);
        const std::uint64_t offset = pointsStart + 12 * point;
        if (n < 2) {
            if (std::optional<IoError> error = checkFinitePoints(path, data + offset, n, point, s, offset))
                return *error;
            skipped.push_back(s);
        } else if (std::optional<IoError> error
            = appendFinitePoints(path, data + offset, n, point, s, offset, curves)) {
            return *error;
        }
        point += n;
    }
    if (curves.strandCount() == 0)
        return IoError{ path, "", "the file holds no strands of two or more points" };

    if (!skipped.empty())
        result.warnings.push_back(skippedStrandsWarning(skipped, "of a single point"));
    if (!extras.empty()) {
        std::string names;
        for (const std::string& e : extras)
            names += (names.empty() ? "" : " and ") + e;
        result.warnings.push_back("the per-point " + names + " in the file " + (extras.size() == 1 ? "was" : "were")
            + " not read: Wisp strands carry positions only");
    }
    if (flags & ~kKnownFlags)
        result.warnings.push_back("unknown flag bits " + hex(flags & ~kKnownFlags) + " in the header were ignored");
    if (size > expected)
        result.warnings.push_back(std::to_string(size - expected) + " bytes after the last array (from byte "
            + std::to_string(expected) + ") were ignored");
    return result;
}

Result<void> writeCyHair(const std::string& path, const HairCurves& strands)
{
    std::uint32_t strandCount = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t n = strands.pointsIn(s);
        if (n > 65536)
            return IoError{ path, "",
                "strand " + std::to_string(s) + " has " + std::to_string(n)
                    + " points; cyHair holds at most 65,536 points a strand" };
        strandCount += n > 0;
    }

    std::string bytes;
    bytes.reserve(kHeaderBytes + 2 * std::size_t(strandCount) + 12 * strands.pointCount());
    bytes.append("HAIR", 4);
    appendU32(bytes, strandCount);
    appendU32(bytes, static_cast<std::uint32_t>(strands.pointCount()));
    appendU32(bytes, kSegmentsArray | kPointsArray);
    appendU32(bytes, 0); // default segments: unused with a segments array
    appendF32(bytes, 1.0f); // default thickness
    appendF32(bytes, 0.0f); // default transparency
    for (int i = 0; i < 3; ++i)
        appendF32(bytes, 1.0f); // default colour
    std::array<char, 88> info{};
    std::memcpy(info.data(), "Wisp", 4);
    bytes.append(info.data(), info.size());

    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        if (const std::uint32_t n = strands.pointsIn(s); n > 0)
            appendU16(bytes, static_cast<std::uint16_t>(n - 1));
    for (const glm::vec3& p : strands.positions) {
        appendF32(bytes, p.x);
        appendF32(bytes, p.y);
        appendF32(bytes, p.z);
    }
    return writeBytesAtomically(path, bytes);
}

} // namespace wisp::io::hair_detail
