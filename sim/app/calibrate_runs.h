// `simulate calibrate` on finished runs: each run paired with its target in
// the config's `calibrate` block, and the block's costs fitted by re-pricing
// the recorded counts (and, under a warp preset, the recorded waves). No
// tracing: the CLI and the Python module both fit runs they already traced.
#pragma once

#include "sim/calibrate/calibrate.h"
#include "sim/calibrate/calibrate_config.h"
#include "sim/run/simulation.h"


#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rtc {

// A method's recorded waves for the fit, or nullptr (its per-ray counts are
// used). The CLI moves them out of its runs; the Python module shares them.
using WarpTraceSource = std::function<std::shared_ptr<const WarpTrace>(RunResult&, MethodRun&)>;

struct CalibrationOutcome {
    CalibrateDesc desc;
    CalibrationResult result;
    std::vector<std::string> skipped;  // labels of runs without a target (or not runnable)
};

// The fit of `plan` on `runs`. It starts from the block's `start` preset,
// else from the first run's primary cost preset. Throws InputError on a
// target that matches no run, or no run with a target.
[[nodiscard]] CalibrationOutcome calibrate_results(std::span<RunResult* const> runs, const CalibratePlan& plan,
                                                   const WarpTraceSource& warps);

// Where `simulate calibrate` writes the fitted preset besides the output
// directory: the block's `output`; "" when it has none. Throws InputError
// naming /calibrate/output when that file exists (a shipped or installed
// preset above all) and `force` is false.
[[nodiscard]] std::string calibrate_output_path(const CalibratePlan& plan, bool force);

}  // namespace rtc
