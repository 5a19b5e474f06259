// A child as the traversal kernel (core/traverse.h) moves it: its
// (first, count) as one 64-bit word, so that it moves in one register (as a
// pair of fields it went through the stack frame: the head frame's traces
// wrote 10 % more and ran 3-5 % slower), with its entry distance.
#pragma once

#include "core/bvh.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace rtc {

struct ChildHit {
    std::uint64_t node;
    float tnear;
};

[[nodiscard, gnu::always_inline]] inline std::uint64_t child_word(const BvhLaneBlock::Child& c) {
    std::uint64_t w;
    std::memcpy(&w, &c, sizeof w);
    return w;
}

// An entry's (first, count), the same word (one 8-byte load).
[[nodiscard, gnu::always_inline]] inline std::uint64_t child_word(const BvhEntry& e) {
    static_assert(offsetof(BvhEntry, count) == offsetof(BvhEntry, first) + 4);
    std::uint64_t w;
    std::memcpy(&w, reinterpret_cast<const char*>(&e) + offsetof(BvhEntry, first), sizeof w);
    return w;
}

[[nodiscard, gnu::always_inline]] inline BvhLaneBlock::Child child_of_word(std::uint64_t w) {
    BvhLaneBlock::Child c;
    std::memcpy(&c, &w, sizeof c);
    return c;
}

}  // namespace rtc
