// The command line (CLI11), paths relative to the config file, the data
// root, presets by name, output-directory safety, calibrate's output, provenance in
// report.json, the sweep order and re-pricing instead of re-tracing.
#include "core/input_error.h"
#include "sim/app/calibrate_runs.h"
#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/app/simulate_main.h"
#include "sim/config/config_json.h"
#include "sim/config/sweep.h"
#include "sim/util/json_file.h"
#include "sim/util/paths.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kTiny = "tests/configs/tiny.json";

fs::path scratch(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "cli_paths" / name;
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

std::string error_of(const std::vector<std::string>& args) {
    try {
        (void)parse_cli(args);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

// Runs simulate in process; quiet, small.
int simulate(std::vector<std::string> args) {
    args.insert(args.end(), {"--quiet", "--threads", "2"});
    return simulate_main(args);
}

json report_of(const fs::path& dir) { return json::parse(read_text_file((dir / "report.json").string())); }

// A report without what changes from run to run (dates, threads, wall times).
json comparable(json r) {
    r.erase("provenance");
    r.erase("wall_seconds");
    r.erase("config");
    r.erase("sweep_point");
    r.erase("sweep_label");
    for (auto& [name, m] : r["methods"].items()) m.erase("simulator");  // build and trace times
    return r;
}

// Moves into `dir` for the scope, so relative paths cannot resolve by accident.
struct WorkingDirectory {
    fs::path saved = fs::current_path();
    explicit WorkingDirectory(const fs::path& dir) { fs::current_path(dir); }
    ~WorkingDirectory() { fs::current_path(saved); }
};

}  // namespace

TEST_CASE("cli: --opt=value, --out --quiet is an error naming --out, exit 2") {
    const CliOptions o = parse_cli({"--out=d", "--threads=3", "x.json", "--max-rays=1e9", "--set=a=1", "--set", "b=2"});
    CHECK(*o.out == "d");
    CHECK(o.threads == 3);
    CHECK(o.limits.max_rays == 1e9);
    CHECK(o.sets == std::vector<std::string>{"a=1", "b=2"});
    CHECK(o.config == "x.json");
    CHECK(o.command_line.front() == "simulate");
    CHECK(error_of({"x.json", "--out", "--quiet"}).find("--out needs a value") != std::string::npos);
    CHECK(error_of({"x.json", "--out"}).find("--out needs a value") != std::string::npos);
    CHECK(error_of({"x.json", "--set", "--force"}).find("--set needs a value") != std::string::npos);
    CHECK(error_of({"x.json", "--threads=many"}).find("--threads") != std::string::npos);
    CHECK(error_of({"x.json", "--frobnicate=3"}).find("unknown option --frobnicate") != std::string::npos);
    CHECK(error_of({"x.json", "y.json"}).find("more than one config") != std::string::npos);
    CHECK(error_of({"calibrate"}).find("no config given") != std::string::npos);
    const CliOptions c = parse_cli({"calibrate", "--out", "o", "x.json"});
    CHECK(c.calibrate);
    CHECK(c.config == "x.json");
    CHECK(simulate_main({kTiny, "--out", "--quiet"}) == 2);
    CHECK_FALSE(fs::exists("--quiet"));
}

TEST_CASE("paths: a config elsewhere runs from any directory, presets by name") {
    const fs::path dir = scratch("elsewhere");
    write(dir / "cfg" / "data" / "strands.txt", "0 0 0 0.02\n0 0.5 0 0.02\n\n0.2 0 0 0.02\n0.2 0.5 0.1 0.01\n");
    write(dir / "cfg" / "run.json", R"({"scene": {"type": "file", "curves": {"path": "data/strands.txt"}},
        "cost": ["turing-per-ray-guess", "turing-calibrated"], "memory": "memory-dxr",
        "workload": {"width": 8, "height": 8, "spp": 1, "bounces": 0}, "output": {"images": false}})");
    const fs::path out = dir / "out";
    {
        const WorkingDirectory cwd(dir.root_path());  // "/"
        REQUIRE(simulate({(dir / "cfg" / "run.json").string(), "--out", out.string()}) == 0);
    }
    const json r = report_of(out);
    CHECK(r["scene"]["strands"] == 2);
    const json& presets = r["provenance"]["presets"];
    CHECK(fs::path(presets["cost"][0]["file"].get<std::string>()).filename() == "turing-per-ray-guess.json");
    CHECK(presets["cost"][1]["name"] == "turing-calibrated");
    CHECK(presets["memory"]["contents"]["name"] ==
          json::parse(read_text_file(presets["memory"]["file"].get<std::string>()))["name"]);
    // Relative to the config, not the working directory: from a directory
    // where the path exists relative to the working directory, it fails,
    // when the config is planned (before anything runs).
    const std::string file = (dir / "cfg" / "run.json").string();
    json config = json::parse(read_text_file(file));
    config["scene"]["curves"]["path"] = "cfg/data/strands.txt";
    const WorkingDirectory cwd(dir);
    REQUIRE(fs::exists("cfg/data/strands.txt"));
    const std::string expected =
        file + ": /scene/curves/path: no such file: " + (dir / "cfg" / "cfg" / "data" / "strands.txt").string();
    CHECK_THROWS_WITH_AS((void)plan_runs(config, file), doctest::Contains(expected.c_str()), InputError);
}

TEST_CASE("paths: data: paths name the data root (--data, then RTCSIM_DATA, then the repository's data/)") {
    const fs::path dir = scratch("data_root");
    write(dir / "root_a" / "hair" / "s.txt", "0 0 0 0.02\n0 0.5 0 0.02\n");
    write(dir / "root_b" / "hair" / "s.txt", "0 0 0 0.02\n0 0.5 0 0.02\n\n0.2 0 0 0.02\n0.2 0.5 0.1 0.01\n");
    write(dir / "cfg" / "run.json", R"({"scene": {"type": "file", "curves": {"path": "data:hair/s.txt"}},
        "workload": {"width": 8, "height": 8, "spp": 1, "bounces": 0}, "output": {"images": false}})");
    const std::string config = (dir / "cfg" / "run.json").string();
    ::unsetenv("RTCSIM_DATA");
    CHECK(data_root() == fs::path(RTCSIM_SOURCE_DIR) / "data");
    ::setenv("RTCSIM_DATA", (dir / "root_a").c_str(), 1);
    CHECK(config_data_path("data:hair/s.txt", config) == (dir / "root_a" / "hair" / "s.txt").string());
    CHECK(config_data_path("hair/s.txt", config) == (dir / "cfg" / "hair" / "s.txt").string());  // no prefix
    REQUIRE(simulate({config, "--out", (dir / "out_a").string()}) == 0);
    CHECK(report_of(dir / "out_a")["scene"]["strands"] == 1);
    CHECK(report_of(dir / "out_a")["provenance"]["data_root"] == (dir / "root_a").string());
    // --data comes before the environment.
    REQUIRE(simulate({config, "--data", (dir / "root_b").string(), "--out", (dir / "out_b").string()}) == 0);
    CHECK(report_of(dir / "out_b")["scene"]["strands"] == 2);
    // A missing model names the file and what to do, when the config is planned.
    ::setenv("RTCSIM_DATA", (dir / "empty").c_str(), 1);
    const std::string expected = config + ": /scene/curves/path: no such file: " +
                                 (dir / "empty" / "hair" / "s.txt").string() + " (data root " +
                                 (dir / "empty").string() + "; run scripts/fetch-data";
    CHECK_THROWS_WITH_AS((void)plan_runs(json::parse(read_text_file(config)), config),
                         doctest::Contains(expected.c_str()), InputError);
    CHECK(simulate({config, "--out", (dir / "out_c").string()}) == 2);
    CHECK(simulate({config, "--data", (dir / "nowhere").string()}) == 2);
    CHECK(error_of({config, "--data", "--quiet"}).find("--data needs a value") != std::string::npos);
    ::unsetenv("RTCSIM_DATA");
}

