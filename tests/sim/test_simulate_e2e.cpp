// End-to-end runs of `simulate` (in process, through run_all): outputs exist
// and agree, ray files replay to the same hits, thread counts do not change
// anything, and bad configs fail with one line naming the file and JSON path.
#include "core/input_error.h"
#include "sim/util/json_file.h"
#include "sim/workload/ray_file.h"
#include "sim/app/run_all.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kTiny = "tests/configs/tiny.json";

std::string out_dir(const std::string& name) {
    const fs::path p = fs::path(RTCSIM_BINARY_DIR) / "e2e" / name;
    fs::remove_all(p);
    return p.string();
}

int run(const std::string& config, const std::string& out, std::vector<std::string> sets = {},
        unsigned threads = 0) {
    CliOptions cli;
    cli.config = config;
    cli.out = out;
    cli.quiet = true;
    cli.threads = threads;
    cli.sets = std::move(sets);
    return run_all(cli);
}

std::string slurp(const std::string& path) { return read_text_file(path); }

nlohmann::json report(const std::string& dir) {
    return nlohmann::json::parse(slurp((fs::path(dir) / "report.json").string()));
}

std::string error_of(const std::string& config, std::vector<std::string> sets = {}, std::string out = "") {
    try {
        run(config, out.empty() ? out_dir("err") : out, std::move(sets));
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("simulate e2e: a tiny run writes every output and both methods agree") {
    const std::string dir = out_dir("tiny");
    REQUIRE(run(kTiny, dir) == 0);
    for (const char* f : {"report.json", "summary.csv", "summary.md", "render.png", "heat_cycles_ref.png",
                          "heat_cycles_obb.png", "heat_is_calls_ref.png", "heat_is_calls_obb.png",
                          "ratio_cycles_ref_over_obb.png", "rays.bin", "hits_ref.bin", "hits_obb.bin"})
        CHECK_MESSAGE(fs::exists(fs::path(dir) / f), f);
    const auto r = report(dir);
    CHECK(r["methods"]["ref"]["runnable"] == true);
    CHECK(r["methods"]["obb"]["instances"] == 60);
    const auto& ref_events = r["methods"]["ref"]["events"];
    const auto& obb_events = r["methods"]["obb"]["events"];
    // Same rays, same hits: identical ray and reported-hit counts.
    CHECK(ref_events["ray"]["total"] == obb_events["ray"]["total"]);
    CHECK(ref_events["ray"]["total"].get<std::uint64_t>() >= 48 * 48 * 2);
    CHECK(obb_events["is_call"]["total"].get<std::uint64_t>() < ref_events["is_call"]["total"].get<std::uint64_t>());
    CHECK(r["speedup_over_ref"]["obb"]["turing-per-ray-guess"].get<double>() > 1.0);
    CHECK(r["scene"]["surface_area"]["aabb_over_obb_paper"].get<double>() > 1.0);
    CHECK(r["memory_overhead_percent"]["obb"].get<double>() > 0.0);
    // Hit files of the two methods are byte-identical.
    CHECK(slurp(dir + "/hits_ref.bin") == slurp(dir + "/hits_obb.bin"));
    CHECK(fs::file_size(dir + "/rays.bin") == 32 * r["methods"]["ref"]["rays"].get<std::uint64_t>());
    CHECK(slurp(dir + "/summary.csv").find("tiny") != std::string::npos);
}

TEST_CASE("simulate e2e: dots reports its hit agreement with ref, traced before or after it") {
    // Without hit files: ref records a sample of its rays for the comparison
    // only; dots traced first waits for it.
    const std::vector<std::string> quiet{"output.rays=false", "output.hits=false", "output.images=false"};
    const std::string after = out_dir("dots_after"), before = out_dir("dots_before");
    auto sets = quiet;
    sets.push_back("methods=[\"ref\",\"dots\"]");
    REQUIRE(run(kTiny, after, sets) == 0);
    sets.back() = "methods=[\"dots\",\"ref\"]";
    REQUIRE(run(kTiny, before, sets) == 0);
    const auto a = report(after), b = report(before);
    const auto& h = a["methods"]["dots"]["hit_agreement"];
    CHECK(h["baseline"] == "ref");
    CHECK(h["rays"].get<std::uint64_t>() == a["methods"]["ref"]["rays"].get<std::uint64_t>());  // all, under 65,536
    CHECK(h["fraction"].get<double>() > 0.9);
    CHECK(h["fraction"].get<double>() <= h["hit_miss_fraction"].get<double>());
    CHECK(b["methods"]["dots"]["hit_agreement"] == h);
    CHECK_FALSE(a["methods"]["ref"].contains("hit_agreement"));  // exact methods are tested, not measured
    CHECK(a["methods"]["dots"]["events"]["is_call"]["total"] == 0);
    CHECK(a["methods"]["dots"]["memory_bytes"]["strip_buffers"].get<double>() > 0.0);
    for (const char* f : {"rays.bin", "hits_ref.bin", "hits_dots.bin"}) CHECK_FALSE(fs::exists(fs::path(after) / f));
    const std::string csv = slurp(after + "/results.csv");
    CHECK(csv.find(",hit_agreement,reason") != std::string::npos);
}

TEST_CASE("simulate e2e: a ray file replays to the same hits") {
    const std::string first = out_dir("record");
    REQUIRE(run(kTiny, first) == 0);
    const std::string replay = out_dir("replay");
    REQUIRE(run(kTiny, replay,
                {"workload={\"type\":\"rays\",\"rays_file\":\"" + first + "/rays.bin\"}", "output.images=false"}) == 0);
    CHECK(slurp(replay + "/hits_ref.bin") == slurp(first + "/hits_ref.bin"));
    CHECK(slurp(replay + "/hits_obb.bin") == slurp(first + "/hits_obb.bin"));
    CHECK(report(replay)["methods"]["obb"]["events"] == report(first)["methods"]["obb"]["events"]);
}

TEST_CASE("simulate e2e: counts and report do not depend on the thread count") {
    const std::string one = out_dir("threads1"), two = out_dir("threads3");
    REQUIRE(run(kTiny, one, {"output.rays=false"}, 1) == 0);
    REQUIRE(run(kTiny, two, {"output.rays=false"}, 3) == 0);
    const auto a = report(one), b = report(two);
    for (const char* m : {"ref", "obb"}) {
        CHECK(a["methods"][m]["events"] == b["methods"][m]["events"]);
        CHECK(a["methods"][m]["cycles"] == b["methods"][m]["cycles"]);
    }
    CHECK(slurp(one + "/hits_obb.bin") == slurp(two + "/hits_obb.bin"));
    CHECK(slurp(one + "/heat_cycles_ref.png") == slurp(two + "/heat_cycles_ref.png"));
}

TEST_CASE("simulate e2e: cluster of size 1 costs what obb costs, and finds ref's hits") {
    const std::string dir = out_dir("cluster1");
    REQUIRE(run(kTiny, dir, {"methods=[\"ref\",\"obb\",\"cluster\"]", "cluster={\"size\":1}",
                             "output={\"images\":false,\"hits\":true}"}) == 0);
    const nlohmann::json r = report(dir);
    CHECK(r["methods"]["cluster"]["events"] == r["methods"]["obb"]["events"]);
    CHECK(r["methods"]["cluster"]["memory_bytes"] == r["methods"]["obb"]["memory_bytes"]);
    CHECK(r["speedup_over_ref"]["cluster"] == r["speedup_over_ref"]["obb"]);
    CHECK(slurp(dir + "/hits_cluster.bin") == slurp(dir + "/hits_ref.bin"));
    const std::string sixteen = out_dir("cluster16");
    REQUIRE(run(kTiny, sixteen, {"methods=[\"ref\",\"cluster\"]", "cluster={\"size\":16}",
                                 "output={\"images\":false,\"hits\":true}"}) == 0);
    CHECK(report(sixteen)["methods"]["cluster"]["instances"] == 4);  // 60 / 16, rounded up
    CHECK(slurp(sixteen + "/hits_cluster.bin") == slurp(sixteen + "/hits_ref.bin"));
}

TEST_CASE("simulate e2e: a sweep writes one row per point and a plot") {
    const std::string dir = out_dir("sweep");
    REQUIRE(run(kTiny, dir, {"sweep={\"scene.tilt_deg\":[0,45]}", "output={\"images\":false}",
                             "workload.width=16", "workload.height=16"}) == 0);
    const std::string csv = slurp(dir + "/summary.csv");
    CHECK(csv.find("scene.tilt_deg=0") != std::string::npos);
    CHECK(csv.find("scene.tilt_deg=45") != std::string::npos);
    CHECK(fs::exists(dir + "/speedup_vs_scene.tilt_deg.svg"));
    CHECK(slurp(dir + "/speedup_vs_memory.svg").find("memory overhead (Pareto)") != std::string::npos);
    CHECK(fs::exists(dir + "/0_scene.tilt_deg=0/report.json"));
}

TEST_CASE("simulate e2e: the phantom program is selectable and reports iterations per call") {
    for (const std::string program : {"bracketed", "paper"}) {
        const std::string dir = out_dir("phantom_" + program);
        REQUIRE(run(kTiny, dir, {"primitives.kind=phantom", "traversal.phantom_program=" + program,
                                 "output={\"images\":false}", "workload.width=24", "workload.height=24"}) == 0);
        const auto r = report(dir);
        for (const char* m : {"ref", "obb"}) {
            CAPTURE(program);
            CAPTURE(m);
            const auto& method = r["methods"][m];
            const auto& ev = method["events"];
            const bool paper = program == "paper";
            CHECK(method["phantom"]["program"] == program);
            CHECK(method["phantom"]["calls"] == ev["is_phantom"]["total"]);
            const double iterations = ev[paper ? "phantom_paper_iteration" : "phantom_iteration"]["total"];
            CHECK(method["phantom"]["iterations_per_call"].get<double>() ==
                  doctest::Approx(iterations / ev["is_phantom"]["total"].get<double>()));
            CHECK(ev[paper ? "phantom_iteration" : "phantom_paper_iteration"]["total"] == 0);
            CHECK(ev[paper ? "phantom_early_out" : "phantom_cylinder_test"]["total"] == 0);
            CHECK(ev["phantom_setup"]["total"].get<double>() > 0);
            CHECK(method["phantom"]["iterations_per_call"].get<double>() <= (paper ? 80.0 : 24.0 * 28));
        }
        CHECK(r["methods"]["ref"]["events"]["reported_hit"]["total"].get<double>() > 0);
    }
}

TEST_CASE("simulate e2e: bad input fails with one line naming the file and JSON path") {
    CHECK(error_of(kTiny, {"traversal.phantom_program=\"fast\""}).find(kTiny + ": /traversal/phantom_program:") == 0);
    CHECK(error_of(kTiny, {"workload.spp=-4"}) ==
          kTiny + ": /workload/spp: expected a positive integer, got -4");
    CHECK(error_of(kTiny, {"workload.bogus=1"}).find(kTiny + ": /workload/bogus: unknown key") == 0);
    CHECK(error_of(kTiny, {"scene.count=\"many\""}).find(kTiny + ": /scene/count:") == 0);
    CHECK(error_of(kTiny, {"methods=[\"fast\"]"}).find(kTiny + ": /methods/0:") == 0);
    CHECK(error_of(kTiny, {"primitives.subdivision=3"}).find(kTiny + ": /primitives/subdivision:") == 0);
    CHECK(error_of(kTiny, {"bvh.width=5"}).find(kTiny + ": /bvh/width:") == 0);
    CHECK(error_of(kTiny, {"cluster.size=0"}).find(kTiny + ": /cluster/size:") == 0);
    CHECK(error_of(kTiny, {"cluster.strategy=\"random\""}).find(kTiny + ": /cluster/strategy:") == 0);
    CHECK(error_of(kTiny, {"cluster.frame=\"pca\""}).find(kTiny + ": /cluster/frame:") == 0);
    CHECK(error_of(kTiny, {"cluster.sise=4"}).find(kTiny + ": /cluster/sise: unknown key") == 0);
    CHECK(error_of(kTiny, {"cost=\"nope.json\""}).find(kTiny + ": /cost: no such preset file: tests/configs/nope.json") == 0);
    CHECK(error_of(kTiny, {"scene={\"type\":\"file\",\"curves\":{\"path\":\"missing.hair\"}}"})
              .find("missing.hair") != std::string::npos);
    CHECK(error_of("tests/configs/does_not_exist.json") == "tests/configs/does_not_exist.json: cannot open file");
    // An output directory that cannot be created (a path below a regular file).
    const std::string blocker = out_dir("blocker");
    fs::create_directories(fs::path(blocker).parent_path());
    std::ofstream(blocker) << "x";
    CHECK(error_of(kTiny, {}, blocker + "/sub").find(blocker + "/sub: cannot create output directory") == 0);
}

}  // namespace RTCSIM_TEST_FILE
