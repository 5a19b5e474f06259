// The `calibrate` config block: parsing, error paths, and matching targets to
// sweep points and labels (sim/calibrate_config.h).
#include "sim/calibrate/calibrate_config.h"

#include <doctest/doctest.h>

#include <string>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using nlohmann::json;

namespace {

CalibrateDesc parse(const std::string& text) {
    const json j = json::parse(text);
    return parse_calibrate(JsonReader(j, "runs/x.json").child("calibrate"));
}

std::string error_of(const std::string& text) {
    try {
        (void)parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

const char* kGood = R"({"calibrate": {
  "parameters": [
    {"events": ["context_switch"], "min": 50, "max": 1000},
    {"events": ["tlas_box_test", "blas_box_test"], "min": 0.25, "max": 4, "tie": "scale"}],
  "targets": [
    {"match": {"scene.count": 1000, "scene.tilt_deg": 45}, "speedup": 3.20},
    {"match": {"scene.count": 1000, "scene.tilt_deg": 0}, "speedup": 1.04, "weight": 2},
    {"match": {"scene.radius": 0.002, "scene.tilt_deg": 15, "scene.count": 100}, "speedup": 2.01},
    {"label": "hair", "speedup": 5.9}],
  "output": "configs/hw/turing-calibrated.json",
  "name": "turing-calibrated",
  "start": "../hw/turing-per-ray-guess.json",
  "reference": "Wald et al. 2020 synthetic table"}})";

}  // namespace

TEST_CASE("calibrate config: a full block parses") {
    const CalibrateDesc d = parse(kGood);
    REQUIRE(d.parameters.size() == 2);
    CHECK(d.start == "../hw/turing-per-ray-guess.json");
    CHECK(d.parameters[0].events == std::vector<Event>{Event::ContextSwitch});
    CHECK(d.parameters[0].lo == 50);
    CHECK(d.parameters[0].hi == 1000);
    CHECK(d.parameters[0].tie == Tie::Value);
    CHECK(d.parameters[1].events == std::vector<Event>{Event::TlasBoxTest, Event::BlasBoxTest});
    CHECK(d.parameters[1].tie == Tie::Scale);
    REQUIRE(d.targets.size() == 4);
    CHECK(d.targets[1].weight == 2);
    CHECK(d.targets[3].label == "hair");
    CHECK(d.targets[0].where == "runs/x.json: /calibrate/targets/0");
    CHECK(d.output == "configs/hw/turing-calibrated.json");
    const CalibrationOptions o = calibration_options(d);
    CHECK(o.name == "turing-calibrated");
    CHECK(o.target_name == "Wald et al. 2020 synthetic table");
    CHECK(o.max_iterations == 200);
}

TEST_CASE("calibrate config: targets match sweep points by the keys they name") {
    const CalibrateDesc d = parse(kGood);
    const json p45 = {{"scene.count", 1000}, {"scene.radius", 0.002}, {"scene.tilt_deg", 45.0}};
    CHECK(target_for(d, p45) == 3.20);
    const json p0 = {{"scene.count", 1000.0}, {"scene.radius", 0.002}, {"scene.tilt_deg", 0}};
    CHECK(target_for(d, p0) == 1.04);
    // 0.001 * 2 is not bit-equal to 0.002 but equal to 1e-9 relative.
    const json p15 = {{"scene.count", 100}, {"scene.radius", 0.001 * 2.0000000001}, {"scene.tilt_deg", 15}};
    CHECK(target_for(d, p15) == 2.01);
    const json p30 = {{"scene.count", 1000}, {"scene.radius", 0.002}, {"scene.tilt_deg", 30}};
    CHECK_FALSE(target_for(d, p30).has_value());
    CHECK_FALSE(target_for(d, json{{"scene.count", 1000}}).has_value());  // a named key is missing
    REQUIRE(find_target(d, json::object(), "hair") != nullptr);
    CHECK(find_target(d, json::object(), "hair")->speedup == 5.9);
    CHECK(find_target(d, json::object(), "fur") == nullptr);
    CHECK_FALSE(target_for(d, json::object()).has_value());  // label targets need a label

    const auto unmatched = unmatched_targets(d, {p45, p0}, {"", "hair"});
    CHECK(unmatched == std::vector<std::string>{"runs/x.json: /calibrate/targets/2"});
}