TEST_CASE("paths: a missing preset names its key and the places searched") {
    const std::string file = (scratch("preset") / "run.json").string();
    json config = json::parse(read_text_file(kTiny));
    config["cost"] = json::array({"turing-per-ray-guess", "no-such-preset"});
    try {
        (void)plan_runs(config, file);
        FAIL("no error");
    } catch (const InputError& e) {
        const std::string what = e.what();
        CHECK(what.rfind(file + ": /cost/1: no preset named \"no-such-preset\" (searched ", 0) == 0);
        CHECK(what.find(RTCSIM_SOURCE_DIR "/configs/hw") != std::string::npos);
    }
    config["cost"] = "no/such/file.json";
    CHECK_THROWS_WITH_AS((void)plan_runs(config, file), doctest::Contains("/cost: no such preset file"), InputError);
    // RTCSIM_PRESET_DIR comes first.
    const fs::path mine = scratch("preset_dir");
    json preset = json::parse(read_text_file(RTCSIM_SOURCE_DIR "/configs/hw/turing-per-ray-guess.json"));
    preset["name"] = "my-guess";
    write(mine / "turing-per-ray-guess.json", preset.dump());
    ::setenv("RTCSIM_PRESET_DIR", mine.c_str(), 1);
    CHECK(preset_dirs().front() == mine);
    CHECK(resolve_preset("turing-per-ray-guess", file, "/cost/0") == (mine / "turing-per-ray-guess.json").string());
    ::unsetenv("RTCSIM_PRESET_DIR");
    CHECK(resolve_preset("turing-per-ray-guess", file, "/cost/0") != (mine / "turing-per-ray-guess.json").string());
    CHECK(is_preset_name("memory-optix7"));
    CHECK_FALSE(is_preset_name("memory-optix7.json"));
    CHECK_FALSE(is_preset_name("../hw/memory-optix7"));
}

