// The "uncertainty" block of a cost preset (sim/hardware/uncertainty):
// parsed strictly with the JSON path in every error, written back unchanged,
// drawn deterministically (clamped into the bounds), and the 90 % interval
// always contains the point estimate.
#include "core/input_error.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// turing-per-ray-guess with a block over context_switch (value 200) and a scale on
// the box tests; `covariance` over those two free parameters.
nlohmann::json preset_json(const nlohmann::json& covariance) {
    nlohmann::json j = nlohmann::json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-per-ray-guess.json"));
    j["uncertainty"] = {
        {"source", "test"},
        {"parameters",
         {{{"events", {"context_switch"}}, {"tie", "value"}, {"value", 200}, {"min", 50}, {"max", 1000}, {"free", true}},
          {{"events", {"tlas_box_test", "blas_box_test"}}, {"tie", "scale"}, {"value", 1.0}, {"min", 0.5}, {"max", 3}, {"free", true}},
          {{"events", {"is_capsule"}}, {"value", 150}, {"min", 150}, {"max", 400}, {"free", false}}}},
        {"covariance", covariance},
        {"fitted_on", {{"workload", "test"}}}};
    return j;
}

const nlohmann::json kCov = {{0.04, 0.01}, {0.01, 0.09}};

std::string error_of(const nlohmann::json& j) {
    try {
        (void)parse_cost_model(j.dump(), "p.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("cost uncertainty: parsed, written back, and optional") {
    const CostModel m = parse_cost_model(preset_json(kCov).dump(), "p.json");
    REQUIRE(m.uncertainty);
    CHECK(m.uncertainty->free_count() == 2);
    CHECK(m.uncertainty->parameters[1].scale);
    CHECK(m.uncertainty->covariance[1][0] == 0.01);
    CHECK(nlohmann::json::parse(m.uncertainty->fitted_on_json)["workload"] == "test");
    const std::string text = cost_model_to_json(m);
    CHECK(cost_model_to_json(parse_cost_model(text, "q.json")) == text);
    nlohmann::json plain = preset_json(kCov);
    plain.erase("uncertainty");
    CHECK_FALSE(parse_cost_model(plain.dump(), "p.json").uncertainty);
    CHECK(cost_model_to_json(parse_cost_model(plain.dump(), "p.json")).find("uncertainty") == std::string::npos);
}

TEST_CASE("cost uncertainty: errors name the JSON path") {
    CHECK(error_of(preset_json({{0.04, 0.01}, {0.02, 0.09}})).find("p.json: /uncertainty/covariance/1/0: not symmetric") == 0);
    CHECK(error_of(preset_json({{0.04, 0.01}, {0.01, "x"}})).find("p.json: /uncertainty/covariance/1/1: expected a finite number") == 0);
    CHECK(error_of(preset_json({{0.04, 0.01}})).find("p.json: /uncertainty/covariance: 1 rows for 2 free parameters") == 0);
    CHECK(error_of(preset_json({{0.04, 0.01}, {0.01}})).find("p.json: /uncertainty/covariance/1: expected a row of 2") == 0);
    // |correlation| > 1: not a covariance.
    CHECK(error_of(preset_json({{0.04, 0.1}, {0.1, 0.09}})).find("p.json: /uncertainty/covariance/1/1: not positive semi-definite") == 0);
    CHECK(error_of(preset_json({{-0.04, 0}, {0, 0.09}})).find("p.json: /uncertainty/covariance/0/0: not positive semi-definite") == 0);
    nlohmann::json j = preset_json(kCov);
    j["uncertainty"]["parameters"][0]["value"] = 210;  // the preset prices context_switch at 200
    CHECK(error_of(j).find("p.json: /uncertainty/parameters/0/value: the preset prices context_switch at 200") == 0);
    j = preset_json(kCov);
    j["uncertainty"]["parameters"][2]["events"] = {"context_swich"};
    CHECK(error_of(j).find("p.json: /uncertainty/parameters/2/events/0: unknown event") == 0);
    j = preset_json(kCov);
    j["uncertainty"]["variance"] = 1;
    CHECK(error_of(j).find("p.json: /uncertainty/variance: unknown key") == 0);
    // A singular (rank-one) covariance is fine: one direction has no variance.
    CHECK(error_of(preset_json({{0.04, 0.06}, {0.06, 0.09}})).empty());
}

TEST_CASE("cost uncertainty: draws are deterministic, clamped and shrink with the covariance") {
    const CostModel m = parse_cost_model(preset_json(kCov).dump(), "p.json");
    const std::vector<CostModel> a = draw_cost_models(m, 400, 7), b = draw_cost_models(m, 400, 7);
    REQUIRE(a.size() == 400);
    double sum = 0.0, sum2 = 0.0;
    for (std::size_t d = 0; d < a.size(); ++d) {
        CHECK(a[d].cycles == b[d].cycles);
        CHECK_FALSE(a[d].uncertainty);
        const double cs = a[d][Event::ContextSwitch];
        CHECK(cs >= 50);
        CHECK(cs <= 1000);
        CHECK(a[d][Event::TlasBoxTest] / 4.0 == doctest::Approx(a[d][Event::BlasBoxTest] / 4.0));  // one scale
        CHECK(a[d][Event::TlasBoxTest] >= 0.5 * 4 - 1e-12);
        CHECK(a[d][Event::IsCapsule] == 150);  // not free: never drawn
        sum += std::log(cs / 200.0), sum2 += std::log(cs / 200.0) * std::log(cs / 200.0);
    }
    CHECK(draw_cost_models(m, 4, 8)[0].cycles != a[0].cycles);
    const double mean = sum / 400.0, sd = std::sqrt(sum2 / 400.0 - mean * mean);
    CHECK(std::abs(mean) < 0.05);
    CHECK(sd == doctest::Approx(0.2).epsilon(0.15));
    // A quarter of the covariance: half the spread.
    const CostModel q = parse_cost_model(preset_json({{0.01, 0.0025}, {0.0025, 0.0225}}).dump(), "p.json");
    const std::vector<CostModel> c = draw_cost_models(q, 400, 7);
    for (std::size_t d = 0; d < 10; ++d)
        CHECK(std::log(c[d][Event::ContextSwitch] / 200.0) == doctest::Approx(0.5 * std::log(a[d][Event::ContextSwitch] / 200.0)));
    nlohmann::json plain = preset_json(kCov);
    plain.erase("uncertainty");
    CHECK(draw_cost_models(parse_cost_model(plain.dump(), "p.json"), 64, 1).empty());
}

TEST_CASE("cost uncertainty: the 90 % interval contains the point estimate") {
    std::vector<double> s;
    for (int i = 0; i <= 100; ++i) s.push_back(1.0 + 0.01 * i);  // 1.00 .. 2.00
    const auto i = interval_90(s, 1.5);
    CHECK(i[0] == doctest::Approx(1.05));
    CHECK(i[1] == doctest::Approx(1.95));
    CHECK(interval_90(s, 2.5)[1] == 2.5);  // widened to include the point
    CHECK(interval_90(s, 0.5)[0] == 0.5);
    CHECK(interval_90({}, 3.0) == std::array<double, 2>{3.0, 3.0});
}

}  // namespace RTCSIM_TEST_FILE
