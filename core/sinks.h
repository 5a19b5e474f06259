// Event sinks: where traversal and intersectors report events.
//
// A sink is a template parameter, never a virtual interface, so the null sink
// compiles to nothing and the counting sink to an increment of a local array.
#pragma once

#include "core/count_sums.h"
#include "core/events.h"

#include <array>
#include <cstddef>
#include <cstdint>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace rtc {

// Discards everything; used when only the hits matter.
struct NullSink {
    static constexpr bool kCounts = false;
    void on(Event) {}
    void add(Event, std::uint32_t) {}
};

// Event counts of one ray (or one pixel), small enough to live in registers /
// on the stack while the ray is traced.
struct RayCounts {
    std::array<std::uint32_t, kEventCount> n{};

    // Zeroes the counts with vector stores: a new RayCounts{} per pixel
    // compiled to `rep stos`, 14 instructions to callgrind and slow to start.
    // With AVX, whole 32-byte stores, the last one overlapping the one before
    // when the counts are not a multiple of 8 (4 stores for 31 counts, not 9).
    void clear() {
#if defined(__AVX__)
        static_assert(sizeof n >= 32);
        for (std::size_t b = 0; b + 32 <= sizeof n; b += 32) store32(b, _mm256_setzero_si256());
        if (sizeof n % 32) store32(sizeof n - 32, _mm256_setzero_si256());
#elif defined(__SSE2__)
        constexpr std::size_t kVectors = sizeof n / 16;
        for (std::size_t v = 0; v < kVectors; ++v)
            _mm_storeu_si128(reinterpret_cast<__m128i*>(n.data()) + v, _mm_setzero_si128());
        for (std::size_t i = kVectors * 4; i < kEventCount; ++i) n[i] = 0;
#else
        n.fill(0);
#endif
    }

    // `*this = from` in the same overlapping 32-byte moves (the plain copy
    // was 8 loads and 8 stores of 16 bytes).
    void copy_from(const RayCounts& from) {
#if defined(__AVX__)
        for (std::size_t b = 0; b + 32 <= sizeof n; b += 32) store32(b, from.load32(b));
        if (sizeof n % 32) store32(sizeof n - 32, from.load32(sizeof n - 32));
#else
        *this = from;
#endif
    }

    [[nodiscard]] std::uint32_t operator[](Event e) const { return n[static_cast<std::size_t>(e)]; }
    [[gnu::always_inline]] RayCounts& operator+=(const RayCounts& o) {
        count_sums::add_words<kEventCount>(n.data(), o.n.data());
        return *this;
    }

private:
#if defined(__AVX__)
    [[nodiscard]] __m256i load32(std::size_t byte) const {
        return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(reinterpret_cast<const char*>(n.data()) + byte));
    }
    void store32(std::size_t byte, __m256i v) {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(reinterpret_cast<char*>(n.data()) + byte), v);
    }
#endif
};

// Totals over many rays; 64-bit so billions of box tests do not wrap.
struct EventTotals {
    std::array<std::uint64_t, kEventCount> n{};

    [[nodiscard]] std::uint64_t operator[](Event e) const { return n[static_cast<std::size_t>(e)]; }
    void add(const RayCounts& c) {
        for (std::size_t i = 0; i < kEventCount; ++i) n[i] += c.n[i];
    }
    // The sum of many rays' (or pixels') counts, exactly add() on each. Sums
    // up to kChunk of them in 32-bit lanes (core/count_sums.h: eight per
    // AVX2 add, no widening), together with the OR of every count: a chunk
    // whose counts are all below 2^24 sums to below kChunk * 2^24 = 2^32, so
    // its 32-bit sums did not wrap; a chunk with a larger count is summed
    // again in 64 bits.
    void add_all(const RayCounts* c, std::size_t count) {
        static_assert(sizeof(RayCounts) == kEventCount * sizeof(std::uint32_t));
        constexpr std::size_t kChunk = 256;
        constexpr std::uint32_t kLimit = 1u << 24;  // kChunk * kLimit == 2^32
        for (std::size_t begin = 0; begin < count; begin += kChunk) {
            const std::size_t end = begin + kChunk < count ? begin + kChunk : count;
            // Not RayCounts (zeroed on construction: `rep stos`), sum_records zeroes them.
            std::uint32_t sum[kEventCount], seen[kEventCount];
            count_sums::sum_records<kEventCount>(reinterpret_cast<const std::uint32_t*>(c + begin), end - begin,
                                                 sum, seen);
            std::uint32_t any = 0;
            for (std::size_t i = 0; i < kEventCount; ++i) any |= seen[i];
            if (any < kLimit) {
                for (std::size_t i = 0; i < kEventCount; ++i) n[i] += sum[i];
            } else {
                for (std::size_t r = begin; r < end; ++r) add(c[r]);
            }
        }
    }
    EventTotals& operator+=(const EventTotals& o) {
        for (std::size_t i = 0; i < kEventCount; ++i) n[i] += o.n[i];
        return *this;
    }
    bool operator==(const EventTotals&) const = default;

};

// Counts the events of the ray being traced. The owner flushes `ray` into its
// per-thread totals once per ray (no atomics, no globals) and resets it.
struct CountingSink {
    static constexpr bool kCounts = true;
    RayCounts ray;

    void on(Event e) { ++ray.n[static_cast<std::size_t>(e)]; }
    void add(Event e, std::uint32_t k) { ray.n[static_cast<std::size_t>(e)] += k; }
};

}  // namespace rtc