TEST_CASE("output directory: refused when not empty, --force clears only what simulate wrote") {
    const fs::path out = scratch("outdir");
    const std::vector<std::string> base{kTiny, "--out", out.string(), "--set", "output.images=false",
                                        "--set", "workload.width=8", "--set", "workload.height=8"};
    REQUIRE(simulate(base) == 0);
    CHECK(fs::exists(out / ".rtcsim-output"));
    CHECK(simulate(base) == 2);  // not empty
    write(out / "stale_point" / "report.json", "{}");
    auto forced = base;
    forced.push_back("--force");
    REQUIRE(simulate(forced) == 0);
    CHECK_FALSE(fs::exists(out / "stale_point"));
    CHECK(fs::exists(out / "report.json"));
    // A directory simulate did not write is never emptied.
    const fs::path foreign = scratch("foreign");
    write(foreign / "notes.txt", "mine");
    auto into_foreign = forced;
    into_foreign[2] = foreign.string();
    CHECK(simulate(into_foreign) == 2);
    CHECK(fs::exists(foreign / "notes.txt"));
}

// A valid calibrate block writing its fitted preset to `output`.
json calibrate_block(const std::string& output) {
    return {{"calibrate", {{"parameters", {{{"events", {"context_switch"}}, {"min", 1}, {"max", 10}}}},
                           {"targets", {{{"label", "tiny"}, {"speedup", 2.0}}}},
                           {"output", output}}}};
}

TEST_CASE("calibrate: an existing output file is refused before tracing, unless --force") {
    const fs::path dir = scratch("calibrate");
    const std::string file = (dir / "fit.json").string();
    const CalibratePlan plan = plan_calibrate(calibrate_block("../hw/turing-per-ray-guess.json"), file);
    CHECK(calibrate_output_path(plan, false) == (dir.parent_path() / "hw" / "turing-per-ray-guess.json").string());
    write(dir / "taken.json", "{}");
    const CalibratePlan taken = plan_calibrate(calibrate_block("taken.json"), file);
    CHECK_THROWS_WITH_AS((void)calibrate_output_path(taken, false),
                         doctest::Contains((file + ": /calibrate/output: " + (dir / "taken.json").string() + " exists").c_str()),
                         InputError);
    CHECK(calibrate_output_path(taken, true) == (dir / "taken.json").string());
    const std::string shipped = std::string(RTCSIM_SOURCE_DIR) + "/configs/runs/x.json";
    const CalibratePlan onto_shipped = plan_calibrate(calibrate_block("../hw/turing-calibrated.json"), shipped);
    CHECK_THROWS_WITH_AS((void)calibrate_output_path(onto_shipped, false), doctest::Contains("is a shipped preset"),
                         InputError);
}

