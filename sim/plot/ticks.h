// Axis ticks shared by the heat-map colour bars and the SVG plots: "nice"
// linear steps (1, 2, 5 x 10^k) and log-scale ticks at decades (with 2 and 5
// in between when the range spans few decades), each with its label text.
#pragma once

#include <string>
#include <vector>

namespace rtc {

struct Tick {
    double value = 0.0;
    std::string label;
};

// Ticks at multiples of a nice step inside [lo, hi], aiming for about
// `target` of them. Empty for a non-finite or empty range (lo > hi).
[[nodiscard]] std::vector<Tick> linear_ticks(double lo, double hi, int target = 5);

// Ticks for a log axis over [lo, hi], 0 < lo <= hi: decades, thinned when
// there are many, refined with 2 and 5 (then linear ticks) when few.
[[nodiscard]] std::vector<Tick> log_ticks(double lo, double hi);

// Label for a linear tick at `value` on a grid of `step`: just enough
// decimals for the step; 12000 -> "12k", 3500000 -> "3.5M".
[[nodiscard]] std::string format_tick(double value, double step);

}  // namespace rtc
