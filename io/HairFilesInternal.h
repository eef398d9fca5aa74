#pragma once
// Shared by HairFiles.cpp, CyHair.cpp, UscHairData.cpp and HairExport.cpp; not part of io/'s API.

#include "io/GltfReader.h"
#include "io/HairFiles.h"
#include "io/ReadFailure.h"
#include "io/RegularFile.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

namespace wisp::io::hair_detail {

// ---- little-endian bytes, whatever the host's byte order ------------------------------------

inline std::uint32_t loadU32(const char* p)
{
    unsigned char b[4];
    std::memcpy(b, p, 4);
    return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
}
inline std::uint16_t loadU16(const char* p)
{
    unsigned char b[2];
    std::memcpy(b, p, 2);
    return static_cast<std::uint16_t>(b[0] | b[1] << 8);
}
inline std::int32_t loadI32(const char* p)
{
    return static_cast<std::int32_t>(loadU32(p));
}
inline float loadF32(const char* p)
{
    return std::bit_cast<float>(loadU32(p));
}

inline void appendU32(std::string& out, std::uint32_t v)
{
    const char b[4] = { char(v & 0xff), char(v >> 8 & 0xff), char(v >> 16 & 0xff), char(v >> 24 & 0xff) };
    out.append(b, 4);
}
inline void appendU16(std::string& out, std::uint16_t v)
{
    const char b[2] = { char(v & 0xff), char(v >> 8 & 0xff) };
    out.append(b, 2);
}
inline void appendI32(std::string& out, std::int32_t v)
{
    appendU32(out, static_cast<std::uint32_t>(v));
}
inline void appendF32(std::string& out, float v)
{
    appendU32(out, std::bit_cast<std::uint32_t>(v));
}

// ---- shared steps -------------------------------------------------------------------------------

// How hair files are read (io/RegularFile.h): regular, non-empty, at most kMaxHairFileBytes.
inline const RegularFileRules kHairFileRules{ kMaxHairFileBytes, "hair", false };

// Writes `bytes` to `path` atomically; nullopt on success.
Result<void> writeBytesAtomically(const std::string& path, const std::string& bytes);

// Checks what every writer needs: offsets that describe the positions, finite positions, and at
// least one point to write. nullopt when fine.
std::optional<IoError> checkStrandsToWrite(const std::string& path, const HairCurves& strands);

// Appends `points` read from `p` (n x 3 little-endian float32) to `out`, refusing a non-finite
// one: "point 17 (strand 2) is not finite". `firstPoint` numbers the points in the file and
// `fileOffset` is where `p` sits in it, so the error can say where.
std::optional<IoError> appendFinitePoints(const std::string& path, const char* p, std::uint32_t points,
    std::uint64_t firstPoint, std::uint64_t strandIndex, std::uint64_t fileOffset, HairCurves& out);

// The same check without keeping the points: for strands a reader skips (a single point), whose
// non-finite coordinates still mean the file is corrupt.
std::optional<IoError> checkFinitePoints(const std::string& path, const char* p, std::uint32_t points,
    std::uint64_t firstPoint, std::uint64_t strandIndex, std::uint64_t fileOffset);

// "skipped 3 strands with a single point (strands 5, 17, 40)": the warning readers give.
std::string skippedStrandsWarning(const std::vector<std::uint64_t>& strands, const std::string& what);

// ---- formats -------------------------------------------------------------------------------------

Result<HairReadResult> readCyHair(const std::string& path);
Result<HairReadResult> readUscData(const std::string& path);
Result<HairReadResult> readObjPolylines(const std::string& path); // ObjPolylines.cpp
Result<HairReadResult> readGltfStrands(const std::string& path); // ObjPolylines.cpp, through io/GltfReader
Result<void> writeCyHair(const std::string& path, const HairCurves& strands);
Result<void> writeUscData(const std::string& path, const HairCurves& strands);
Result<void> writeObjPolylines(const std::string& path, const HairCurves& strands, const HairExportOptions& options);
Result<void> writeGltf(
    const std::string& path, const HairCurves& strands, const HairExportOptions& options, bool binary);

} // namespace wisp::io::hair_detail
