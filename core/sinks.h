// Event sinks: where traversal and intersectors report events.
//
// A sink is a template parameter, never a virtual interface, so the null sink
// compiles to nothing and the counting sink to an increment of a local array.
#pragma once

#include "core/events.h"

#include <array>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
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
    void clear() {
#if defined(__SSE2__)
        constexpr std::size_t kVectors = sizeof n / 16;
        for (std::size_t v = 0; v < kVectors; ++v)
            _mm_storeu_si128(reinterpret_cast<__m128i*>(n.data()) + v, _mm_setzero_si128());
        for (std::size_t i = kVectors * 4; i < kEventCount; ++i) n[i] = 0;
#else
        n.fill(0);
#endif
    }

    [[nodiscard]] std::uint32_t operator[](Event e) const { return n[static_cast<std::size_t>(e)]; }
    RayCounts& operator+=(const RayCounts& o) {
        for (std::size_t i = 0; i < kEventCount; ++i) n[i] += o.n[i];
        return *this;
    }
};

// Totals over many rays; 64-bit so billions of box tests do not wrap.
struct EventTotals {
    std::array<std::uint64_t, kEventCount> n{};

    [[nodiscard]] std::uint64_t operator[](Event e) const { return n[static_cast<std::size_t>(e)]; }
    void add(const RayCounts& c) {
        for (std::size_t i = 0; i < kEventCount; ++i) n[i] += c.n[i];
    }
    // The sum of many rays' (or pixels') counts, exactly add() on each. Sums
    // up to kChunk of them in 32-bit lanes (four per SSE add, no widening),
    // together with the OR of every count: a chunk whose counts are all below
    // 2^24 sums to below kChunk * 2^24 = 2^32, so its 32-bit sums did not
    // wrap; a chunk with a larger count is summed again in 64 bits.
    void add_all(const RayCounts* c, std::size_t count) {
        constexpr std::size_t kChunk = 256;
        constexpr std::uint32_t kLimit = 1u << 24;  // kChunk * kLimit == 2^32
        for (std::size_t begin = 0; begin < count; begin += kChunk) {
            const std::size_t end = begin + kChunk < count ? begin + kChunk : count;
            RayCounts sum, seen;
            for (std::size_t r = begin; r < end; ++r)
                for (std::size_t i = 0; i < kEventCount; ++i) {
                    sum.n[i] += c[r].n[i];
                    seen.n[i] |= c[r].n[i];
                }
            std::uint32_t any = 0;
            for (std::size_t i = 0; i < kEventCount; ++i) any |= seen.n[i];
            if (any < kLimit) {
                add(sum);
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
