// Issue 56: what a run reads besides its config. A merge refuses shards that
// read different versions of a scene file or preset (or a derived preset's
// base), and files changed since the shards ran: exit 0 used to merge them
// into a speedup that neither version gives. And report.json records the
// presets as they were loaded before tracing, bases included, not as re-read
// when the report is written.
#include "core/input_error.h"
#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/app/shard_runs.h"
#include "sim/app/simulate_main.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

// A config with a curve file and a derived preset on a base, in a fresh directory.
fs::path make_run(const std::string& name) {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_input_versions" / name;
    fs::remove_all(dir);
    fs::create_directories(dir / "hw");
    json base = parse_json_text(read_text_file(RTCSIM_SOURCE_DIR "/configs/hw/turing-per-ray-guess.json"), "base");
    base["name"] = "base";
    std::ofstream(dir / "hw" / "base.json") << base.dump(1);
    std::ofstream(dir / "hw" / "derived.json")
        << R"({"name": "derived", "derived_from": "base.json", "deltas": []})";
    std::ofstream(dir / "curves.txt") << "0 -1 0 0.05\n0.1 1 0 0.05\n\n-0.5 -1 0 0.05\n-0.4 1 0 0.05\n";
    std::ofstream(dir / "run.json") << R"({"name": "versions",
        "scene": {"type": "file", "curves": {"path": "curves.txt"}},
        "cost": ["hw/derived.json"], "memory": ")" RTCSIM_SOURCE_DIR R"(/configs/hw/memory-optix7.json",
        "workload": {"width": 8, "height": 8, "spp": 1, "bounces": 0},
        "output": {"images": false, "arrays": false}})";
    return dir;
}

void edit_base(const fs::path& dir, double cost) {
    json base = parse_json_text(read_text_file((dir / "hw" / "base.json").string()), "base");
    base["cycles"]["blas_box_test"]["value"] = cost;
    std::ofstream(dir / "hw" / "base.json", std::ios::trunc) << base.dump(1);
}

int shard(const fs::path& dir, const std::string& spec) {
    return simulate_main({(dir / "run.json").string(), "--shard", spec, "--out", (dir / ("s" + spec.substr(0, 1))).string(),
                          "--quiet", "--threads", "1"});
}

std::string merge_error(const fs::path& dir) {
    const fs::path out = dir / "merged";
    fs::remove_all(out);
    try {
        (void)run_merge(parse_cli({"merge", (dir / "s0").string(), (dir / "s1").string(), "--out", out.string(),
                                   "--quiet"}));
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("merge: shards that read different versions of a preset's base are refused, naming the file") {
    const fs::path dir = make_run("base_between");
    REQUIRE(shard(dir, "0/2") == 0);
    edit_base(dir, 99.0);
    REQUIRE(shard(dir, "1/2") == 0);
    const std::string e = merge_error(dir);
    CAPTURE(e);
    CHECK(e.rfind((dir / "hw" / "base.json").string() + ": content hash ", 0) == 0);
    CHECK(e.find("edited in between") != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
}

TEST_CASE("merge: a scene file or preset edited after the shards ran is refused, naming the file") {
    const fs::path dir = make_run("after");
    REQUIRE(shard(dir, "0/2") == 0);
    REQUIRE(shard(dir, "1/2") == 0);
    CHECK(merge_error(dir) == "(no error)");
    std::ofstream(dir / "curves.txt", std::ios::app) << "\n1 -1 0 0.05\n1 1 0 0.05\n";
    std::string e = merge_error(dir);
    CHECK(e.rfind((dir / "curves.txt").string() + ": content hash ", 0) == 0);
    fs::remove(dir / "curves.txt");
    std::ofstream(dir / "curves.txt") << "0 -1 0 0.05\n0.1 1 0 0.05\n\n-0.5 -1 0 0.05\n-0.4 1 0 0.05\n";
    CHECK(merge_error(dir) == "(no error)");  // restored: the same bytes
    std::ofstream(dir / "hw" / "derived.json", std::ios::trunc)
        << R"({"name": "derived", "derived_from": "base.json", "deltas": [
               {"events": ["blas_box_test"], "scale": 2, "source": "[I] test"}]})";
    e = merge_error(dir);
    CHECK(e.rfind((dir / "hw" / "derived.json").string() + ": content hash ", 0) == 0);
}

