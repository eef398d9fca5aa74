#pragma once
// FNV-1a over raw bytes: a cheap, deterministic 64-bit hash for telling whether cached work (a
// rest shape solved for a comb, a wisp's edited rest shape) still matches what it was made from.

#include <cstddef>
#include <cstdint>

namespace wisp {

struct ByteHash {
    std::uint64_t value = 1469598103934665603ull; // the FNV-1a offset basis

    void add(const void* data, std::size_t size)
    {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i)
            value = (value ^ bytes[i]) * 1099511628211ull;
    }
    template <typename T> void add(const T& plain) { add(&plain, sizeof plain); }
};

} // namespace wisp