TEST_CASE("calibrate: the start preset is loaded and checked when the config is planned, and the fit uses that load") {
    const fs::path dir = scratch("calibrate_start");
    write(dir / "start.json", "{\"name\": \"broken\"}");
    json config = json::parse(read_text_file(kTiny));
    config["cost"] = json::array({"turing-per-ray-guess"});
    config["memory"] = "memory-optix7";
    config["calibrate"] = {{"parameters", {{{"events", {"context_switch"}}, {"min", 1}, {"max", 10}}}},
                           {"targets", {{{"label", "tiny"}, {"speedup", 2.0}}}},
                           {"start", "start.json"}};
    const std::string file = (dir / "run.json").string();
    CHECK_THROWS_WITH_AS((void)plan_runs(config, file), doctest::Contains((dir / "start.json").string().c_str()),
                         InputError);
    json start = json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/turing-per-ray-guess.json"));
    start["name"] = "my-start";
    write(dir / "start.json", start.dump());
    const RunPlan plan = plan_runs(config, file);
    REQUIRE(plan.calibrate);
    CHECK(plan.calibrate->desc.start == "start.json");
    REQUIRE(plan.calibrate->start);
    // Edited after planning, as during the runs: the plan keeps what it loaded.
    write(dir / "start.json", "{\"name\": \"broken\"}");
    CHECK(plan.calibrate->start->name == "my-start");
    RunContext ctx;
    ctx.threads = 1;
    ctx.quiet = true;
    RunResult run = run_point(plan, 0, ctx);
    RunResult* runs[] = {&run};
    const CalibrationOutcome fit = calibrate_results(runs, *plan.calibrate, nullptr);
    CHECK(fit.result.model.name.find("my-start") != std::string::npos);  // "<start>-calibrated" unless named
}

TEST_CASE("provenance: version, commit, effective config with defaults, presets, threads, date") {
    const fs::path out = scratch("provenance");
    REQUIRE(simulate({kTiny, "--out", out.string(), "--set", "output.images=false", "--set", "workload.width=8",
                      "--set", "workload.height=8"}) == 0);
    const json p = report_of(out)["provenance"];
    CHECK(p["git_commit"].is_string());
    CHECK_FALSE(p["git_commit"].get<std::string>().empty());
    CHECK(p["threads"]["requested"] == 2);
    CHECK(p["date"].get<std::string>().size() == 20);
    CHECK(p["date"].get<std::string>().back() == 'Z');
    CHECK(p["command_line"][1] == kTiny);
    // Defaults filled in: the tiny config sets no bvh, traversal or seed.
    const json& e = p["effective_config"];
    CHECK(e["bvh"]["width"] == 4);
    CHECK(e["traversal"]["schedule"] == "immediate");
    CHECK(e["workload"]["seed"] == 0);
    CHECK(e["workload"]["width"] == 8);
    // It parses again as a config, to the same effective config.
    const RunConfig again = parse_run_config(e, kTiny);
    CHECK(json(run_config_to_json(again, e)) == e);
    // Preset contents as in the files.
    for (const json& preset : p["presets"]["cost"])
        CHECK(preset["contents"] == json::parse(read_text_file(preset["file"].get<std::string>())));
    CHECK(p["presets"]["memory"]["contents"]["name"].is_string());
}

TEST_CASE("sweep: the first key varies slowest, in the order written") {
    const std::string text = R"({"sweep": {"scene.tilt_deg": [0, 30], "memory": ["memory-optix7", "memory-dxr"]}})";
    const std::vector<std::string> order = sweep_key_order(text);
    REQUIRE(order == std::vector<std::string>{"scene.tilt_deg", "memory"});
    const auto points = expand_sweep(json::parse(text), "x.json", order);
    REQUIRE(points.size() == 4);
    CHECK(points[0].label == "scene.tilt_deg=0 memory=memory-optix7");
    CHECK(points[1].label == "scene.tilt_deg=0 memory=memory-dxr");
    CHECK(points[2].label == "scene.tilt_deg=30 memory=memory-optix7");
    // Without the order, alphabetical (nlohmann sorts keys).
    CHECK(expand_sweep(json::parse(text), "x.json")[1].label == "memory=memory-optix7 scene.tilt_deg=30");
    // --set sweep={...} replaces the order; --set sweep.key=[...] appends.
    CHECK(sweep_key_order(text, {R"(sweep={"b": [1], "a": [2]})"}) == std::vector<std::string>{"b", "a"});
    CHECK(sweep_key_order(text, {R"(sweep.cost=["turing-per-ray-guess"])"}).back() == "cost");
}

