// Calibration: recovery of known costs from synthetic counts, bounds,
// identifiability flags, error bars and determinism (sim/calibrate.h).
#include "sim/calibrate/calibrate.h"
#include "sim/calibrate/calibrate_report.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// A deterministic generator of plausible counts (no <random>: its
// distributions differ between standard libraries).
struct Lcg {
    std::uint64_t s;
    double next() {  // in [0, 1)
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(s >> 11) * 0x1.0p-53;
    }
    std::uint64_t count(double lo, double hi) { return static_cast<std::uint64_t>(lo + (hi - lo) * next()); }
};

CostModel guess_model() {
    CostModel m;
    m.name = "test-guess";
    m.description = "test";
    m[Event::Ray] = 400;
    m[Event::TlasNodeVisit] = 8;
    m[Event::TlasBoxTest] = 4;
    m[Event::InstanceTransform] = 8;
    m[Event::BlasNodeVisit] = 8;
    m[Event::BlasBoxTest] = 4;
    m[Event::TriangleTest] = 8;
    m[Event::ContextSwitch] = 200;
    m[Event::IsCylinder] = 120;
    m[Event::IsCapsule] = 150;
    m[Event::ReportedHit] = 50;
    for (auto& s : m.source) s = "guess";
    return m;
}

CostModel true_model() {
    CostModel m = guess_model();
    m[Event::ContextSwitch] = 310;
    m[Event::IsCylinder] = 85;
    m[Event::TlasBoxTest] = 6.5;
    m[Event::BlasBoxTest] = 6.5;
    return m;
}

// Runs shaped like the synthetic experiment: the reference method does many
// context switches, the masquerade method many more box tests and transforms.
std::vector<CalibrationRun> synthetic_runs(const CostModel& truth, int n = 8) {
    Lcg rng{12345};
    std::vector<CalibrationRun> runs;
    for (int i = 0; i < n; ++i) {
        CalibrationRun r;
        r.label = "run" + std::to_string(i);
        const std::uint64_t rays = 640000;
        const double thin = 1.0 + 30.0 * rng.next();  // how much the AABBs overestimate
        const double hits = 0.2 + 0.3 * rng.next();
        r.ref.n[static_cast<std::size_t>(Event::Ray)] = rays;
        r.ref.n[static_cast<std::size_t>(Event::TlasNodeVisit)] = rays;
        r.ref.n[static_cast<std::size_t>(Event::TlasBoxTest)] = 2 * rays;
        r.ref.n[static_cast<std::size_t>(Event::InstanceTransform)] = rays;
        r.ref.n[static_cast<std::size_t>(Event::BlasNodeVisit)] = rng.count(5, 15) * rays;
        r.ref.n[static_cast<std::size_t>(Event::BlasBoxTest)] = rng.count(20, 60) * rays;
        const auto is_ref = static_cast<std::uint64_t>(hits * thin * rays);
        r.ref.n[static_cast<std::size_t>(Event::ContextSwitch)] = is_ref;
        r.ref.n[static_cast<std::size_t>(Event::IsCall)] = is_ref;
        // Mixed primitive kinds, so is_cylinder is not collinear with context_switch.
        const double cyl = 0.3 + 0.7 * rng.next();
        r.ref.n[static_cast<std::size_t>(Event::IsCylinder)] = static_cast<std::uint64_t>(cyl * is_ref);
        r.ref.n[static_cast<std::size_t>(Event::ReportedHit)] = static_cast<std::uint64_t>(hits * rays);
        r.obb = r.ref;
        r.obb.n[static_cast<std::size_t>(Event::TlasNodeVisit)] = rng.count(5, 15) * rays;
        r.obb.n[static_cast<std::size_t>(Event::TlasBoxTest)] = rng.count(20, 80) * rays;
        r.obb.n[static_cast<std::size_t>(Event::InstanceTransform)] = static_cast<std::uint64_t>(thin * rays * (1 + rng.next()));
        r.obb.n[static_cast<std::size_t>(Event::BlasNodeVisit)] = r.obb[Event::InstanceTransform];
        r.obb.n[static_cast<std::size_t>(Event::BlasBoxTest)] = r.obb[Event::InstanceTransform];
        const auto is_obb = static_cast<std::uint64_t>(hits * rays * (1.0 + 0.5 * rng.next()));
        r.obb.n[static_cast<std::size_t>(Event::ContextSwitch)] = is_obb;
        r.obb.n[static_cast<std::size_t>(Event::IsCall)] = is_obb;
        r.obb.n[static_cast<std::size_t>(Event::IsCylinder)] = static_cast<std::uint64_t>(cyl * is_obb);
        r.target_speedup = predicted_speedup(r, truth);
        runs.push_back(r);
    }
    return runs;
}

