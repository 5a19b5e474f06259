// Runs a config from the command line: overrides, sweep expansion, each point
// through run_simulation, then the reports, pictures and summary tables.
#pragma once

#include "sim/app/cli.h"
#include "sim/app/calibrate_runs.h"
#include "sim/config/run_config.h"
#include "sim/config/sweep.h"
#include "sim/run/simulation.h"
#include "sim/run/work_estimate.h"

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace rtc {

// A config's runs before any work: `--set` overrides applied, the sweep
// expanded and every point parsed into its typed plan (scene checked, paths
// absolute, presets loaded once and shared), so a bad value anywhere fails
// in a second with the CLI's message ("<file>: <JSON path>: ..."), every
// point's. The Python module runs the same plan, so its errors and results
// are the CLI's. A run reads nothing but its RunConfig.
struct RunPlan {
    std::string file;                // where the config came from (messages, relative paths)
    nlohmann::json config;           // with the overrides, still with its sweep block
    std::vector<SweepPoint> points;  // one (empty label) for a run without a sweep
    std::vector<RunConfig> parsed;   // per point
    std::optional<CalibratePlan> calibrate;  // the `calibrate` block planned (start preset loaded), when there is one
    WorkLimits limits;               // checked here and again once each scene is loaded
    WorkEstimate work;               // over every point
    std::vector<std::string> command_line;  // for the reports' provenance (empty: not from the CLI)
};

// Throws InputError naming `file` and the JSON path, one line per error of
// every point, also when the work estimate exceeds `limits` (the CLI's
// --max-rays, --max-memory, --force).
// `sweep_order`: the sweep keys in written order (sweep_key_order of the
// config text), so the first key varies slowest.
[[nodiscard]] RunPlan plan_runs(nlohmann::json config, const std::string& file,
                                const std::vector<std::string>& sets = {}, const WorkLimits& limits = {},
                                const std::vector<std::string>& sweep_order = {});

// The number of points a config's `sweep` block expands to, computed without
// expanding it; throws InputError naming /sweep above the limit (unless
// forced) or on overflow.
[[nodiscard]] double sweep_point_count(const nlohmann::json& config, const std::string& file,
                                       const WorkLimits& limits);

// Runs point `i` of a plan under the plan's limits (its sweep values, label
// and provenance set on the result).
[[nodiscard]] RunResult run_point(const RunPlan& plan, std::size_t i, RunContext context);

// Point `i` priced from `traced`, the result of another point of the plan
// with the same trace (same_trace: only cost/memory presets differ), without
// tracing; nullopt when it cannot be (see reprice_run).
[[nodiscard]] std::optional<RunResult> reprice_point(const RunPlan& plan, std::size_t i, const RunResult& traced,
                                                     unsigned threads);

// The plan of a config given as text (as read from `file`), with the
// command line's overrides and limits; the sweep runs in written key order.
[[nodiscard]] RunPlan plan_config_text(const std::string& file, const std::string& text,
                                       const std::vector<std::string>& sets, const WorkLimits& limits);

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
