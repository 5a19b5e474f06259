// Shared helpers for the tests of the SIMT model's pricing (tests/execution,
// tests/sim): random program-call profiles and bit equality of doubles, for
// comparing a fast pricing path with its lane-by-lane reference.
#pragma once

#include "sim/hardware/call_profiles.h"

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace rtc::test {

// `count` call profiles, each program event counted 0-39 times.
[[nodiscard]] inline std::vector<ProgramCounts> random_program_calls(std::mt19937& rng, int count) {
    std::vector<ProgramCounts> calls;
    for (int k = 0; k < count; ++k) {
        ProgramCounts c;
        for (const std::uint8_t e : kProgramEvents) c.n[kProgramSlot[e]] = static_cast<std::uint16_t>(rng() % 40);
        calls.push_back(c);
    }
    return calls;
}

// The same double bit for bit (signed zeros and NaN payloads included).
[[nodiscard]] inline bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace rtc::test