std::vector<FitParameter> three_parameters() {
    return {{{Event::ContextSwitch}, 50, 1000, Tie::Value},
            {{Event::IsCylinder}, 0, 500, Tie::Value},
            {{Event::TlasBoxTest, Event::BlasBoxTest}, 1, 32, Tie::Value}};
}

}  // namespace

TEST_CASE("calibrate: recovers known costs from exact targets") {
    const CostModel truth = true_model();
    const auto runs = synthetic_runs(truth);
    const CalibrationResult res = calibrate(runs, guess_model(), three_parameters());
    CHECK(res.converged);
    CHECK(res.rms_log_error_start > 0.01);
    CHECK(res.rms_log_error < 1e-9);
    for (Event e : {Event::ContextSwitch, Event::IsCylinder, Event::TlasBoxTest, Event::BlasBoxTest})
        CHECK(res.model[e] == doctest::Approx(truth[e]).epsilon(1e-3));
    CHECK(res.model[Event::Ray] == 400);  // not fitted: untouched
    CHECK(res.model.source[static_cast<std::size_t>(Event::Ray)] == "guess");
    CHECK(res.model.source[static_cast<std::size_t>(Event::ContextSwitch)] ==
          "fitted by rtcsim calibrate to target speedups, was 200");
    CHECK(res.model.name == "test-guess-calibrated");
    for (const RunFit& r : res.runs) CHECK(std::abs(r.rel_error) < 1e-8);
    CHECK(res.observations == 8);
    CHECK(res.free_parameters == 3);
    CHECK(res.degrees_of_freedom == 5);
    for (const ParameterFit& p : res.parameters) {
        CHECK_FALSE(p.unidentifiable);
        CHECK_FALSE(p.at_lower);
        CHECK_FALSE(p.at_upper);
        CHECK(p.std_error < 1e-6 * p.fitted);  // exact targets: ~zero error bars
        CHECK(p.sensitivity > 1e-3);
        CHECK(p.note.empty());
    }
}

TEST_CASE("calibrate: noisy targets give finite error bars and honest dof") {
    auto runs = synthetic_runs(true_model());
    Lcg rng{7};
    for (CalibrationRun& r : runs) r.target_speedup *= std::exp(0.05 * (rng.next() - 0.5));
    const CalibrationResult res = calibrate(runs, guess_model(), three_parameters());
    CHECK(res.rms_log_error > 1e-4);
    CHECK(res.rms_log_error < res.rms_log_error_start);
    CHECK(res.degrees_of_freedom == 5);
    for (const ParameterFit& p : res.parameters) {
        CHECK(std::isfinite(p.std_error));
        CHECK(p.std_error > 0);
    }
    // As many runs as parameters: the fit interpolates, no error estimate.
    runs.resize(3);
    const CalibrationResult exact = calibrate(runs, guess_model(), three_parameters());
    CHECK(exact.degrees_of_freedom == 0);
    for (const ParameterFit& p : exact.parameters) {
        CHECK(std::isnan(p.std_error));
        CHECK(p.note.find("degrees of freedom") != std::string::npos);
    }
    CHECK(calibration_report_markdown(exact).find("no degrees of freedom") != std::string::npos);
}

TEST_CASE("calibrate: a target needing a negative cost stops at the bound and is flagged") {
    auto runs = synthetic_runs(true_model());
    CostModel zero_cs = guess_model();
    zero_cs[Event::ContextSwitch] = 0;
    for (CalibrationRun& r : runs) r.target_speedup = 0.8 * predicted_speedup(r, zero_cs);
    const std::vector<FitParameter> params = {{{Event::ContextSwitch}, 0, 1000, Tie::Value}};
    const CalibrationResult res = calibrate(runs, guess_model(), params);
    CHECK(res.model[Event::ContextSwitch] == 0.0);
    CHECK(res.parameters[0].at_lower);
    CHECK_FALSE(res.parameters[0].at_upper);
    CHECK(res.parameters[0].note.find("at lower bound") != std::string::npos);
    CHECK(std::isnan(res.parameters[0].std_error));
    CHECK(res.free_parameters == 0);
    // Upper bound: the truth (310) lies above max = 250.
    CostModel truth = guess_model();
    truth[Event::ContextSwitch] = 310;
    const std::vector<FitParameter> capped = {{{Event::ContextSwitch}, 50, 250, Tie::Value}};
    const CalibrationResult up = calibrate(synthetic_runs(truth), guess_model(), capped);
    CHECK(up.model[Event::ContextSwitch] == 250.0);
    CHECK(up.parameters[0].at_upper);
}

