// Distinct intersection-program call profiles (each call's own events).
// The SIMT model prices a round by its most expensive call, so it needs every
// call's events; but a frame's calls share a handful of profiles (a capsule
// miss, a capsule hit, a phantom call with k iterations, ...). A call's
// events are counted in a few bytes (ProgramCounts, program events only) and
// kept as a 2-byte id into this table: recording is a comparison with the
// previous call (the usual case) or a hash lookup, and pricing is one table
// lookup per call.
#pragma once

#include "core/sinks.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#if defined(__AVX2__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace rtc {

// Program events (event unit Program) and their slots in ProgramCounts.
inline constexpr auto kProgramEvents = events_of_unit<EventUnit::Program>();
inline constexpr std::size_t kProgramEventCount = kProgramEvents.size();
inline constexpr auto kProgramSlot = [] {  // event -> slot (0xFF: not a program event)
    std::array<std::uint8_t, kEventCount> s{};
    for (auto& x : s) x = 0xFF;
    for (std::size_t k = 0; k < kProgramEventCount; ++k) s[kProgramEvents[k]] = static_cast<std::uint8_t>(k);
    return s;
}();

// One call's program events (a call counts at most a few hundred of each),
// padded to whole 8-byte words so equality is a few word compares.
inline constexpr std::size_t kProgramSlots = (kProgramEventCount + 3) / 4 * 4;

struct ProgramCounts {
    std::array<std::uint16_t, kProgramSlots> n{};

    [[nodiscard]] std::uint32_t operator[](Event e) const {
        const std::uint8_t s = kProgramSlot[static_cast<std::size_t>(e)];
        return s == 0xFF ? 0u : n[s];
    }
    // Once per program call: 32-byte (AVX2) or 16-byte compares, then the
    // last 8 bytes (the 2-vector form this replaces required exactly 16
    // slots and had not applied since there are 20).
    [[nodiscard]] bool operator==(const ProgramCounts& o) const {
        constexpr std::size_t kBytes = sizeof n;
        static_assert(kBytes % 8 == 0);
        std::size_t b = 0;
#if defined(__AVX2__)
        for (; b + 32 <= kBytes; b += 32)
            if (_mm256_movemask_epi8(_mm256_cmpeq_epi8(load32(b), o.load32(b))) != -1) return false;
#endif
#if defined(__SSE2__)
        __m128i eq = _mm_set1_epi8(-1);
        for (; b + 16 <= kBytes; b += 16) eq = _mm_and_si128(eq, _mm_cmpeq_epi8(load16(b), o.load16(b)));
        if (_mm_movemask_epi8(eq) != 0xFFFF) return false;
#endif
        for (; b < kBytes; b += 8)
            if (word(b) != o.word(b)) return false;
        return true;
    }
    [[nodiscard]] RayCounts ray_counts() const {
        RayCounts c;
        for (std::size_t k = 0; k < kProgramEventCount; ++k) c.n[kProgramEvents[k]] = n[k];
        return c;
    }

private:
    [[nodiscard]] std::uint64_t word(std::size_t byte) const {
        std::uint64_t w;
        std::memcpy(&w, reinterpret_cast<const char*>(n.data()) + byte, 8);
        return w;
    }
#if defined(__AVX2__)
    [[nodiscard]] __m256i load32(std::size_t byte) const {
        return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(reinterpret_cast<const char*>(n.data()) + byte));
    }
#endif
#if defined(__SSE2__)
    [[nodiscard]] __m128i load16(std::size_t byte) const {
        return _mm_loadu_si128(reinterpret_cast<const __m128i*>(reinterpret_cast<const char*>(n.data()) + byte));
    }
#endif
};

// Counts a call into the ray's sink and, apart, into the call's own counts.
struct CallSink {
    static constexpr bool kCounts = true;
    CountingSink& ray;
    ProgramCounts& call;

    void on(Event e) { add(e, 1); }
    void add(Event e, std::uint32_t k) {
        ray.add(e, k);
        const std::uint8_t s = kProgramSlot[static_cast<std::size_t>(e)];
        if (s != 0xFF) call.n[s] = static_cast<std::uint16_t>(call.n[s] + k);
    }
};

// Each program call's own counts during one ray, in call order: one zeroed
// slot per call, from storage kept across rays. add() is inline:
// std::vector's emplace_back stayed an out-of-line call (27 instructions per
// program call, case 1 ref).
class CallCounts {
public:
    CallCounts() = default;
    // A copy has its own slots (the pointers are rebased; moves copy too).
    CallCounts(const CallCounts& o) { *this = o; }
    CallCounts& operator=(const CallCounts& o) {
        if (this == &o) return *this;
        const std::size_t used = o.size();
        slots_ = o.slots_;
        next_ = slots_.data() + used;
        end_ = slots_.data() + slots_.size();
        return *this;
    }
    [[gnu::always_inline]] ProgramCounts& add() {
        if (next_ == end_) [[unlikely]]
            grow();
        ProgramCounts& c = *next_++;
        c = ProgramCounts{};
        return c;
    }
    void clear() { next_ = slots_.data(); }
    [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(next_ - slots_.data()); }
    [[nodiscard]] const ProgramCounts* begin() const { return slots_.data(); }
    [[nodiscard]] const ProgramCounts* end() const { return next_; }

private:
    // Pointers, not an index: no multiply by the slot size per call.
    [[gnu::noinline]] void grow() {
        const std::size_t used = size();
        slots_.resize(std::max<std::size_t>(64, 2 * slots_.size()));
        next_ = slots_.data() + used;
        end_ = slots_.data() + slots_.size();
    }
    std::vector<ProgramCounts> slots_;
    ProgramCounts* next_ = nullptr;  // the next free slot
    ProgramCounts* end_ = nullptr;   // past the last slot
};

class CallProfiles {
public:
    using Id = std::uint16_t;

    // The id of `c`, adding it when new. Throws std::length_error past 65,536
    // distinct profiles. Inline fast path: the same profile as the last call.
    Id id(const ProgramCounts& c) {
        if (has_last_ && last_counts_ == c) return last_;  // a copy here: no bounds check, no indirection
        return find_or_add(c);
    }
    [[nodiscard]] const ProgramCounts& operator[](Id i) const { return profiles_[i]; }
    [[nodiscard]] std::size_t size() const { return profiles_.size(); }

private:
    Id find_or_add(const ProgramCounts& c);
    std::vector<ProgramCounts> profiles_;
    std::unordered_multimap<std::uint64_t, Id> index_;  // hash -> id
    Id last_ = 0;
    ProgramCounts last_counts_;  // profiles_[last_]
    bool has_last_ = false;
};

}  // namespace rtc
