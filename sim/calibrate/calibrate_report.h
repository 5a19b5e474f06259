// Output of a calibration: the fitted preset as configs/hw JSON and Markdown
// tables of the fit (per run, per parameter, with a summary of how honest
// the fit is: RMS log error, observations, free parameters, dof).
#pragma once

#include "sim/calibrate/calibrate.h"

#include <optional>
#include <string>

namespace rtc {

// The fitted parameters and their covariance as a preset's "uncertainty"
// block (cost_uncertainty.h); nullopt when the fit has no covariance.
[[nodiscard]] std::optional<CostUncertainty> calibration_uncertainty(const CalibrationResult& result);
// The fitted model in the configs/hw preset format (cost_model_to_json), with
// its "uncertainty" block when the fit has a covariance.
[[nodiscard]] std::string calibrated_preset_json(const CalibrationResult& result);
// "| run | target | start | fitted | error % |"
[[nodiscard]] std::string calibration_runs_markdown(const CalibrationResult& result);
// "| event | start | fitted | std. error | sensitivity | note |"
[[nodiscard]] std::string calibration_parameters_markdown(const CalibrationResult& result);
// Summary line, then both tables.
[[nodiscard]] std::string calibration_report_markdown(const CalibrationResult& result);

}  // namespace rtc
