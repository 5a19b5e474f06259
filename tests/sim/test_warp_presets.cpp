// The execution block of a hardware preset: parsed strictly with the JSON
// path in every error, and a run whose presets group rays differently is
// refused before tracing; and which program group (operation classes or
// programs by name) a preset prices.
#include "core/input_error.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

std::string preset_with(const std::string& execution) {
    nlohmann::json j = nlohmann::json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-per-ray-guess.json"));
    j["execution"] = nlohmann::json::parse(execution);
    return j.dump();
}

std::string error_of(const std::string& execution) {
    try {
        (void)parse_cost_model(preset_with(execution), "p.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("warp presets: the execution block") {
    const CostModel m = parse_cost_model(
        preset_with(R"({"model": {"value": "warp", "source": "s"}, "warp_width": {"value": 32, "source": "s"},
                        "tile": {"value": [8, 4], "source": "s"}, "rt_parallel_lanes": {"value": 6, "source": "s"}})"),
        "p.json");
    CHECK(m.execution.warp());
    CHECK(m.execution.tile_width == 8);
    CHECK(m.execution.tile_height == 4);
    CHECK(m.execution.rt_parallel_lanes == 6.0);
    // Round trip through the JSON writer (calibrated presets keep the block).
    const CostModel again = parse_cost_model(cost_model_to_json(m), "q.json");
    CHECK(again.execution.warp());
    CHECK(again.execution.rt_parallel_lanes == 6.0);
    CHECK(!parse_cost_model(preset_with("{}"), "p.json").execution.warp());

    CHECK(error_of(R"({"model": {"value": "simd", "source": "s"}})").find("p.json: /execution/model/value") == 0);
    CHECK(error_of(R"({"tile": {"value": [8, 8], "source": "s"}})") ==
          "p.json: /execution/tile: a tile of 8 x 8 pixels does not fill a warp of 32 lanes");
    CHECK(error_of(R"({"rt_parallel_lanes": {"value": 0, "source": "s"}})").find("p.json: /execution/rt_parallel_lanes/value") == 0);
    CHECK(error_of(R"({"warp_width": {"value": 32}})").find("p.json: /execution/warp_width/source") == 0);
    CHECK(error_of(R"({"lanes": 3})").find("p.json: /execution/lanes: unknown key") == 0);
}

TEST_CASE("program pricing: a preset prices operation classes or programs by name, never both") {
    const std::string dir = std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/";
    const CostModel by_ops = load_cost_model(dir + "turing-calibrated.json");
    const CostModel by_name = load_cost_model(dir + "turing-per-ray-guess.json");
    CHECK(by_ops.program_pricing == ProgramPricing::ByOperation);
    CHECK(by_name.program_pricing == ProgramPricing::ByName);
    // The shipped calibrated preset has no per-kind program constant.
    for (const Event e : {Event::IsCylinder, Event::IsCapsule, Event::IsLink, Event::PhantomPaperIteration}) {
        CHECK(!by_ops.prices(e));
        CHECK(by_ops[e] == 0.0);
        CHECK(by_name.prices(e));
    }
    CHECK(by_ops[Event::OpFma] > 0.0);
    CHECK(by_name[Event::OpFma] == 0.0);
    // Written back with only the group it prices, and read back the same.
    const nlohmann::json j = nlohmann::json::parse(cost_model_to_json(by_ops));
    CHECK(!j["cycles"].contains("is_capsule"));
    CHECK(parse_cost_model(j.dump(), "again.json").cycles == by_ops.cycles);

    nlohmann::json mixed = j;
    mixed["cycles"]["is_capsule"] = {{"value", 150}, {"source", "guess"}};
    CHECK_THROWS_WITH_AS((void)parse_cost_model(mixed.dump(), "p.json"),
                         doctest::Contains("p.json: /cycles/is_capsule: this preset prices programs by operation class"),
                         InputError);
    nlohmann::json partial = j;
    partial["cycles"].erase("op_sqrt");
    CHECK_THROWS_WITH_AS((void)parse_cost_model(partial.dump(), "p.json"),
                         doctest::Contains("p.json: /cycles/op_sqrt: missing"), InputError);
}

TEST_CASE("resolution: a run more than 4x off the preset's fitted pixel count is told") {
    CostModel m = load_cost_model(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-calibrated.json");
    REQUIRE(m.fitted_on.pixels() == 800u * 800u);  // what fig3_bundles.json fits on
    CHECK(resolution_note(m, 400 * 400).empty());   // 4x: within
    CHECK(resolution_note(m, 1600 * 1600).empty());
    CHECK(resolution_note(m, 160 * 160).find("25x fewer") != std::string::npos);
    CHECK(resolution_note(m, 4000 * 4000).find("25x more") != std::string::npos);
    m.fitted_on = {};
    CHECK(resolution_note(m, 8 * 8).empty());  // a preset that does not say: no note
    // Read back as written.
    m.fitted_on = {64, 32, 2, 1, "x.json"};
    const CostModel again = parse_cost_model(cost_model_to_json(m), "again.json");
    CHECK(again.fitted_on.pixels() == 64u * 32u);
    CHECK(again.fitted_on.config == "x.json");
}

}  // namespace RTCSIM_TEST_FILE
