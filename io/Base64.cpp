#include "io/Base64.h"

#include <array>
#include <bit>

namespace wisp::io {

namespace {

constexpr std::string_view kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<std::int8_t, 256> makeDecodeTable()
{
    std::array<std::int8_t, 256> table{};
    for (auto& entry : table)
        entry = -1;
    for (std::size_t i = 0; i < kAlphabet.size(); ++i)
        table[static_cast<unsigned char>(kAlphabet[i])] = static_cast<std::int8_t>(i);
    return table;
}
constexpr std::array<std::int8_t, 256> kDecode = makeDecodeTable();

std::vector<std::uint8_t> packLittleEndian(std::span<const std::uint32_t> words)
{
    std::vector<std::uint8_t> bytes(words.size() * 4);
    for (std::size_t i = 0; i < words.size(); ++i)
        for (int b = 0; b < 4; ++b)
            bytes[i * 4 + b] = static_cast<std::uint8_t>(words[i] >> (8 * b));
    return bytes;
}

std::optional<std::vector<std::uint32_t>> unpackLittleEndian(std::string_view text)
{
    std::optional<std::vector<std::uint8_t>> bytes = base64Decode(text);
    if (!bytes || bytes->size() % 4 != 0)
        return std::nullopt;
    std::vector<std::uint32_t> words(bytes->size() / 4);
    for (std::size_t i = 0; i < words.size(); ++i)
        for (int b = 0; b < 4; ++b)
            words[i] |= std::uint32_t((*bytes)[i * 4 + b]) << (8 * b);
    return words;
}

} // namespace

std::string base64Encode(std::span<const std::uint8_t> bytes)
{
    std::string text;
    text.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 3 <= bytes.size(); i += 3) {
        const std::uint32_t group = std::uint32_t(bytes[i]) << 16 | std::uint32_t(bytes[i + 1]) << 8 | bytes[i + 2];
        text += kAlphabet[group >> 18 & 63];
        text += kAlphabet[group >> 12 & 63];
        text += kAlphabet[group >> 6 & 63];
        text += kAlphabet[group & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        std::uint32_t group = std::uint32_t(bytes[i]) << 16;
        if (rest == 2)
            group |= std::uint32_t(bytes[i + 1]) << 8;
        text += kAlphabet[group >> 18 & 63];
        text += kAlphabet[group >> 12 & 63];
        text += rest == 2 ? kAlphabet[group >> 6 & 63] : '=';
        text += '=';
    }
    return text;
}

std::optional<std::vector<std::uint8_t>> base64Decode(std::string_view text, std::size_t* badOffset)
{
    auto fail = [&](std::size_t offset) {
        if (badOffset)
            *badOffset = offset;
        return std::nullopt;
    };
    if (text.size() % 4 != 0)
        return fail(text.size());
    std::size_t padding = 0;
    if (!text.empty() && text.back() == '=')
        padding = text.size() >= 2 && text[text.size() - 2] == '=' ? 2 : 1;
    std::vector<std::uint8_t> bytes;
    bytes.reserve(text.size() / 4 * 3);
    for (std::size_t i = 0; i < text.size(); i += 4) {
        const bool last = i + 4 == text.size();
        std::uint32_t group = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const bool isPadding = last && k >= 4 - padding;
            const std::int8_t sextet = isPadding ? 0 : kDecode[static_cast<unsigned char>(text[i + k])];
            if (sextet < 0)
                return fail(i + k);
            group = group << 6 | static_cast<std::uint32_t>(sextet);
        }
        const std::size_t keep = last ? 3 - padding : 3;
        // Bits below the last kept byte must be zero, or two texts would decode to the same bytes.
        if (keep < 3 && (group & ((1u << (8 * (3 - keep))) - 1)) != 0)
            return fail(i + 4 - padding - 1);
        for (std::size_t b = 0; b < keep; ++b)
            bytes.push_back(static_cast<std::uint8_t>(group >> (16 - 8 * b)));
    }
    return bytes;
}

std::string encodeFloat32Array(std::span<const float> values)
{
    std::vector<std::uint32_t> words(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        words[i] = std::bit_cast<std::uint32_t>(values[i]);
    return base64Encode(packLittleEndian(words));
}

std::string encodeUint32Array(std::span<const std::uint32_t> values)
{
    return base64Encode(packLittleEndian(values));
}

std::optional<std::vector<float>> decodeFloat32Array(std::string_view text)
{
    std::optional<std::vector<std::uint32_t>> words = unpackLittleEndian(text);
    if (!words)
        return std::nullopt;
    std::vector<float> values(words->size());
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = std::bit_cast<float>((*words)[i]);
    return values;
}

std::optional<std::vector<std::uint32_t>> decodeUint32Array(std::string_view text)
{
    return unpackLittleEndian(text);
}

} // namespace wisp::io