TEST_CASE("sweep: points that differ only in presets are re-priced, not traced, with the same results") {
    const fs::path dir = scratch("reprice");
    const std::vector<std::string> small{"--set", "output.images=false", "--set", "workload.width=12",
                                         "--set", "workload.height=12", "--set", "output.rays=false",
                                         "--set", "output.hits=false"};
    auto sweep = small;
    sweep.insert(sweep.end(), {"--set", R"(sweep={"scene.tilt_deg": [0, 30], "memory": ["memory-optix7", "memory-dxr"], "cost": ["turing-per-ray-guess", "turing-per-ray-calibrated"]})",
                               kTiny, "--out", (dir / "sweep").string()});
    REQUIRE(simulate(sweep) == 0);
    const fs::path point3 = dir / "sweep" / "3_scene.tilt_deg=0_memory=memory-dxr_cost=turing-per-ray-calibrated";
    REQUIRE(fs::exists(point3 / "report.json"));
    CHECK(report_of(dir / "sweep" / "0_scene.tilt_deg=0_memory=memory-optix7_cost=turing-per-ray-guess")["provenance"]["repriced"] == false);
    CHECK(report_of(point3)["provenance"]["repriced"] == true);
    CHECK(report_of(dir / "sweep" / "4_scene.tilt_deg=30_memory=memory-optix7_cost=turing-per-ray-guess")["provenance"]["repriced"] == false);
    // The same point traced on its own gives the same report.
    auto single = small;
    single.insert(single.end(), {"--set", "scene.tilt_deg=0", "--set", "memory=memory-dxr", "--set",
                                 "cost=turing-per-ray-calibrated", kTiny, "--out", (dir / "single").string()});
    REQUIRE(simulate(single) == 0);
    CHECK(comparable(report_of(point3)) == comparable(report_of(dir / "single")));
}

TEST_CASE("sweep: re-priced points with their warp presets in another order keep each preset's pixel cycles and sampling interval") {
    // Results are keyed by preset name (FrameResult::warp_of). Before, a
    // re-priced point read the per-pixel cycles by position: with the
    // presets reordered, cycles_<method>_<preset>.npy and the sampling
    // intervals were another preset's.
    const fs::path dir = scratch("reprice_order");
    REQUIRE(simulate({"--set", "output.images=false", "--set", "workload.width=16", "--set", "workload.height=16",
                      "--set", "output.rays=false", "--set", "output.hits=false", "--set",
                      R"(sampling={"fraction": 0.5, "seed": 1})", "--set",
                      R"(sweep={"cost": [["turing-calibrated", "turing-sm"], ["turing-sm", "turing-calibrated"], ["turing-calibrated", "turing-sm"]]})",
                      kTiny, "--out", (dir / "sweep").string()}) == 0);
    std::vector<fs::path> points;
    for (const auto& e : fs::directory_iterator(dir / "sweep"))
        if (e.is_directory()) points.push_back(e.path());
    std::sort(points.begin(), points.end());  // 0_..., 1_..., 2_...
    REQUIRE(points.size() == 3);
    const json first = report_of(points[0]);
    CHECK(first["provenance"]["repriced"] == false);
    for (std::size_t i = 1; i < points.size(); ++i) {
        CAPTURE(i);
        const json point = report_of(points[i]);
        CHECK(point["provenance"]["repriced"] == true);
        for (const char* preset : {"turing-calibrated", "turing-sm"}) {
            CAPTURE(preset);
            const json& want = first["speedup_sampling_interval_over_ref"]["obb"][preset];
            REQUIRE(want.is_array());
            CHECK(point["speedup_sampling_interval_over_ref"]["obb"][preset] == want);
            for (const char* method : {"ref", "obb"}) {
                const std::string npy = std::string("cycles_") + method + "_" + preset + ".npy";
                CAPTURE(npy);
                CHECK(read_text_file((points[i] / npy).string()) == read_text_file((points[0] / npy).string()));
            }
        }
    }
}

}  // namespace RTCSIM_TEST_FILE
