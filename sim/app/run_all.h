// Runs a config from the command line: overrides, sweep expansion, each point
// through run_simulation, then the reports, pictures and summary tables.
#pragma once

#include "sim/app/cli.h"
#include "sim/app/calibrate_runs.h"
#include "sim/config/plan.h"
#include "sim/config/run_config.h"
#include "sim/config/sweep.h"
#include "sim/run/simulation.h"
#include "sim/config/work_estimate.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace rtc {

// Runs point `i` of a plan under the plan's limits (its sweep values, label
// and provenance set on the result).
[[nodiscard]] RunResult run_point(const RunPlan& plan, std::size_t i, RunContext context);

// Point `i` priced from `traced`, the result of another point of the plan
// with the same trace (same_trace: only cost/memory presets differ), without
// tracing; nullopt when it cannot be (see reprice_run).
[[nodiscard]] std::optional<RunResult> reprice_point(const RunPlan& plan, std::size_t i, const RunResult& traced,
                                                     unsigned threads);

// Returns the process exit code. Throws InputError on bad input.
int run_all(const CliOptions& cli);

// Each method's frame of each sweep point, assembled rather than traced
// (`simulate merge`).
using PointFrames = std::function<FrameResult(std::size_t point, const std::string& method)>;

// Runs every point of `plan` and writes every output into `out` (prepared
// by the caller); with `frames`, points take their frames from it.
int run_planned(const RunPlan& plan, const CliOptions& cli, const std::string& out, const PointFrames* frames);

// `simulate CONFIG --estimate --target-error E` (docs/sampling.md): traces a
// pilot sample of every sweep point and suggests the sampling fraction whose
// 95 % intervals on every speedup are within +/-E.
// One JSON line per sweep point (its pilot, its widest speedup interval and
// the fraction it needs), then the suggestion over all points.
int print_sampling_estimate(const CliOptions& cli);

}  // namespace rtc
