// Event sinks: where traversal and intersectors report events.
//
// A sink is a template parameter, never a virtual interface, so the null sink
// compiles to nothing and the counting sink to an increment of a local array.
#pragma once

#include "core/events.h"

#include <array>
#include <cstddef>
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
            sum_chunk(c + begin, end - begin, sum, seen);
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

private:
    // The 32-bit sums and ORs of `count` counts. With SSE the counts are read
    // in groups of kGroup (two 26-count RayCounts are 13 whole vectors): lane
    // sums per group word, in two passes over half the words each so that
    // every sum and OR stays in a register, then folded per event. About
    // half the instructions of a loop over each RayCounts's 6.5 vectors.
    static void sum_chunk(const RayCounts* c, std::size_t count, RayCounts& sum, RayCounts& seen) {
        sum.clear();
        seen.clear();
        std::size_t done = 0;
#if defined(__SSE2__)
        static_assert(sizeof(RayCounts) == kEventCount * sizeof(std::uint32_t));
        constexpr std::size_t kGroup = kEventCount % 4 == 0 ? 1 : kEventCount % 2 == 0 ? 2 : 4;
        constexpr std::size_t kWords = kGroup * kEventCount, kVectors = kWords / 4;
        static_assert(kWords % 4 == 0);
        const std::size_t groups = count / kGroup;
        const auto* words = reinterpret_cast<const std::uint32_t*>(c);
        alignas(16) std::uint32_t lane_sum[kWords], lane_seen[kWords];
        // Aligned groups (the usual case: an even-width row of a frame whose
        // array is 16-byte aligned) let each add and OR read memory itself.
        if (reinterpret_cast<std::uintptr_t>(words) % 16 == 0) {
            sum_lanes<0, kVectors / 2, kWords, true>(words, groups, lane_sum, lane_seen);
            sum_lanes<kVectors / 2, kVectors - kVectors / 2, kWords, true>(words, groups, lane_sum, lane_seen);
        } else {
            sum_lanes<0, kVectors / 2, kWords, false>(words, groups, lane_sum, lane_seen);
            sum_lanes<kVectors / 2, kVectors - kVectors / 2, kWords, false>(words, groups, lane_sum, lane_seen);
        }
        for (std::size_t g = 0; g < kGroup; ++g)
            for (std::size_t i = 0; i < kEventCount; ++i) {
                sum.n[i] += lane_sum[g * kEventCount + i];
                seen.n[i] |= lane_seen[g * kEventCount + i];
            }
        done = groups * kGroup;
#endif
        for (std::size_t r = done; r < count; ++r)
            for (std::size_t i = 0; i < kEventCount; ++i) {
                sum.n[i] += c[r].n[i];
                seen.n[i] |= c[r].n[i];
            }
    }

#if defined(__SSE2__)
    // Vectors [First, First + N) of each of `groups` groups of kWords words:
    // their lane sums and ORs into sum[4 First, 4 (First + N)) and seen[...].
    template <std::size_t First, std::size_t N, std::size_t kWords, bool kAligned>
    [[gnu::always_inline]] static void sum_lanes(const std::uint32_t* words, std::size_t groups,
                                                 std::uint32_t* sum, std::uint32_t* seen) {
        __m128i s[N], o[N];
        for (std::size_t v = 0; v < N; ++v) s[v] = o[v] = _mm_setzero_si128();
        for (std::size_t g = 0; g < groups; ++g) {
            const std::uint32_t* p = words + g * kWords + First * 4;
#pragma GCC unroll 16
            for (std::size_t v = 0; v < N; ++v) {
                const auto* at = reinterpret_cast<const __m128i*>(p + 4 * v);
                const __m128i x = kAligned ? _mm_load_si128(at) : _mm_loadu_si128(at);
                s[v] = _mm_add_epi32(s[v], x);
                o[v] = _mm_or_si128(o[v], x);
            }
        }
        for (std::size_t v = 0; v < N; ++v) {
            _mm_store_si128(reinterpret_cast<__m128i*>(sum + 4 * (First + v)), s[v]);
            _mm_store_si128(reinterpret_cast<__m128i*>(seen + 4 * (First + v)), o[v]);
        }
    }
#endif
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