TEST_CASE("calibrate: a parameter with no counts is flagged unidentifiable, the rest still fit") {
    const CostModel truth = true_model();
    auto params = three_parameters();
    params.push_back({{Event::IsCapsule}, 10, 500, Tie::Value});  // never counted
    const CalibrationResult res = calibrate(synthetic_runs(truth), guess_model(), params);
    CHECK(res.parameters[3].unidentifiable);
    CHECK(std::isinf(res.parameters[3].std_error));
    CHECK(res.parameters[3].sensitivity == 0.0);
    CHECK(res.parameters[3].fitted == 150.0);  // left at its start
    CHECK(res.parameters[3].note.find("UNIDENTIFIABLE") != std::string::npos);
    CHECK(res.free_parameters == 3);
    CHECK(res.model[Event::ContextSwitch] == doctest::Approx(truth[Event::ContextSwitch]).epsilon(1e-3));
}

TEST_CASE("calibrate: events that always occur together are flagged, their sum still fits") {
    auto runs = synthetic_runs(true_model());
    for (CalibrationRun& r : runs) {  // every context switch runs the cylinder program
        r.ref.n[static_cast<std::size_t>(Event::IsCylinder)] = r.ref[Event::ContextSwitch];
        r.obb.n[static_cast<std::size_t>(Event::IsCylinder)] = r.obb[Event::ContextSwitch];
        r.target_speedup = predicted_speedup(r, true_model());
    }
    const CalibrationResult res = calibrate(runs, guess_model(), three_parameters());
    CHECK(res.parameters[0].unidentifiable);
    CHECK(res.parameters[1].unidentifiable);
    CHECK_FALSE(res.parameters[2].unidentifiable);
    CHECK(res.free_parameters == 1);
    CHECK(res.model[Event::ContextSwitch] + res.model[Event::IsCylinder] ==
          doctest::Approx(310 + 85).epsilon(1e-6));
    CHECK(res.rms_log_error < 1e-9);
}

TEST_CASE("calibrate: fitting every priced event is scale-free and flagged") {
    // Speedups are ratios: scaling every cost leaves them unchanged, so with
    // no fixed cost the targets cannot determine the level.
    std::vector<FitParameter> params;
    const CostModel start = guess_model();
    for (std::size_t i = 0; i < kEventCount; ++i)
        if (start.cycles[i] > 0) params.push_back({{static_cast<Event>(i)}, 0.5, 5, Tie::Scale});
    const CalibrationResult res = calibrate(synthetic_runs(true_model()), start, params);
    int flagged = 0;
    for (const ParameterFit& p : res.parameters) flagged += p.unidentifiable ? 1 : 0;
    CHECK(flagged >= 2);
}

TEST_CASE("calibrate: a scale tie keeps the ratio of the tied start costs") {
    CostModel start = guess_model();
    start[Event::BlasBoxTest] = 6;
    CostModel truth = start;
    truth[Event::TlasBoxTest] = 4 * 1.7;
    truth[Event::BlasBoxTest] = 6 * 1.7;
    truth[Event::ContextSwitch] = 310;
    const std::vector<FitParameter> params = {{{Event::ContextSwitch}, 50, 1000, Tie::Value},
                                              {{Event::TlasBoxTest, Event::BlasBoxTest}, 0.25, 4, Tie::Scale}};
    const CalibrationResult res = calibrate(synthetic_runs(truth), start, params);
    CHECK(res.parameters[1].start == 1.0);
    CHECK(res.parameters[1].fitted == doctest::Approx(1.7).epsilon(1e-6));
    CHECK(res.model[Event::BlasBoxTest] == doctest::Approx(10.2).epsilon(1e-6));
    CHECK(res.model[Event::ContextSwitch] == doctest::Approx(310).epsilon(1e-6));
}

