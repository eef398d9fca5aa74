#include "io/gltf/GlbContainer.h"

#include "io/ReadFailure.h"
#include "io/mesh/ByteReader.h"

#include <cstdio>

namespace wisp::io::gltf {

namespace {

constexpr std::uint32_t glbChunkJson = 0x4E4F534A; // "JSON"
constexpr std::uint32_t glbChunkBin = 0x004E4942; // "BIN\0"

std::uint32_t u32At(std::string_view bytes, std::size_t offset)
{
    return mesh::loadLittle<std::uint32_t>(bytes.data() + offset);
}

std::string chunkTypeName(std::uint32_t type)
{
    std::string name;
    for (int i = 0; i < 4; ++i) {
        const auto c = static_cast<unsigned char>((type >> (8 * i)) & 0xFFu);
        if (c == 0)
            continue;
        if (c < 0x20 || c > 0x7E) {
            char hex[16];
            std::snprintf(hex, sizeof hex, "0x%08X", static_cast<unsigned>(type));
            return hex;
        }
        name += static_cast<char>(c);
    }
    return "'" + name + "'";
}

} // namespace

bool startsWithGlbMagic(std::string_view bytes)
{
    return bytes.size() >= 4 && u32At(bytes, 0) == kGlbMagic;
}

GlbParts splitGlb(std::string_view bytes, std::vector<std::string>& warnings)
{
    if (bytes.size() < 12)
        fail({},
            "the file is " + plural(bytes.size(), "byte", "bytes")
                + ", too short for the 12-byte header of a binary glTF (GLB) file");
    if (u32At(bytes, 0) != kGlbMagic) {
        const std::size_t first = bytes.find_first_not_of(" \t\r\n");
        const bool looksLikeJson = first != std::string_view::npos && bytes[first] == '{';
        fail(byteAt(0),
            std::string("this is not a binary glTF (GLB) file: it does not start with 'glTF'")
                + (looksLikeJson ? " (it looks like a text glTF: name it .gltf)" : ""));
    }
    const std::uint32_t version = u32At(bytes, 4);
    if (version != 2)
        fail(byteAt(4),
            "GLB version " + std::to_string(version) + "; Wisp reads version 2 (glTF 2.0)"
                + (version == 1 ? ": re-export the head as glTF 2.0" : ""));
    const std::uint32_t length = u32At(bytes, 8);
    if (length < 20)
        fail(byteAt(8),
            "the header declares a total length of " + std::to_string(length)
                + " bytes, too small for the header and a JSON chunk (20 bytes at least)");
    if (length > bytes.size())
        fail(byteAt(8),
            "the header declares " + std::to_string(length) + " bytes but the file has only "
                + std::to_string(bytes.size()) + ": it is truncated");
    if (length < bytes.size())
        warnings.push_back("ignored " + plural(bytes.size() - length, "byte", "bytes")
            + " after the end of the GLB data (the header declares " + std::to_string(length) + ")");

    GlbParts parts;
    bool haveJson = false;
    bool haveBin = false;
    std::size_t chunkIndex = 0;
    std::size_t offset = 12;
    while (offset < length) {
        const std::size_t left = length - offset;
        if (left < 8)
            fail(byteAt(offset), "the data ends inside a chunk header (" + std::to_string(left) + " of 8 bytes)");
        const std::uint32_t chunkBytes = u32At(bytes, offset);
        const std::uint32_t type = u32At(bytes, offset + 4);
        if (chunkBytes > left - 8)
            fail(byteAt(offset),
                "a chunk of " + std::to_string(chunkBytes) + " bytes starts here, but only " + std::to_string(left - 8)
                    + " bytes of GLB data follow its header: it is truncated or corrupt");
        // The spec: chunks start and end on 4-byte boundaries (Khronos' validator:
        // CHUNK_LENGTH_UNALIGNED). A reader that accepts an unaligned length reads the next
        // chunk's header from the wrong bytes.
        if (chunkBytes % 4 != 0)
            fail(byteAt(offset),
                "a chunk of " + std::to_string(chunkBytes)
                    + " bytes: GLB chunk lengths are multiples of 4 (the chunk is not padded; the file is malformed)");
        const std::string_view data = bytes.substr(offset + 8, chunkBytes);
        if (chunkIndex == 0 && type != glbChunkJson)
            fail(byteAt(offset + 4), "the first chunk must be JSON but is of type " + chunkTypeName(type));
        if (type == glbChunkJson) {
            if (haveJson)
                fail(byteAt(offset), "a second JSON chunk; a GLB file holds exactly one");
            if (chunkBytes == 0)
                fail(byteAt(offset), "the JSON chunk is empty");
            parts.json = data;
            parts.jsonOffset = offset + 8;
            haveJson = true;
        } else if (type == glbChunkBin) {
            if (haveBin)
                fail(byteAt(offset), "a second BIN chunk; a GLB file holds at most one");
            if (chunkIndex != 1)
                fail(byteAt(offset),
                    "the BIN chunk must directly follow the JSON chunk, but it is chunk "
                        + std::to_string(chunkIndex + 1));
            parts.bin = data;
            haveBin = true;
        } else {
            warnings.push_back(
                "skipped a GLB chunk of unknown type " + chunkTypeName(type) + " at byte " + std::to_string(offset));
        }
        offset += 8 + std::size_t{ chunkBytes };
        ++chunkIndex;
    }
    return parts;
}

} // namespace wisp::io::gltf
