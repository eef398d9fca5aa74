#pragma once
// Counter-based randomness: a value is a pure function of (seed, keys), so results never depend on
// the order in which work is done or on how many threads do it, and a local edit changes only the
// values whose keys it touches.

#include <cstdint>

namespace wisp {

constexpr std::uint64_t mixBits(std::uint64_t x)
{
    // splitmix64 finaliser (Steele, Lea, Flood 2014): full avalanche in a few operations.
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

constexpr std::uint64_t hashKeys(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0)
{
    return mixBits(mixBits(mixBits(seed ^ mixBits(a)) ^ b) ^ c);
}

// Uniform in [0, 1).
constexpr float unitFloat(std::uint64_t bits)
{
    return static_cast<float>(bits >> 40) * (1.0f / 16777216.0f);
}

constexpr float randomUnit(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0, std::uint64_t c = 0)
{
    return unitFloat(hashKeys(seed, a, b, c));
}

} // namespace wisp