TEST_CASE("merge: a shard.json's deep --set is refused naming its key (issue 56, finding 1)") {
    const fs::path dir = make_run("deep_set");
    REQUIRE(shard(dir, "0/2") == 0);
    REQUIRE(shard(dir, "1/2") == 0);
    std::string deep = "description";
    for (int i = 0; i < 60000; ++i) deep += ".a";
    for (const char* s : {"s0", "s1"}) {
        json m = parse_json_text(read_text_file((dir / s / "shard.json").string()), "shard.json");
        m["sets"] = {deep + "=1"};
        std::ofstream(dir / s / "shard.json", std::ios::trunc) << m.dump();
    }
    const std::string e = merge_error(dir);  // was: SIGSEGV
    CHECK(e.rfind((dir / "s0").string() + "/shard.json: /sets/0: --set description.a.a", 0) == 0);
    CHECK(e.find("deeper than 128 levels") != std::string::npos);
}

TEST_CASE("provenance: presets as loaded before tracing, with a derived preset's bases") {
    const fs::path dir = make_run("provenance");
    const std::string config = (dir / "run.json").string();
    const RunPlan plan = plan_config_text(config, read_text_file(config), {}, {});
    const json base_then = parse_json_text(read_text_file((dir / "hw" / "base.json").string()), "base");
    const json derived_then = parse_json_text(read_text_file((dir / "hw" / "derived.json").string()), "derived");
    // Edited after the presets were loaded, as an edit during tracing would be.
    edit_base(dir, 99.0);
    std::ofstream(dir / "hw" / "derived.json", std::ios::trunc) << "{}";
    RunContext ctx;
    ctx.threads = 1;
    ctx.quiet = true;
    const RunResult r = run_point(plan, 0, ctx);
    const json p = json(r.point.provenance)["presets"]["cost"][0];
    CHECK(p["name"] == "derived");
    CHECK(p["file"] == (dir / "hw" / "derived.json").lexically_normal().string());
    CHECK(p["contents"] == derived_then);
    REQUIRE(p["bases"].size() == 1);
    CHECK(p["bases"][0]["file"] == (dir / "hw" / "base.json").lexically_normal().string());
    CHECK(p["bases"][0]["contents"] == base_then);
    CHECK(json(r.point.provenance)["presets"]["memory"]["contents"]["name"] == "memory-optix7");
    // The effective costs are the loaded ones, not the edited file's 99.
    const double loaded = parse_json_text(read_text_file(RTCSIM_SOURCE_DIR "/configs/hw/turing-per-ray-guess.json"),
                                          "guess")["cycles"]["blas_box_test"]["value"];
    REQUIRE(loaded != 99.0);
    CHECK(p["effective"]["cycles"]["blas_box_test"]["value"] == loaded);
}

TEST_CASE("provenance: a run priced under ada alone records ada's effective costs and the ampere and turing-calibrated it derives from") {
    const fs::path dir = make_run("provenance_ada");
    std::ofstream(dir / "run.json", std::ios::trunc) << R"({"name": "ada only",
        "scene": {"type": "file", "curves": {"path": "curves.txt"}},
        "cost": ["ada"], "memory": "memory-optix7",
        "workload": {"width": 8, "height": 8, "spp": 1, "bounces": 0},
        "output": {"images": false, "arrays": false}})";
    const std::string config = (dir / "run.json").string();
    const RunPlan plan = plan_config_text(config, read_text_file(config), {}, {});
    RunContext ctx;
    ctx.threads = 1;
    ctx.quiet = true;
    const RunResult r = run_point(plan, 0, ctx);
    const json p = json(r.point.provenance)["presets"]["cost"][0];
    const auto shipped = [](const char* name) {
        return parse_json_text(read_text_file(std::string(RTCSIM_SOURCE_DIR "/configs/hw/") + name), name);
    };
    CHECK(p["name"] == "ada");
    CHECK(p["contents"] == shipped("ada.json"));
    REQUIRE(p["bases"].size() == 2);  // derived_from, then its own base
    CHECK(p["bases"][0]["contents"] == shipped("ampere.json"));
    CHECK(p["bases"][1]["contents"] == shipped("turing-calibrated.json"));
    // Effective: every cost ada prices with, as a number, deltas applied.
    const json& effective = p["effective"]["cycles"];
    REQUIRE(!effective.empty());
    for (const auto& item : effective.items()) {  // no structured binding: INFO's lambda captures it (clang 14)
        const std::string event = item.key();
        const json& entry = item.value();
        INFO(event);
        const Event e = *event_from_name(event);
        CHECK(entry["value"].get<double>() == r.costs[0].cycles[static_cast<std::size_t>(e)]);
    }
    // ada changes some cost from turing-calibrated's: the flattened costs
    // are not simply the root's.
    bool differs = false;
    const json root = shipped("turing-calibrated.json");  // named: a temporary's items() would dangle
    for (const auto& [event, entry] : root["cycles"].items())
        if (entry.contains("value") && effective.contains(event) && effective[event]["value"] != entry["value"]) differs = true;
    CHECK(differs);
}

}  // namespace RTCSIM_TEST_FILE
