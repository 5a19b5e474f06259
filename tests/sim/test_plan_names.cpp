// Issue 56's planning findings: what used to pass the plan and go wrong
// later with exit 0 (or after tracing). Two cost presets of one name;
// break-even names that are not file names, or shared by two maps; one event
// on both axes; a method listed twice; a misspelt hypothetical method; the
// break-even maps' work above its ceiling; and derived presets' errors that
// name the derived preset and the config's key, cycles by their members.
#include "core/input_error.h"
#include "sim/app/run_all.h"
#include "sim/hardware/cost_model.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const std::string kHw = RTCSIM_SOURCE_DIR "/configs/hw/";

fs::path scratch() {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_plan_names";
    fs::create_directories(dir);
    return dir;
}

json tiny() { return parse_json_text(read_text_file("tests/configs/tiny.json"), "tiny"); }

json preset(const std::string& base, const std::string& name) {
    json p = parse_json_text(read_text_file(kHw + base + ".json"), base);
    p["name"] = name;
    return p;
}

std::string write(const std::string& file, const json& j) {
    const fs::path p = scratch() / file;
    std::ofstream(p, std::ios::trunc) << j.dump(1);
    return p.string();
}

std::string plan_error(const json& config, WorkLimits limits = {}) {
    try {
        (void)plan_runs(config, "tests/configs/tiny.json", {}, limits);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

// A break_even list is written json::array({m}): a braced list of one json
// is a copy of it under clang (nlohmann/json's documented pitfall), not a list.
json map(const std::string& name, std::vector<std::string> x, std::vector<std::string> y) {
    return {{"name", name}, {"preset", "turing-per-ray-guess"}, {"cells", 8},
            {"x", {{"events", x}, {"min", 1}, {"max", 100}}}, {"y", {{"events", y}, {"min", 1}, {"max", 100}}}};
}

void check_error(const std::string& e, const std::string& start, const std::string& part) {
    CAPTURE(e);
    CHECK(e.rfind(start, 0) == 0);
    CHECK(e.find(part) != std::string::npos);
    CHECK(e.find('\n') == std::string::npos);
}

}  // namespace

TEST_CASE("plan: two cost presets of one name are refused, naming both files") {
    const std::string a = write("dup_a.json", preset("turing-per-ray-guess", "dup"));
    const std::string b = write("dup_b.json", preset("turing-warp-guess", "dup"));
    json c = tiny();
    c["cost"] = {a, b};
    check_error(plan_error(c), "tests/configs/tiny.json: /cost/1: preset \"dup\" (" + b + "): has the name of /cost/0 (" + a + ")",
                "rename one");
    // Names that differ but make one file name (cycles_<method>_<name>.npy).
    c["cost"] = {write("slash.json", preset("turing-per-ray-guess", "a/b")),
                 write("under.json", preset("turing-warp-guess", "a_b"))};
    check_error(plan_error(c), "tests/configs/tiny.json: /cost/1: preset \"a_b\"", "names the same files as /cost/0");
}

TEST_CASE("plan: break-even names, axes and methods are checked before tracing") {
    json c = tiny();
    c["cost"] = {"turing-per-ray-guess"};
    c["break_even"] = json::array({map("../up", {"tlas_box_test"}, {"blas_box_test"})});
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/0/name: \"../up\" cannot name the map's files",
                "letters, digits");
    c["break_even"] = {map("m", {"tlas_box_test"}, {"blas_box_test"}), map("m", {"ray"}, {"triangle_test"})};
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/1/name: \"m\" is also the name of /break_even/0", "");
    c["break_even"] = json::array({map("m", {"tlas_box_test"}, {"blas_box_test", "tlas_box_test"})});
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/0/y/events/1: tlas_box_test is on the x axis too", "");
    c["break_even"] = json::array({map("m", {"tlas_box_test", "tlas_box_test"}, {"blas_box_test"})});
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/0/x/events/1: tlas_box_test is listed twice", "");
    json twice = map("m", {"tlas_box_test"}, {"blas_box_test"});
    twice["methods"] = {"obb", "obb"};
    c["break_even"] = json::array({twice});
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/0/methods/1: \"obb\" is listed twice", "");
    c["break_even"] = json::array({map("fine-name_1.2", {"tlas_box_test"}, {"blas_box_test"})});
    CHECK(plan_error(c) == "(no error)");
}

