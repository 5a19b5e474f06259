// Calibration: fit chosen per-event costs so that predicted speedups
// (cycles of the reference method / cycles of the masquerade method, both
// priced with one CostModel) match target speedups, e.g. the synthetic table
// of Wald et al. 2020 (docs/calibration.md).
//
// Tracing happens once per run elsewhere; the fit only re-prices recorded
// EventTotals, so it is cheap. It minimizes
//     sum_i weight_i * (log predicted_i - log target_i)^2
// over the fitted costs within bounds, by a deterministic bounded
// Levenberg-Marquardt with the exact Jacobian (speedups are ratios of sums
// linear in the costs), and reports how well each cost is determined.
#pragma once

#include "core/sinks.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/warp_trace.h"

#include <memory>

#include <string>
#include <vector>

namespace rtc {

// One run: the counts of both methods on the same scene and rays.
struct CalibrationRun {
    std::string label;
    EventTotals ref;  // the baseline's counts (per-ray model)
    EventTotals obb;  // the calibrated method's
    // The traced waves (SIMT model): when both are set and the model is a
    // warp model, cycles come from re-pricing them (per-ray counts otherwise).
    std::shared_ptr<const WarpTrace> ref_warps, obb_warps;
    double target_speedup = 1.0;  // cycles(ref) / cycles(obb) to reproduce; > 0
    double weight = 1.0;          // >= 0
    // The SM each method's waves run on (its pipeline's resident warps).
    Roofline ref_roof = {}, obb_roof = {};
};

// How the events of one FitParameter share the fitted number.
enum class Tie {
    Value,  // every event costs the fitted value (bounds are in cycles)
    Scale,  // every event costs its starting cost x the fitted factor (bounds
            // are on the dimensionless factor, which starts at 1)
};

// One fitted number; several events may share it.
struct FitParameter {
    std::vector<Event> events;  // non-empty; an event may appear in one parameter only
    double lo = 0.0;            // >= 0: no negative cycles
    double hi = 1e6;            // >= lo
    Tie tie = Tie::Value;
};

struct CalibrationOptions {
    std::string target_name = "target speedups";  // "<what>" in the provenance
    std::string name;         // of the fitted model; empty: "<start name>-calibrated"
    std::string description;  // empty: keep the start model's
    int max_iterations = 200;
};

struct RunFit {
    std::string label;
    double target = 0.0;
    double start = 0.0;      // speedup predicted by the start model
    double fitted = 0.0;     // ... by the fitted model
    double rel_error = 0.0;  // fitted / target - 1
};

struct ParameterFit {
    std::vector<Event> events;
    Tie tie = Tie::Value;
    double lo = 0.0, hi = 0.0;
    double start = 0.0;   // starting value (Tie::Scale: 1)
    double fitted = 0.0;
    // Standard error of `fitted` from the Gauss-Newton covariance
    // sigma^2 (J^T J)^+ with sigma^2 = SSR / dof. NaN when not estimable (at a
    // bound, or dof <= 0); +inf when unidentifiable.
    double std_error = 0.0;
    // RMS over runs of d log(speedup) / d log(value): how much the speedups
    // move per relative change of this parameter (0: no influence at all).
    double sensitivity = 0.0;
    bool at_lower = false, at_upper = false;
    bool unidentifiable = false;  // no influence, or a near-null direction of J
    bool free = false;            // has a finite std. error: a row of log_covariance
    std::string note;             // human-readable summary of the flags
};

struct CalibrationResult {
    CostModel model;  // the start model with fitted costs and provenance
    std::vector<RunFit> runs;
    std::vector<ParameterFit> parameters;
    double rms_log_error_start = 0.0;  // sqrt(sum w r^2 / sum w), r = log(pred/target)
    double rms_log_error = 0.0;
    int observations = 0;        // runs with weight > 0
    int free_parameters = 0;     // fitted, not at a bound, identifiable
    int degrees_of_freedom = 0;  // observations - free_parameters (may be <= 0)
    int iterations = 0;
    bool converged = false;
    // sigma^2 (J^T J)^+ at the optimum, as the covariance of log(fitted) over
    // the free parameters in their order (empty when dof <= 0 or none is
    // free). model.uncertainty carries it into the fitted preset.
    std::vector<std::vector<double>> log_covariance;
};

// Throws std::invalid_argument on unusable input (no runs, a non-positive
// target, bad bounds, an event in two parameters, non-positive start cycles).
[[nodiscard]] CalibrationResult calibrate(const std::vector<CalibrationRun>& runs,
                                          const CostModel& start,
                                          const std::vector<FitParameter>& params,
                                          const CalibrationOptions& options = {});

// Predicted speedup of one run under a model: cycles(ref) / cycles(obb).
[[nodiscard]] double predicted_speedup(const CalibrationRun& run, const CostModel& model);

// Names of a parameter's events joined by "+" ("tlas_box_test+blas_box_test").
[[nodiscard]] std::string parameter_label(const FitParameter& p);

}  // namespace rtc
