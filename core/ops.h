// What an intersection program executes, as counts of a few operation classes
// (the op_* events of core/events.h), so a preset can price programs by their
// work instead of by name (docs/execution-model.md, "Program costs").
//
// Each program tallies, per exit, the operations of the path that led there,
// as a GPU would run it in FP32: the simulator computes in double for exact
// hits (intersectors/span.h), but the counted work is the program's, not the
// CPU's. A tally is a constexpr sum of the steps the comments beside it name,
// with these conventions:
//   fma:    each FP32 add, subtract, multiply, fused multiply-add, min, max,
//           abs or select; a 3-vector sum or scale is 3, a dot product 3, a
//           cross product 6, a length 3 plus one sqrt;
//   div:    each division or reciprocal (a division by a shared value is one
//           reciprocal and multiplies);
//   sqrt:   each square root or reciprocal square root;
//   branch: each compare-and-branch that can end the call or choose a path;
//   load:   each 16-byte load of the primitive's data (a capsule's 28 B: 2).
// One count_ops() per call (at its exit): a handful of adds on the hot path.
#pragma once

#include "core/events.h"

#include <cstdint>

namespace rtc {

struct Ops {
    std::uint16_t fma = 0, div = 0, sqrt = 0, branch = 0, load = 0;

    [[nodiscard]] constexpr Ops operator+(const Ops& o) const {
        return {static_cast<std::uint16_t>(fma + o.fma), static_cast<std::uint16_t>(div + o.div),
                static_cast<std::uint16_t>(sqrt + o.sqrt), static_cast<std::uint16_t>(branch + o.branch),
                static_cast<std::uint16_t>(load + o.load)};
    }
    [[nodiscard]] constexpr bool operator==(const Ops&) const = default;
};

// Counts `times` executions of `ops` into the sink (nothing for a sink that
// does not count). No branch per class: where `ops` is a constant the
// compiler drops the additions of zero, elsewhere five adds beat five tests.
template <class Sink>
[[gnu::always_inline]] inline void count_ops(Sink& sink, const Ops& ops, std::uint32_t times = 1) {
    if constexpr (Sink::kCounts) {
        sink.add(Event::OpFma, ops.fma * times);
        sink.add(Event::OpDiv, ops.div * times);
        sink.add(Event::OpSqrt, ops.sqrt * times);
        sink.add(Event::OpBranch, ops.branch * times);
        sink.add(Event::OpLoad, ops.load * times);
    }
}

}  // namespace rtc
