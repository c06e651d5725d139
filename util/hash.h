#pragma once
/// Counter-based randomness: values are pure functions of (seed, counters), never of thread or
/// call order, so every output is bitwise reproducible for a seed.

#include <cstdint>

namespace nenrin {

/// SplitMix64 finaliser: a strong 64-bit mix.
constexpr uint64_t mix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

constexpr uint64_t hashCombine(uint64_t seed, uint64_t value) { return mix64(seed ^ mix64(value)); }

/// Uniform double in [0, 1) from (seed, a, b).
constexpr double uniform01(uint64_t seed, uint64_t a, uint64_t b = 0) {
    return static_cast<double>(hashCombine(hashCombine(seed, a), b) >> 11) * 0x1.0p-53;
}

/// A small sequential generator (for generators that draw many numbers in a fixed order).
class SplitMix {
public:
    explicit SplitMix(uint64_t seed) : state_(seed) {}
    uint64_t next() { return mix64(state_++); }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    uint64_t state_;
};

}  // namespace nenrin
