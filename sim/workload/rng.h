// Counter-based random numbers for ray generation.
//
// Every random number a workload uses is a pure function of
// (seed, pixel x, pixel y, sample, dimension): no generator state is carried
// from one ray to the next, so both methods, any thread count and any order of
// work produce bit-identical rays. The mixing is a chain of 64-bit avalanche
// finalizers (the splitmix64 / MurmurHash3 fmix64 family): each input word is
// folded into the running hash and the result is re-mixed, so neighbouring
// counters give unrelated outputs.
#pragma once

#include <cstdint>

namespace rtc {

// 64-bit avalanche mix: every input bit affects every output bit.
[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    x ^= x >> 31;
    return x;
}

// Folds one more 32-bit word into a running hash.
[[nodiscard]] constexpr std::uint64_t hash_combine(std::uint64_t h, std::uint32_t word) {
    return mix64(h ^ (static_cast<std::uint64_t>(word) + 0x9E3779B97F4A7C15ull + (h << 6) +
                      (h >> 2)));
}

// Maps the top 24 bits of a hash to a float in [0, 1): exactly representable,
// never 1.0f.
[[nodiscard]] constexpr float to_unit_float(std::uint64_t h) {
    return static_cast<float>(static_cast<std::uint32_t>(h >> 40)) * (1.0f / 16777216.0f);
}

// The random stream of one camera sample: a key fixed by (seed, pixel,
// sample); `uniform(dim)` is the dimension-th number of that stream. Cheap to
// construct (four mixes), trivially copyable, no global state.
class SampleRng {
public:
    constexpr SampleRng(std::uint32_t seed, std::uint32_t px, std::uint32_t py,
                        std::uint32_t sample)
        : key_(hash_combine(hash_combine(hash_combine(mix64(0x5EED0000ull + seed), px), py),
                            sample)) {}

    [[nodiscard]] constexpr float uniform(std::uint32_t dim) const {
        return to_unit_float(hash_combine(key_, dim));
    }
    [[nodiscard]] constexpr std::uint64_t bits(std::uint32_t dim) const {
        return hash_combine(key_, dim);
    }

private:
    std::uint64_t key_;
};

// One uniform float in [0, 1) for (seed, px, py, sample, dim).
[[nodiscard]] constexpr float uniform_float(std::uint32_t seed, std::uint32_t px,
                                            std::uint32_t py, std::uint32_t sample,
                                            std::uint32_t dim) {
    return SampleRng(seed, px, py, sample).uniform(dim);
}

// Fixed dimension layout shared by every workload, so a given random number
// always drives the same decision: the pixel jitter, then a block per bounce.
namespace rng_dim {
inline constexpr std::uint32_t kPixelX = 0;
inline constexpr std::uint32_t kPixelY = 1;
inline constexpr std::uint32_t kPerBounce = 4;  // direction u, v, roulette, spare
[[nodiscard]] constexpr std::uint32_t bounce(std::uint32_t depth, std::uint32_t k) {
    return 2 + depth * kPerBounce + k;
}
}  // namespace rng_dim

}  // namespace rtc
