#pragma once
// The GLB container (glTF 2.0 specification, "Binary glTF Layout"): a 12-byte header (magic
// 'glTF', version 2, total length) and chunks of (length, type, data). The first chunk is JSON;
// an optional BIN chunk follows it directly; chunks of other types are skipped, as the spec asks.
// Every length is checked against the file before any byte is read.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io::gltf {

inline constexpr std::uint32_t kGlbMagic = 0x46546C67; // "glTF"

struct GlbParts {
    std::string_view json;
    std::size_t jsonOffset = 0; // bytes from the start of the file to the JSON text
    std::string_view bin; // empty when the file has no BIN chunk
};

bool startsWithGlbMagic(std::string_view bytes);

// Throws io::ReadFailure naming the byte of the problem.
GlbParts splitGlb(std::string_view bytes, std::vector<std::string>& warnings);

} // namespace wisp::io::gltf
