// Summing many records of E 32-bit counts (a frame row's per-pixel event
// counts) in SIMD lanes: the per-word sums and ORs of `count` records, which
// EventTotals::add_all (core/sinks.h) turns into exact 64-bit totals.
//
// Records are read in groups whose words fill whole vectors: with W words per
// vector, a group is W / gcd(E, W) records, W / gcd(E, W) * E / W vectors.
// Each pass keeps at most kPassVectors sums and as many ORs in registers
// (with 16 vector registers, 7 + 7 and one spare), reading every group's
// vectors [first, first + kPassVectors) as operands of its adds and ORs; the
// passes together cover the group, and their lane results are folded per
// word at the end. A pass that kept more than that spilled its sums to the
// stack at every group: with 31 events, two passes of 15 and 16 vectors cost
// 47 instructions per pixel, seven passes of AVX2 vectors about 10.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <utility>


namespace rtc::count_sums {

inline constexpr std::size_t kPassVectors = 7;

// 32-bit lanes of one vector width, as GCC/clang vector types: with the
// intrinsics' __m256i (four 64-bit lanes) an add on eight 32-bit lanes
// changed the value's mode, and GCC copied every sum to a new register at
// each add. Loads and stores are unaligned (memcpy).
template <std::size_t kBytes>
struct Lanes {
    using V [[gnu::vector_size(kBytes)]] = std::uint32_t;
    static constexpr std::size_t kWords = kBytes / 4;
    static V zero() { return V{}; }
    static V load(const std::uint32_t* p) {
        V v;
        std::memcpy(&v, p, sizeof v);
        return v;
    }
    static V add(V a, V b) { return a + b; }
    static V bit_or(V a, V b) { return a | b; }
    static void store(std::uint32_t* p, V v) { std::memcpy(p, &v, sizeof v); }
};

// Vectors [First, First + N) of each of `groups` groups of kVectors vectors:
// their lane sums and ORs into sum[...] and seen[...] at the same words. The
// vectors are indexed by a pack, not a loop: GCC kept a looped array of
// vector sums on the stack (a store and a reload per add), with constant
// indices it keeps each in a register.
template <class L, std::size_t kVectors, std::size_t First, std::size_t... I>
[[gnu::always_inline]] inline void sum_pass(const std::uint32_t* words, std::size_t groups, std::uint32_t* sum,
                                            std::uint32_t* seen, std::index_sequence<I...>) {
    typename L::V s[sizeof...(I)] = {((void)I, L::zero())...};
    typename L::V o[sizeof...(I)] = {((void)I, L::zero())...};
    const std::uint32_t* p = words + First * L::kWords;
    const std::uint32_t* const end = p + groups * kVectors * L::kWords;
    do {
        ((o[I] = L::bit_or(o[I], L::load(p + I * L::kWords))), ...);
        ((s[I] = L::add(s[I], L::load(p + I * L::kWords))), ...);
        p += kVectors * L::kWords;
    } while (p != end);
    (L::store(sum + (First + I) * L::kWords, s[I]), ...);
    (L::store(seen + (First + I) * L::kWords, o[I]), ...);
}

template <class L, std::size_t kVectors, std::size_t First = 0>
[[gnu::always_inline]] inline void sum_passes(const std::uint32_t* words, std::size_t groups, std::uint32_t* sum,
                                              std::uint32_t* seen) {
    constexpr std::size_t N = kVectors - First < kPassVectors ? kVectors - First : kPassVectors;
    sum_pass<L, kVectors, First>(words, groups, sum, seen, std::make_index_sequence<N>());
    if constexpr (First + N < kVectors) sum_passes<L, kVectors, First + N>(words, groups, sum, seen);
}

// Adds the words of the whole groups among `count` records of E words at
// `words` into sum[0, E) and ORs them into seen[0, E); returns how many
// records that was (the rest are the caller's).
template <class L, std::size_t E>
std::size_t sum_groups(const std::uint32_t* words, std::size_t count, std::uint32_t* sum, std::uint32_t* seen) {
    constexpr std::size_t kGroup = L::kWords / std::gcd(E, L::kWords);
    constexpr std::size_t kVectors = kGroup * E / L::kWords;
    const std::size_t groups = count / kGroup;
    if (groups == 0) return 0;
    alignas(32) std::uint32_t lane_sum[kGroup * E], lane_seen[kGroup * E];
    sum_passes<L, kVectors>(words, groups, lane_sum, lane_seen);
    for (std::size_t g = 0; g < kGroup; ++g)
        for (std::size_t i = 0; i < E; ++i) {
            sum[i] += lane_sum[g * E + i];
            seen[i] |= lane_seen[g * E + i];
        }
    return groups * kGroup;
}

// The per-word sums (wrapping at 2^32) and ORs of `count` records of E words:
// 32-byte vectors first (with AVX2: as two 16-byte halves they would not fit
// the registers), then 16-byte ones, then one record at a time.
template <std::size_t E>
void sum_records(const std::uint32_t* words, std::size_t count, std::uint32_t* sum, std::uint32_t* seen) {
    for (std::size_t i = 0; i < E; ++i) sum[i] = seen[i] = 0;
    std::size_t done = 0;
#if defined(__AVX2__)
    done += sum_groups<Lanes<32>, E>(words, count, sum, seen);
#endif
    done += sum_groups<Lanes<16>, E>(words + done * E, count - done, sum, seen);
    for (std::size_t r = done; r < count; ++r)
        for (std::size_t i = 0; i < E; ++i) {
            sum[i] += words[r * E + i];
            seen[i] |= words[r * E + i];
        }
}

// to[i] += from[i] for E words: 32-byte vectors (with AVX2), then 16-byte
// ones, then one at a time (GCC's -O2 left a loop of 31 adds scalar).
template <std::size_t E>
[[gnu::always_inline]] inline void add_words(std::uint32_t* to, const std::uint32_t* from) {
    std::size_t i = 0;
#if defined(__AVX2__)
    for (; i + 8 <= E; i += 8) Lanes<32>::store(to + i, Lanes<32>::add(Lanes<32>::load(to + i), Lanes<32>::load(from + i)));
#endif
    for (; i + 4 <= E; i += 4) Lanes<16>::store(to + i, Lanes<16>::add(Lanes<16>::load(to + i), Lanes<16>::load(from + i)));
    for (; i < E; ++i) to[i] += from[i];
}

}  // namespace rtc::count_sums
