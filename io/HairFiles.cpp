// Hair files: picking the format by extension, and the steps every hair reader and writer shares.
// The formats themselves live in CyHair.cpp, UscHairData.cpp and HairExport.cpp.

#include "io/HairFiles.h"

#include "io/AtomicFile.h"
#include "io/HairFilesInternal.h"
#include "io/RegularFile.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace wisp::io {

namespace {

const char* formatName(HairFormat format)
{
    switch (format) {
    case HairFormat::CyHair:
        return "cyHair";
    case HairFormat::UscData:
        return "USC-HairSalon";
    case HairFormat::ObjPolylines:
        return "OBJ polylines";
    case HairFormat::Gltf:
        return "glTF";
    case HairFormat::Glb:
        return "binary glTF";
    }
    return "?";
}

// ".hair (cyHair), .data (USC-HairSalon)"
std::string describe(const std::vector<std::string>& extensions)
{
    std::string s;
    for (const std::string& e : extensions) {
        if (!s.empty())
            s += ", ";
        s += "." + e + " (" + formatName(*hairFormatForPath("x." + e)) + ")";
    }
    return s;
}

std::string unknownExtension(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    return ext.empty() ? std::string("the file name has no extension to tell its format")
                       : "'." + ext + "' is not a hair file extension Wisp knows";
}

} // namespace

std::optional<HairFormat> hairFormatForPath(const std::string& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == "hair")
        return HairFormat::CyHair;
    if (ext == "data")
        return HairFormat::UscData;
    if (ext == "obj")
        return HairFormat::ObjPolylines;
    if (ext == "gltf")
        return HairFormat::Gltf;
    if (ext == "glb")
        return HairFormat::Glb;
    return std::nullopt;
}

const std::vector<std::string>& hairReadExtensions()
{
    static const std::vector<std::string> extensions{ "hair", "data", "obj", "gltf", "glb" };
    return extensions;
}

const std::vector<std::string>& hairWriteExtensions()
{
    static const std::vector<std::string> extensions{ "hair", "data", "obj", "gltf", "glb" };
    return extensions;
}

Result<HairReadResult> readHair(const std::string& path)
{
    const std::optional<HairFormat> format = hairFormatForPath(path);
    if (format == HairFormat::CyHair)
        return hair_detail::readCyHair(path);
    if (format == HairFormat::UscData)
        return hair_detail::readUscData(path);
    if (format == HairFormat::ObjPolylines)
        return hair_detail::readObjPolylines(path);
    if (format == HairFormat::Gltf || format == HairFormat::Glb)
        return hair_detail::readGltfStrands(path);
    const std::string readable = "Wisp reads hair from " + describe(hairReadExtensions());
    if (format)
        return IoError{ path, "",
            std::string("Wisp writes ") + formatName(*format) + " but cannot read strands from it; " + readable };
    return IoError{ path, "", unknownExtension(path) + "; " + readable };
}

Result<void> writeHair(const std::string& path, const HairCurves& strands, const HairExportOptions& options)
{
    const std::optional<HairFormat> format = hairFormatForPath(path);
    if (!format)
        return IoError{ path, "", unknownExtension(path) + "; Wisp writes hair as " + describe(hairWriteExtensions()) };
    if (std::optional<IoError> error = hair_detail::checkStrandsToWrite(path, strands))
        return *error;
    switch (*format) {
    case HairFormat::CyHair:
        return hair_detail::writeCyHair(path, strands);
    case HairFormat::UscData:
        return hair_detail::writeUscData(path, strands);
    case HairFormat::ObjPolylines:
        return hair_detail::writeObjPolylines(path, strands, options);
    case HairFormat::Gltf:
        return hair_detail::writeGltf(path, strands, options, false);
    case HairFormat::Glb:
        return hair_detail::writeGltf(path, strands, options, true);
    }
    return IoError{ path, "", "unknown hair format" };
}

namespace hair_detail {

Result<void> writeBytesAtomically(const std::string& path, const std::string& bytes)
{
    return writeFileAtomically(
        path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

std::optional<IoError> checkStrandsToWrite(const std::string& path, const HairCurves& strands)
{
    const std::vector<std::uint32_t>& offsets = strands.offsets;
    if (offsets.empty() || offsets.front() != 0 || offsets.back() != strands.positions.size())
        return IoError{ path, "",
            "the strands' offsets do not match their points (an internal error; nothing was written)" };
    for (std::size_t s = 0; s + 1 < offsets.size(); ++s)
        if (offsets[s + 1] < offsets[s])
            return IoError{ path, "",
                "strand " + std::to_string(s)
                    + " has a negative point count (an internal error; nothing was written)" };
    if (strands.positions.empty())
        return IoError{ path, "", "there are no strands to write" };
    std::size_t strand = 0;
    for (std::size_t i = 0; i < strands.positions.size(); ++i) {
        while (offsets[strand + 1] <= i)
            ++strand;
        const glm::vec3& p = strands.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return IoError{ path, "",
                "point " + std::to_string(i) + " (strand " + std::to_string(strand)
                    + ") is not finite; nothing was written" };
    }
    return std::nullopt;
}

std::optional<IoError> checkFinitePoints(const std::string& path, const char* p, std::uint32_t points,
    std::uint64_t firstPoint, std::uint64_t strandIndex, std::uint64_t fileOffset)
{
    for (std::uint32_t i = 0; i < points; ++i, p += 12) {
        const glm::vec3 v{ loadF32(p), loadF32(p + 4), loadF32(p + 8) };
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            return IoError{ path, byteAt(fileOffset + 12ull * i),
                "point " + std::to_string(firstPoint + i) + " (strand " + std::to_string(strandIndex)
                    + ") is not finite" };
    }
    return std::nullopt;
}

std::optional<IoError> appendFinitePoints(const std::string& path, const char* p, std::uint32_t points,
    std::uint64_t firstPoint, std::uint64_t strandIndex, std::uint64_t fileOffset, HairCurves& out)
{
    if (std::optional<IoError> error = checkFinitePoints(path, p, points, firstPoint, strandIndex, fileOffset))
        return error;
    const std::size_t first = out.positions.size();
    out.positions.resize(first + points);
    for (std::uint32_t i = 0; i < points; ++i, p += 12)
        out.positions[first + i] = glm::vec3{ loadF32(p), loadF32(p + 4), loadF32(p + 8) };
    out.offsets.push_back(static_cast<std::uint32_t>(out.positions.size()));
    return std::nullopt;
}

std::string skippedStrandsWarning(const std::vector<std::uint64_t>& strands, const std::string& what)
{
    constexpr std::size_t listed = 8;
    std::string s = "skipped " + std::to_string(strands.size()) + (strands.size() == 1 ? " strand " : " strands ")
        + what + " (strand";
    s += strands.size() == 1 ? " " : "s ";
    for (std::size_t i = 0; i < strands.size() && i < listed; ++i)
        s += (i ? ", " : "") + std::to_string(strands[i]);
    return s + (strands.size() > listed ? ", ...)" : ")");
}

} // namespace hair_detail

} // namespace wisp::io