TEST_CASE("calibrate: weights, validation and determinism") {
    auto runs = synthetic_runs(true_model());
    runs[0].target_speedup *= 3.0;  // an outlier ...
    runs[0].weight = 0.0;           // ... ignored
    const CalibrationResult res = calibrate(runs, guess_model(), three_parameters());
    CHECK(res.observations == 7);
    CHECK(res.runs[0].rel_error == doctest::Approx(-2.0 / 3.0).epsilon(1e-6));
    CHECK(res.model[Event::ContextSwitch] == doctest::Approx(310).epsilon(1e-6));

    const CalibrationResult again = calibrate(runs, guess_model(), three_parameters());
    CHECK(calibration_report_markdown(res) == calibration_report_markdown(again));
    CHECK(calibrated_preset_json(res) == calibrated_preset_json(again));
    CHECK(calibration_runs_markdown(res).find("| run0 | ") != std::string::npos);
    CHECK(calibration_parameters_markdown(res).find("| tlas_box_test+blas_box_test | 4 | 6.5") !=
          std::string::npos);

    auto bad = runs;
    bad[1].target_speedup = -1;
    CHECK_THROWS_AS((void)calibrate(bad, guess_model(), three_parameters()), std::invalid_argument);
    auto dup = three_parameters();
    dup.push_back({{Event::BlasBoxTest}, 0, 10, Tie::Value});
    CHECK_THROWS_AS((void)calibrate(runs, guess_model(), dup), std::invalid_argument);
    auto neg = three_parameters();
    neg[1].lo = -5;
    CHECK_THROWS_AS((void)calibrate(runs, guess_model(), neg), std::invalid_argument);
    CHECK_THROWS_AS((void)calibrate({}, guess_model(), neg), std::invalid_argument);
}

TEST_CASE("calibrate: one-parameter std. error equals sigma / |J| by finite differences") {
    CostModel truth = guess_model();
    truth[Event::ContextSwitch] = 310;
    auto runs = synthetic_runs(truth);
    Lcg rng{99};
    for (CalibrationRun& r : runs) r.target_speedup *= std::exp(0.04 * (rng.next() - 0.5));
    const std::vector<FitParameter> params = {{{Event::ContextSwitch}, 50, 1000, Tie::Value}};
    const CalibrationResult res = calibrate(runs, guess_model(), params);
    const double x = res.model[Event::ContextSwitch], h = 1e-3;
    CostModel lo = res.model, hi = res.model;
    lo[Event::ContextSwitch] = x - h;
    hi[Event::ContextSwitch] = x + h;
    double jj = 0, ssr = 0, jr = 0;
    for (const CalibrationRun& r : runs) {
        const double j = (std::log(predicted_speedup(r, hi)) - std::log(predicted_speedup(r, lo))) / (2 * h);
        const double rr = std::log(predicted_speedup(r, res.model) / r.target_speedup);
        jj += j * j, ssr += rr * rr, jr += j * rr;
    }
    CHECK(std::abs(jr) < 1e-6 * std::sqrt(jj * ssr));  // stationary: J^T r = 0
    CHECK(res.degrees_of_freedom == 7);
    CHECK(res.parameters[0].std_error == doctest::Approx(std::sqrt(ssr / 7 / jj)).epsilon(1e-5));
    CHECK(res.rms_log_error == doctest::Approx(std::sqrt(ssr / 8)).epsilon(1e-9));
}

TEST_CASE("calibrate: the fitted preset carries the covariance, and loads back") {
    auto runs = synthetic_runs(true_model());
    Lcg rng{7};
    for (CalibrationRun& r : runs) r.target_speedup *= std::exp(0.05 * (rng.next() - 0.5));
    std::vector<FitParameter> params = three_parameters();
    params.push_back({{Event::IsCapsule}, 150, 400, Tie::Value});  // no counts: unidentifiable, not free
    const CalibrationResult res = calibrate(runs, guess_model(), params);
    REQUIRE(res.model.uncertainty);
    const CostUncertainty& u = *res.model.uncertainty;
    REQUIRE(u.parameters.size() == 4);
    CHECK_FALSE(u.parameters[3].free);
    REQUIRE(res.log_covariance.size() == 3);
    REQUIRE(u.covariance == res.log_covariance);
    for (std::size_t k = 0; k < 3; ++k) {  // its diagonal is the std. errors, relative
        CHECK(u.parameters[k].free);
        const ParameterFit& p = res.parameters[k];
        CHECK(std::sqrt(u.covariance[k][k]) == doctest::Approx(p.std_error / p.fitted).epsilon(1e-9));
    }
    const std::string text = calibrated_preset_json(res);
    const CostModel back = parse_cost_model(text, "fitted.json");
    REQUIRE(back.uncertainty);
    CHECK(back.uncertainty->covariance == u.covariance);
    CHECK(cost_model_to_json(back) == text);
    CHECK(draw_cost_models(back, 8, 1).size() == 8);
    // No degrees of freedom: no covariance, and no block.
    runs.resize(3);
    CHECK_FALSE(calibrate(runs, guess_model(), three_parameters()).model.uncertainty);
}

}  // namespace RTCSIM_TEST_FILE
