// Runs a config from the command line: overrides, sweep expansion, each point
// through run_simulation, then the reports, pictures and summary tables.
#pragma once

#include "sim/app/cli.h"
#include "sim/config/run_config.h"
#include "sim/config/sweep.h"
#include "sim/run/simulation.h"
#include "sim/run/work_estimate.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

// A config's runs before any work: `--set` overrides applied, the sweep
// expanded and every point parsed, so a bad value fails in a second with the
// CLI's message ("<file>: <JSON path>: ..."). The Python module runs the same
// plan, so its errors and results are the CLI's.
struct RunPlan {
    std::string file;                // where the config came from (messages, relative paths)
    nlohmann::json config;           // with the overrides, still with its sweep block
    std::vector<SweepPoint> points;  // one (empty label) for a run without a sweep
    std::vector<RunConfig> parsed;   // per point
    WorkLimits limits;               // checked here and again once each scene is loaded
    WorkEstimate work;               // over every point
};

// Throws InputError naming `file` and the JSON path, also when the work
// estimate exceeds `limits` (the CLI's --max-rays, --max-memory, --force).
[[nodiscard]] RunPlan plan_runs(nlohmann::json config, const std::string& file,
                                const std::vector<std::string>& sets = {}, const WorkLimits& limits = {});

// Runs point `i` of a plan under the plan's limits (its sweep values and
// label set on the result).
[[nodiscard]] RunResult run_point(const RunPlan& plan, std::size_t i, RunContext context);

// Returns the process exit code. Throws InputError on bad input.
int run_all(const CliOptions& cli);

}  // namespace rtc
