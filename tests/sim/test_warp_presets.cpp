// The execution block of a hardware preset: parsed strictly with the JSON
// path in every error, and a run whose presets group rays differently is
// refused before tracing.
#include "core/input_error.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

using namespace rtc;

namespace {

std::string preset_with(const std::string& execution) {
    nlohmann::json j = nlohmann::json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-guess.json"));
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
