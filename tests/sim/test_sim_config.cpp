// CLI parsing, --set overrides, sweep expansion, cost and memory presets.
#include "core/input_error.h"
#include "sim/app/cli.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/memory_model.h"
#include "sim/config/sweep.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using nlohmann::json;

TEST_CASE("cli: options, errors and help") {
    const CliOptions o = parse_cli({"x.json", "--threads", "3", "--set", "a.b=4", "--set=c=\"s\"", "--quiet",
                                    "--out", "dir"});
    CHECK(o.config == "x.json");
    CHECK(o.threads == 3);
    CHECK(o.sets == std::vector<std::string>{"a.b=4", "c=\"s\""});
    CHECK(o.quiet);
    CHECK(*o.out == "dir");
    CHECK(parse_cli({"calibrate", "y.json"}).calibrate);
    CHECK(parse_cli({"--help"}).help);
    CHECK(parse_cli({"x.json", "--threads", "0"}).threads == 0);  // all cores, as report.json documents
    CHECK_THROWS_WITH_AS((void)parse_cli({"x.json", "--threads", "-1"}), doctest::Contains("--threads"), InputError);
    CHECK_THROWS_WITH_AS((void)parse_cli({"x.json", "--threads", "2000"}), doctest::Contains("--threads"), InputError);
    CHECK(!parse_cli({"x.json"}).show_config);  // the config echo is opt-in
    CHECK(parse_cli({"x.json", "--show-config"}).show_config);
    CHECK_THROWS_WITH_AS((void)parse_cli({"x.json", "--bogus"}), doctest::Contains("unknown option --bogus"), InputError);
    CHECK_THROWS_AS((void)parse_cli({}), InputError);
    CHECK_THROWS_AS((void)parse_cli({"x.json", "--set"}), InputError);
    CHECK(cli_help().find("--set key.path=value") != std::string::npos);
}

TEST_CASE("sweep: --set paths, JSON values and bare strings") {
    json c = {{"workload", {{"spp", 4}}}};
    apply_set(c, "workload.spp=1", "x.json");
    apply_set(c, "scene.type=bundle", "x.json");
    apply_set(c, "methods=[\"obb\"]", "x.json");
    CHECK(c["workload"]["spp"] == 1);
    CHECK(c["scene"]["type"] == "bundle");
    CHECK(c["methods"] == json::array({"obb"}));
    CHECK_THROWS_WITH_AS(apply_set(c, "novalue", "x.json"), doctest::Contains("x.json: --set novalue"), InputError);
}

TEST_CASE("sweep: --set enters a list by an element's index, and refuses anything else there") {
    json c = {{"sweep", {{"scene", json::array({{{"name", "a"}, {"radius", 1}}, {{"name", "b"}, {"radius", 2}}})}}},
              {"workload", {{"camera", {{"position", {0, 0, 1}}}}}}};
    apply_set(c, "sweep.scene.1.radius=0.5", "x.json");
    apply_set(c, "workload.camera.position.2=3", "x.json");
    CHECK(c["sweep"]["scene"][0]["radius"] == 1);
    CHECK(c["sweep"]["scene"][1]["radius"] == 0.5);
    CHECK(c["sweep"]["scene"][1]["name"] == "b");
    CHECK(c["workload"]["camera"]["position"] == json::array({0, 0, 3}));
    const json before = c;
    // Before, a name or an index past the end replaced the whole list with an object.
    CHECK_THROWS_WITH_AS(apply_set(c, "sweep.scene.2.radius=1", "x.json"),
                         doctest::Contains("x.json: --set sweep.scene.2.radius: \"2\" is not an index of the list there (0 to 1)"),
                         InputError);
    CHECK_THROWS_WITH_AS(apply_set(c, "sweep.scene.name=x", "x.json"), doctest::Contains("\"name\" is not an index"),
                         InputError);
    CHECK_THROWS_AS(apply_set(c, "sweep.scene.-1.radius=1", "x.json"), InputError);
    CHECK_THROWS_AS(apply_set(c, "sweep.scene.99999999999.radius=1", "x.json"), InputError);
    CHECK(c == before);
    // The same rule for a sweep axis into a list of the base config.
    const json axis = {{"workload", {{"camera", {{"position", {0, 0, 1}}}}}},
                       {"sweep", {{"workload.camera.position.5", {1, 2}}}}};
    CHECK_THROWS_WITH_AS((void)expand_sweep(axis, "x.json"),
                         doctest::Contains("x.json: /sweep/workload.camera.position.5: \"5\" is not an index"),
                         InputError);
}

