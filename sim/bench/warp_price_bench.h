// `bench --warp-price` (issue 39): what the SIMT model costs the simulator,
// as a ratio measured side by side in one process. For each of a run's
// methods, per-ray and warp traces of the same frame are timed alternately
// (per-ray, warp, per-ray, ...), so that both see the same machine load, and
// warp's time over per-ray's is taken pair by pair. Both must count the same
// events and rays (the warp model only groups and prices what per-ray
// tracing counts); a difference is reported and fails the command.
#pragma once

#include "sim/bench/bench_run.h"

namespace rtc {

// Times `run` as above under options.warp_preset and prints it; returns
// false when the two executions' counts differ.
[[nodiscard]] bool compare_warp_price(const BenchRun& run, const BenchOptions& options);

}  // namespace rtc