TEST_CASE("plan: the break-even maps' work is estimated and bounded (--max-break-even, --force)") {
    json c = tiny();
    c["cost"] = {"turing-calibrated"};  // a preset with a covariance: its draws are priced too
    json big = map("big", {"tlas_box_test"}, {"blas_box_test"});
    big["preset"] = "turing-calibrated";
    big["cells"] = 256;
    c["break_even"] = json::array({big});
    c["uncertainty"] = {{"draws", 4096}};
    // 256 x 256 cells x 4,097 cost models x 2 methods: 113 s once, unbounded.
    check_error(plan_error(c), "tests/configs/tiny.json: /break_even/0/cells: about 5.37e+08 break-even cell prices "
                               "(256 x 256 cells x 4097 cost model(s) x 2 method(s)) exceed --max-break-even 2e+08",
                "--force");
    WorkLimits forced;
    forced.force = true;
    const RunPlan p = plan_runs(c, "tests/configs/tiny.json", {}, forced);
    CHECK(p.work.break_even == doctest::Approx(256.0 * 256 * 4097 * 2));
    WorkLimits raised;
    raised.max_break_even = 1e9;
    CHECK(plan_error(c, raised) == "(no error)");
}

TEST_CASE("plan: a preset's hypothetical method must be a method") {
    json p = preset("turing-per-ray-guess", "typo");
    p["hypothetical"] = {{"obb-quantised", "[I] misspelt"}};
    const std::string file = write("typo.json", p);
    json c = tiny();
    c["cost"] = {file};
    check_error(plan_error(c), file + ": /hypothetical/obb-quantised: not a method (expected one of ", "obb-quantized");
}

TEST_CASE("derived presets: a base's error names the derived preset and /cost/N, cycles name their members") {
    json base = preset("turing-per-ray-guess", "base");
    base["cycles"].erase("ray");
    write("broken_base.json", base);
    const std::string derived = write("derived_on_broken.json", {{"name", "d"}, {"derived_from", "broken_base.json"},
                                                                {"deltas", json::array()}});
    json c = tiny();
    c["cost"] = {"turing-per-ray-guess", derived};
    check_error(plan_error(c), (scratch() / "broken_base.json").string() + ": /cycles/ray: missing",
                "(the base of " + derived + ") (tests/configs/tiny.json: /cost/1)");
    // Three presets deriving from each other: named as the cycle.
    write("cyc_a.json", {{"name", "a"}, {"derived_from", "cyc_b.json"}, {"deltas", json::array()}});
    write("cyc_b.json", {{"name", "b"}, {"derived_from", "cyc_c.json"}, {"deltas", json::array()}});
    write("cyc_c.json", {{"name", "c"}, {"derived_from", "cyc_a.json"}, {"deltas", json::array()}});
    c["cost"] = {(scratch() / "cyc_a.json").string()};
    check_error(plan_error(c), (scratch() / "cyc_c.json").string() + ": /derived_from: presets derive from each other in a cycle: "
                               "cyc_a.json -> cyc_b.json -> cyc_c.json -> cyc_a.json", "/cost/0");
    // Sums of costs in a cycle of three, with a sum outside it that depends on it: the cycle is named.
    json sums = preset("turing-per-ray-guess", "sums");
    sums["cycles"]["tlas_box_test"] = {{"sum_of", {{"blas_box_test", 1}}}, {"source", "x"}};
    sums["cycles"]["blas_box_test"] = {{"sum_of", {{"triangle_test", 1}}}, {"source", "x"}};
    sums["cycles"]["triangle_test"] = {{"sum_of", {{"tlas_box_test", 1}}}, {"source", "x"}};
    sums["cycles"]["ray"] = {{"sum_of", {{"triangle_test", 1}}}, {"source", "x"}};
    const std::string e = [&] {
        try {
            (void)parse_cost_model(sums.dump(), "sums.json");
        } catch (const InputError& x) {
            return std::string(x.what());
        }
        return std::string("(no error)");
    }();
    CAPTURE(e);
    CHECK(e.find("sums.json: /cycles/") == 0);
    CHECK(e.find("/cycles/ray") == std::string::npos);  // ray only depends on the cycle
    CHECK(e.find("in a cycle: ") != std::string::npos);
    CHECK(e.find("tlas_box_test") != std::string::npos);
    CHECK(e.find("blas_box_test") != std::string::npos);
}

TEST_CASE("derived presets: the resolution note does not say a derived preset was fitted") {
    CostModel m = load_cost_model(kHw + "ampere.json");
    REQUIRE(m.fitted_on.pixels() > 0);
    const std::string note = resolution_note(m, 16);
    CHECK(note.find("ampere (derived from turing-calibrated) takes its costs from a fit at ") == 0);
    CHECK(note.find("ampere was fitted") == std::string::npos);
}

}  // namespace RTCSIM_TEST_FILE
