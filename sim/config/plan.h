// The plan of a config: everything a run needs, parsed and checked before
// any work. `plan_runs` reads the config's JSON once (with the `--set`
// overrides), expands the sweep, parses every point into its typed RunConfig
// (presets loaded once and shared), plans the `calibrate` block and checks
// the work estimate. After planning nothing reads the config's JSON again:
// sim/run takes a RunConfig, `simulate calibrate` a CalibratePlan.
#pragma once

#include "sim/calibrate/calibrate_config.h"
#include "sim/config/run_config.h"
#include "sim/config/sweep.h"
#include "sim/config/work_estimate.h"

#include <nlohmann/json.hpp>

#include <optional>
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

// The plan of a config given as text (as read from `file`), with the
// command line's overrides and limits; the sweep runs in written key order.
[[nodiscard]] RunPlan plan_config_text(const std::string& file, const std::string& text,
                                       const std::vector<std::string>& sets, const WorkLimits& limits);

}  // namespace rtc