TEST_CASE("sweep: cartesian product with paired object axes, first key slowest") {
    const json c = {{"scene", {{"type", "bundle"}, {"tilt_deg", 0}}},
                    {"sweep",
                     {{"scene", json::array({{{"count", 1}, {"radius", 0.1}}, {{"count", 10}, {"radius", 0.01}}})},
                      {"scene.tilt_deg", {0, 15, 30}}}}};
    const auto points = expand_sweep(c, "x.json");
    REQUIRE(points.size() == 6);
    CHECK(points[0].config["scene"]["count"] == 1);
    CHECK(points[0].config["scene"]["tilt_deg"] == 0);
    CHECK(points[0].config["scene"]["type"] == "bundle");  // merged, not replaced
    CHECK(points[1].config["scene"]["tilt_deg"] == 15);
    CHECK(points[5].config["scene"]["count"] == 10);
    CHECK(points[5].config["scene"]["radius"] == 0.01);
    CHECK(points[5].config["scene"]["tilt_deg"] == 30);
    CHECK(!points[0].config.contains("sweep"));
    CHECK(points[4].values["scene.count"] == 10);
    CHECK(points[4].label.find("scene.tilt_deg=15") != std::string::npos);
    CHECK(expand_sweep(json{{"a", 1}}, "x.json").size() == 1);
    CHECK_THROWS_WITH_AS((void)expand_sweep(json{{"sweep", {{"a", 3}}}}, "x.json"),
                         doctest::Contains("x.json: /sweep/a: expected a non-empty list"), InputError);
}

TEST_CASE("cost model: presets load, pricing is linear, errors name the key") {
    const CostModel guess = load_cost_model(RTCSIM_SOURCE_DIR "/configs/hw/turing-per-ray-guess.json");
    CHECK(guess.name == "turing-per-ray-guess");
    for (std::size_t i = 0; i < kEventCount; ++i) CHECK(!guess.source[i].empty());

    EventTotals a, b;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        a.n[i] = 3 * i + 1;
        b.n[i] = 7 * i;
    }
    EventTotals sum = a;
    sum += b;
    CHECK(price(sum, guess).total_cycles == doctest::Approx(price(a, guess).total_cycles + price(b, guess).total_cycles));

    // Every cost zero but the context switch: cycles = switches x that cost.
    CostModel only_switch = guess;
    only_switch.cycles.fill(0.0);
    only_switch[Event::ContextSwitch] = 250.0;
    CHECK(price(a, only_switch).total_cycles == 250.0 * static_cast<double>(a[Event::ContextSwitch]));

    // Round trip through JSON.
    const CostModel again = parse_cost_model(cost_model_to_json(guess), "again.json");
    CHECK(again.cycles == guess.cycles);

    json j = json::parse(cost_model_to_json(guess));
    j["cycles"]["context_switch"]["value"] = -5;
    CHECK_THROWS_WITH_AS((void)parse_cost_model(j.dump(), "p.json"),
                         doctest::Contains("p.json: /cycles/context_switch/value"), InputError);
    j = json::parse(cost_model_to_json(guess));
    j["cycles"].erase("ray");
    CHECK_THROWS_WITH_AS((void)parse_cost_model(j.dump(), "p.json"), doctest::Contains("/cycles/ray: missing"), InputError);
    j["cycles"]["warp_drive"] = {{"value", 1}, {"source", "?"}};
    CHECK_THROWS_WITH_AS((void)parse_cost_model(j.dump(), "p.json"), doctest::Contains("unknown event"), InputError);
    CHECK_THROWS_WITH_AS((void)parse_cost_model("{\n\"name\": ,}", "bad.json"), doctest::Contains("bad.json: line 2"), InputError);
    CHECK_THROWS_WITH_AS((void)load_cost_model("/nonexistent/preset.json"), doctest::Contains("/nonexistent/preset.json"), InputError);
}

TEST_CASE("memory model: presets and pricing") {
    const MemoryModel optix = load_memory_model(RTCSIM_SOURCE_DIR "/configs/hw/memory-optix7.json");
    const MemoryModel dxr = load_memory_model(RTCSIM_SOURCE_DIR "/configs/hw/memory-dxr.json");
    CHECK(optix.instance_bytes == 250);
    CHECK(dxr.instance_bytes == 64);
    CHECK(optix.instance_limit == (1u << 24));
    StructureCounts c;
    c.width = 4;
    c.tlas_nodes = 10;
    c.instances = 1000;
    const MemoryBreakdown m = price_memory(c, optix, PrimitiveKind::Capsule, 1000, 0, 0);
    CHECK(m.instances == 250000.0);
    CHECK(optix.instance_includes_tlas_nodes);  // the measured 250 B per instance holds the TLAS
    CHECK(m.tlas_nodes == 0.0);
    CHECK(price_memory(c, dxr, PrimitiveKind::Capsule, 1000, 0, 0).tlas_nodes == 10 * dxr.node_bytes_w4);
    CHECK(m.common == 1000 * optix.primitive_data_bytes[1]);
    // Every preset prices a BLAS (header + alignment), which cluster has one of per group.
    CHECK(optix.blas_bytes == 192);
    CHECK(dxr.blas_bytes == 256);
    CHECK(load_memory_model(RTCSIM_SOURCE_DIR "/configs/hw/memory-optix-record.json").blas_bytes == 64);
    c.blases = 10;
    CHECK(price_memory(c, optix, PrimitiveKind::Capsule, 1000, 0, 0).blas_headers == 1920.0);
    CHECK(m.total() == doctest::Approx(m.acceleration() + m.common));
}

}  // namespace RTCSIM_TEST_FILE
