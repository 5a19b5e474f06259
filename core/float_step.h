// One float step up or down: std::nextafter(x, +-infinity) without the call
// into libm (the conservative box and OBB roundings of every build take a
// step in about half their components: 275 M of the head frame's 8.3 G build
// instructions went to nextafterf). Exactly nextafter's results for every
// float, tested against it (tests/core/test_core_float_step.cpp): on the bit
// pattern a step away from zero is +1 and towards zero -1; zeros step to the
// smallest denormal of the direction's sign, infinities in their own
// direction stay, NaNs stay NaN.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace rtc {

// std::nextafter(x, +infinity).
[[nodiscard]] inline float float_step_up(float x) {
    if (!(x < std::numeric_limits<float>::infinity())) return x;  // +inf, NaN
    if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(x);
    return std::bit_cast<float>(x > 0.0f ? bits + 1u : bits - 1u);
}

// std::nextafter(x, -infinity).
[[nodiscard]] inline float float_step_down(float x) {
    if (!(x > -std::numeric_limits<float>::infinity())) return x;  // -inf, NaN
    if (x == 0.0f) return -std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(x);
    return std::bit_cast<float>(x > 0.0f ? bits - 1u : bits + 1u);
}

}  // namespace rtc
