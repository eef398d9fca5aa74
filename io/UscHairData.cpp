// USC-HairSalon .data (Hu et al., "Single-view hair modeling using a hairstyle database"),
// little-endian:
//
//   int32 strand count S
//   S times: int32 n, then n x (float32 x, y, z)
//
// Some USC files hold strands of a single point (n == 1, a root without hair) or none; they are
// skipped with a warning.

#include "io/HairFilesInternal.h"

#include <limits>

namespace wisp::io::hair_detail {

Result<HairReadResult> readUscData(const std::string& path)
{
    Result<std::string> file = readRegularFile(path, kHairFileRules);
    if (!file)
        return file.error();
    const std::string& bytes = file.value();
    const std::uint64_t size = bytes.size();
    const char* data = bytes.data();

    if (size < 4)
        return IoError{ path, byteAt(0),
            "the file is " + std::to_string(size) + " bytes, too short to hold a strand count" };
    const std::int32_t claimed = loadI32(data);
    if (claimed < 0)
        return IoError{ path, byteAt(0), "the strand count is negative (" + std::to_string(claimed) + ")" };
    if (claimed == 0)
        return IoError{ path, byteAt(0), "the strand count is 0: the file holds no strands" };
    const std::uint64_t strandCount = static_cast<std::uint64_t>(claimed);
    // Every strand takes at least its 4-byte point count.
    if (strandCount > (size - 4) / 4)
        return IoError{ path, byteAt(0),
            "the header claims " + std::to_string(strandCount) + " strands but the " + std::to_string(size)
                + "-byte file can hold at most " + std::to_string((size - 4) / 4) };

    HairReadResult result;
    HairCurves& curves = result.strands;
    curves.offsets.reserve(strandCount + 1);
    curves.positions.reserve((size - 4 - 4 * strandCount) / 12); // no more points than the file has room for
    std::vector<std::uint64_t> skipped;
    std::uint64_t at = 4;
    std::uint64_t point = 0;
    for (std::uint64_t s = 0; s < strandCount; ++s) {
        if (size - at < 4)
            return IoError{ path, byteAt(at),
                "the file ends before strand " + std::to_string(s) + " of " + std::to_string(strandCount) + " ("
                    + std::to_string(size - at) + " bytes left)" };
        const std::int32_t n = loadI32(data + at);
        if (n < 0)
            return IoError{ path, byteAt(at),
                "strand " + std::to_string(s) + " claims a negative point count (" + std::to_string(n) + ")" };
        at += 4;
        const std::uint64_t remaining = size - at;
        if (std::uint64_t(n) > remaining / 12)
            return IoError{ path, byteAt(at - 4),
                "strand " + std::to_string(s) + " claims " + std::to_string(n) + " points but the file holds only "
                    + std::to_string(remaining / 12) + " more" };
        if (point + std::uint64_t(n) > std::numeric_limits<std::uint32_t>::max())
            return IoError{ path, byteAt(at - 4),
                "the file holds more than 4,294,967,295 points, more than Wisp can hold" };
        if (n < 2) {
            if (std::optional<IoError> error
                = checkFinitePoints(path, data + at, static_cast<std::uint32_t>(n), point, s, at))
                return *error;
            skipped.push_back(s);
        } else if (std::optional<IoError> error
            = appendFinitePoints(path, data + at, static_cast<std::uint32_t>(n), point, s, at, curves)) {
            return *error;
        }
        at += 12 * std::uint64_t(n);
        point += std::uint64_t(n);
    }
    if (curves.strandCount() == 0)
        return IoError{ path, "", "the file holds no strands of two or more points" };

    if (!skipped.empty())
        result.warnings.push_back(skippedStrandsWarning(skipped, "of fewer than two points"));
    if (at < size)
        result.warnings.push_back(std::to_string(size - at) + " bytes after the last strand (from byte "
            + std::to_string(at) + ") were ignored");
    return result;
}

Result<void> writeUscData(const std::string& path, const HairCurves& strands)
{
    std::uint64_t strandCount = 0;
    for (std::size_t s = 0; s < strands.strandCount(); ++s)
        strandCount += strands.pointsIn(s) > 0;
    if (strandCount > std::uint64_t(std::numeric_limits<std::int32_t>::max()))
        return IoError{ path, "", "too many strands for a .data file (" + std::to_string(strandCount) + ")" };

    std::string bytes;
    bytes.reserve(4 + 4 * strandCount + 12 * strands.pointCount());
    appendI32(bytes, static_cast<std::int32_t>(strandCount));
    for (std::size_t s = 0; s < strands.strandCount(); ++s) {
        const std::uint32_t n = strands.pointsIn(s);
        if (n == 0)
            continue;
        if (n > std::uint32_t(std::numeric_limits<std::int32_t>::max()))
            return IoError{ path, "", "strand " + std::to_string(s) + " has too many points for a .data file" };
        appendI32(bytes, static_cast<std::int32_t>(n));
        for (const glm::vec3& p : strands.strand(s)) {
            appendF32(bytes, p.x);
            appendF32(bytes, p.y);
            appendF32(bytes, p.z);
        }
    }
    return writeBytesAtomically(path, bytes);
}

} // namespace wisp::io::hair_detail
