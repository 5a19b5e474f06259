// Markdown and JSON rendering of a CalibrationResult (see calibrate_report.h).
// Numbers are printed with fixed printf formats so reports are byte-stable.
#include "sim/calibrate/calibrate_report.h"

#include <cmath>
#include <optional>
#include <cstdio>

namespace rtc {
namespace {

[[nodiscard]] std::string fmt(double x, const char* spec) {
    if (std::isnan(x)) return "n/a";
    if (std::isinf(x)) return "inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, spec, x);
    return buf;
}

[[nodiscard]] std::string label_of(const ParameterFit& p) {
    FitParameter f;
    f.events = p.events;
    return parameter_label(f) + (p.tie == Tie::Scale ? " (scale)" : "");
}

}  // namespace

std::string parameter_label(const FitParameter& p) {
    std::string s;
    for (Event e : p.events) {
        if (!s.empty()) s += '+';
        s += event_name(e);
    }
    return s;
}

std::optional<CostUncertainty> calibration_uncertainty(const CalibrationResult& result) {
    if (result.log_covariance.empty()) return std::nullopt;  // no free parameter, or dof <= 0: nothing to draw
    CostUncertainty u;
    u.source = "Gauss-Newton covariance sigma^2 (J^T J)^+ of the fit at its optimum, of log(value) over the free "
               "parameters (rtcsim calibrate, docs/calibration.md)";
    for (const ParameterFit& p : result.parameters)
        u.parameters.push_back({p.events, p.tie == Tie::Scale, p.fitted, p.lo, p.hi, p.free});
    u.covariance = result.log_covariance;
    return u;
}

std::string calibrated_preset_json(const CalibrationResult& result) {
    return cost_model_to_json(result.model);
}

std::string calibration_runs_markdown(const CalibrationResult& result) {
    std::string s = "| run | target | start | fitted | error % |\n|---|---|---|---|---|\n";
    for (const RunFit& r : result.runs)
        s += "| " + r.label + " | " + fmt(r.target, "%.3f") + " | " + fmt(r.start, "%.3f") +
             " | " + fmt(r.fitted, "%.3f") + " | " + fmt(100.0 * r.rel_error, "%+.2f") + " |\n";
    return s;
}

std::string calibration_parameters_markdown(const CalibrationResult& result) {
    std::string s =
        "| event | start | fitted | std. error | sensitivity | note |\n|---|---|---|---|---|---|\n";
    for (const ParameterFit& p : result.parameters)
        s += "| " + label_of(p) + " | " + fmt(p.start, "%.6g") + " | " + fmt(p.fitted, "%.6g") +
             " | " + fmt(p.std_error, "%.3g") + " | " + fmt(p.sensitivity, "%.3g") + " | " +
             p.note + " |\n";
    return s;
}

std::string calibration_report_markdown(const CalibrationResult& result) {
    std::string s = "RMS log error: start " + fmt(result.rms_log_error_start, "%.4g") +
                    ", fitted " + fmt(result.rms_log_error, "%.4g") + "; " +
                    std::to_string(result.observations) + " observations, " +
                    std::to_string(result.free_parameters) + " free parameters, " +
                    std::to_string(result.degrees_of_freedom) + " degrees of freedom; " +
                    std::to_string(result.iterations) + " iterations" +
                    (result.converged ? "" : " (NOT converged)") + ".\n\n";
    if (result.degrees_of_freedom <= 0)
        s += "Warning: no degrees of freedom left: the fit interpolates the targets and the "
             "error bars are not estimable.\n\n";
    return s + calibration_runs_markdown(result) + "\n" + calibration_parameters_markdown(result);
}

}  // namespace rtc
