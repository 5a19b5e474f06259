// A small seeded generator (SplitMix64) for the scene generators. Written out
// rather than std::mt19937 + std distributions because the standard
// distributions differ between library implementations, and a scene must be
// the same on every machine for a given seed.
#pragma once

#include <cstdint>

namespace rtc {

class SceneRng {
public:
    explicit SceneRng(std::uint64_t seed) : state_(seed) {}

    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1) with 53 random bits.
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    std::uint64_t state_;
};

}  // namespace rtc
