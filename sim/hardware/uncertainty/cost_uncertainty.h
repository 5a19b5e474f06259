// The calibration uncertainty of a fitted cost preset (its optional
// "uncertainty" block, docs/calibration.md): the fitted parameters, and the
// Gauss-Newton covariance of the log of the free ones at the optimum. Runs
// price every method under N cost models drawn from it and report the 90 %
// interval of each speedup. It covers how well the fit's targets determine
// the fitted costs, not whether the model's structure is right.
//
// In its own folder because sim/hardware is at its file budget
// (tests/sim/test_architecture.cpp).
#pragma once

#include "core/events.h"

// json_fwd, not json.hpp: every method includes this header (through
// cost_model.h), and parsing json.hpp costs each of them about 2.5 CPU-s.
#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

class JsonReader;
struct CostModel;

// One fitted number of the calibration (calibrate.h's FitParameter at its optimum).
struct UncertainParameter {
    std::vector<Event> events;  // each event in one parameter only (empty: none taken from the fit)
    bool scale = false;  // tie "scale": the events cost their start cost x value; "value": each costs value
    double value = 0.0;  // fitted: cycles ("value"), or the factor ("scale")
    double lo = 0.0, hi = 0.0;  // the fit's bounds; draws are clamped into them
    bool free = false;   // has a row in the covariance: not at a bound, identifiable
};

struct CostUncertainty {
    std::string source;  // how the covariance was made
    std::vector<UncertainParameter> parameters;
    // Covariance of log(value) over the free parameters, in their order: the
    // fit's Jacobian is value-scaled, so log space is where it is Gaussian to
    // first order, and a draw exp(z) x value stays positive.
    std::vector<std::vector<double>> covariance;
    // The workload the fit saw, as JSON text (empty: not given); text so that
    // this struct needs no complete JSON type.
    std::string fitted_on_json;

    [[nodiscard]] std::size_t free_count() const;
};

// Reads a preset's "uncertainty" block against the preset's costs (a "value"
// parameter's events must cost its value). Checks that the covariance is
// square over the free parameters, finite, symmetric and positive
// semi-definite (Cholesky with a small tolerance). Errors name the file and
// JSON path, e.g. "x.json: /uncertainty/covariance/1/2: ...".
[[nodiscard]] CostUncertainty parse_cost_uncertainty(const JsonReader& block,
                                                     const std::array<double, kEventCount>& cycles);
[[nodiscard]] nlohmann::ordered_json cost_uncertainty_to_json(const CostUncertainty& u);

// Lower-triangular L with L L^T = cov, a zero column where cov is singular;
// throws std::invalid_argument (with "row/column") when cov is not PSD.
[[nodiscard]] std::vector<std::vector<double>> psd_cholesky(const std::vector<std::vector<double>>& cov);

// `n` copies of `model` with the free parameters drawn from N(log value, cov)
// (multivariate normal through the Cholesky factor; normals from splitmix64
// and Box-Muller, so the same seed gives the same draws on every platform's
// standard library), truncated to the bounds by rejection: a draw with any
// parameter outside its [lo, hi] is drawn again, so every draw lies on the
// fit's own ridge (clamping one parameter would pair it with the others'
// values the fit never paired it with). Parameters fitted at a bound are not
// free and stay at their value in every draw. Throws std::runtime_error when
// fewer than 1 in kMaxDrawAttempts draws fall inside the bounds. Empty when
// the model has no uncertainty block. Draw d is the same whichever method it
// prices.
inline constexpr std::size_t kMaxDrawAttempts = 10000;
[[nodiscard]] std::vector<CostModel> draw_cost_models(const CostModel& model, std::size_t n, std::uint64_t seed);

// [5th, 95th] percentile of `samples` (linear interpolation between order
// statistics), widened to contain `point` when it falls outside.
[[nodiscard]] std::array<double, 2> interval_90(std::vector<double> samples, double point);

}  // namespace rtc
