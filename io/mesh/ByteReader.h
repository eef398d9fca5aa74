#pragma once
// Fixed-size numbers out of a byte buffer in a stated byte order: the one byte reader binary PLY,
// binary STL and the glTF container share. The caller checks the bounds first.

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

namespace wisp::io::mesh {

template <typename T> T loadScalar(const char* p, std::endian fileOrder)
{
    std::array<char, sizeof(T)> raw;
    std::memcpy(raw.data(), p, sizeof(T));
    if (fileOrder != std::endian::native)
        std::reverse(raw.begin(), raw.end());
    return std::bit_cast<T>(raw);
}

template <typename T> T loadLittle(const char* p)
{
    return loadScalar<T>(p, std::endian::little);
}

} // namespace wisp::io::mesh
