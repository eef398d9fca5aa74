#pragma once
// Base64 (RFC 4648, standard alphabet, '=' padding, no line breaks) for the binary arrays inside
// project files: a head's positions and triangles and the painted weights are stored as base64 of
// little-endian float32 / uint32 so that they round-trip bit for bit and take 4/3 of their binary
// size instead of the ~10 characters per number that decimal text would.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::io {

std::string base64Encode(std::span<const std::uint8_t> bytes);

// Strict: the length must be a multiple of 4, only alphabet characters, '=' only as the last one
// or two, and the unused bits of the last group zero (so each byte string has exactly one text).
// On failure returns nullopt and, when `badOffset` is given, the offset of the first bad character
// (or the text's length when it is only too short).
std::optional<std::vector<std::uint8_t>> base64Decode(std::string_view text, std::size_t* badOffset = nullptr);

// Little-endian packing of 32-bit floats and unsigned integers, whatever the machine's byte order.
std::string encodeFloat32Array(std::span<const float> values);
std::string encodeUint32Array(std::span<const std::uint32_t> values);
// nullopt when the text is not strict base64 or its byte count is not a multiple of 4.
std::optional<std::vector<float>> decodeFloat32Array(std::string_view text);
std::optional<std::vector<std::uint32_t>> decodeUint32Array(std::string_view text);

} // namespace wisp::io