TEST_CASE("calibrate config: two targets matching one point is an error naming both") {
    const CalibrateDesc d = parse(R"({"calibrate": {
      "parameters": [{"events": ["context_switch"], "min": 0, "max": 10}],
      "targets": [{"match": {"scene.count": 10}, "speedup": 1.2},
                  {"match": {"scene.tilt_deg": 45}, "speedup": 1.3}]}})");
    CHECK(target_for(d, json{{"scene.count", 10}, {"scene.tilt_deg", 0}}) == 1.2);
    try {
        (void)target_for(d, json{{"scene.count", 10}, {"scene.tilt_deg", 45}});
        FAIL("expected an ambiguity error");
    } catch (const InputError& e) {
        const std::string m = e.what();
        CHECK(m.find("/calibrate/targets/1") != std::string::npos);
        CHECK(m.find("/calibrate/targets/0") != std::string::npos);
        CHECK(m.find("ambiguous") != std::string::npos);
    }
}

TEST_CASE("calibrate config: errors name the file and JSON path") {
    const std::string params = R"("parameters": [{"events": ["context_switch"], "min": 0, "max": 10}])";
    const std::string targets = R"("targets": [{"label": "a", "speedup": 2}])";
    const auto block = [](const std::string& body) { return R"({"calibrate": {)" + body + "}}"; };

    CHECK(error_of(block(params + "," + targets + R"(, "outptu": "x")")) ==
          "runs/x.json: /calibrate/outptu: unknown key (expected one of: parameters, targets, output, "
          "name, description, reference, max_iterations, start, method)");
    CHECK(error_of(block(targets)) ==
          "runs/x.json: /calibrate/parameters: missing (expected a non-empty array of parameters)");
    CHECK(error_of(block(params + R"(, "targets": [])")) ==
          "runs/x.json: /calibrate/targets: expected a non-empty array of targets, got []");
    CHECK(error_of(block(R"("parameters": [{"events": ["context_swich"], "min": 0, "max": 1}],)" + targets)) ==
          "runs/x.json: /calibrate/parameters/0/events/0: unknown event \"context_swich\" (see core/events.h)");
    CHECK(error_of(block(R"("parameters": [{"events": ["ray"], "min": -1, "max": 1}],)" + targets)) ==
          "runs/x.json: /calibrate/parameters/0/min: expected a number in [0.0, 1000000000.0], got -1");
    CHECK(error_of(block(R"("parameters": [{"events": ["ray"], "min": 5, "max": 1}],)" + targets)) ==
          "runs/x.json: /calibrate/parameters/0/max: must be >= min (5), got 1");
    CHECK(error_of(block(R"("parameters": [{"events": ["ray"], "min": 0, "max": 1, "tie": "sum"}],)" + targets)) ==
          "runs/x.json: /calibrate/parameters/0/tie: expected one of value, scale, got \"sum\"");
    CHECK(error_of(block(R"("parameters": [{"events": ["ray"], "min": 0, "max": 1},
                                           {"events": ["is_call", "ray"], "min": 0, "max": 1}],)" + targets)) ==
          "runs/x.json: /calibrate/parameters/1/events/1: event \"ray\" is already fitted at "
          "/calibrate/parameters/0/events/0 (an event may be in one parameter only)");
    CHECK(error_of(block(params + R"(, "targets": [{"speedup": 2}])")) ==
          "runs/x.json: /calibrate/targets/0: needs exactly one of \"label\" or \"match\"");
    CHECK(error_of(block(params + R"(, "targets": [{"label": "a", "speedup": 0}])")) ==
          "runs/x.json: /calibrate/targets/0/speedup: expected a positive number, got 0");
    CHECK(error_of(block(params + R"(, "targets": [{"match": {"scene.count": {"a": 1}}, "speedup": 2}])")) ==
          "runs/x.json: /calibrate/targets/0/match: value of \"scene.count\" must be a number, string, "
          "bool or array, got {\"a\":1}");
    CHECK(error_of(block(params + R"(, "targets": [{"label": "a", "speedup": 2}, {"label": "a", "speedup": 3}])")) ==
          "runs/x.json: /calibrate/targets/1: same label as /calibrate/targets/0");
    CHECK(error_of(block(params + "," + targets + R"(, "max_iterations": 0)")) ==
          "runs/x.json: /calibrate/max_iterations: expected an integer in [1, 100000], got 0");
}

}  // namespace RTCSIM_TEST_FILE
