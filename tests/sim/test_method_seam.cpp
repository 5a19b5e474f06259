// The method seam from outside the tree: a toy method defined only here (no
// BVH at all: every primitive is a candidate, as a brute-force reference
// would be) is registered at run time, and the real `simulate` program runs
// it beside ref and obb. It must find the same hit for every ray (hits files
// byte for byte), and the reports must carry its speedup against the baseline.
#include "sim/app/simulate_main.h"
#include "sim/hardware/cost_model.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <filesystem>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

// No acceleration structure: each ray visits every triangle in the RT unit
// and hands every custom primitive to its program (world-space ray).
struct BruteForce {
    struct Structures {
        std::uint32_t primitives = 0, triangles = 0;
    };
    static StructureCounts count(const Structures& s) {
        StructureCounts c;
        c.custom_prims = s.primitives;
        c.triangles = s.triangles;
        return c;
    }
    static std::size_t bytes(const Structures&) { return sizeof(Structures); }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        float tmax = ray.tmax;
        for (std::uint32_t i = 0; i < s.triangles; ++i) tmax = std::min(tmax, programs.triangle(i, ray, tmax));
        for (std::uint32_t i = 0; i < s.primitives; ++i) tmax = std::min(tmax, programs.custom(i, ray, tmax));
        return programs.template finish<Mode>(ray);
    }
};

void register_brute_force_once() {
    if (find_method("test-brute")) return;
    register_method({{"test-brute", "test only: every primitive is a candidate (no BVH)", {"custom_primitives"}},
                     [](const Geometry&, const MethodOptions&) -> std::uint64_t { return 0; },
                     [](const Geometry& g, const MethodOptions&) -> std::unique_ptr<BuiltMethod> {
                         return std::make_unique<BuiltMethodOf<BruteForce>>(BruteForce::Structures{
                             static_cast<std::uint32_t>(g.primitive_count()),
                             static_cast<std::uint32_t>(g.triangles.size())});
                     }});
}

}  // namespace

TEST_CASE("method seam: a method added from the test tree runs in simulate beside ref and obb") {
    register_brute_force_once();
    CHECK(method_names_list().find("test-brute") != std::string::npos);
    const fs::path out = fs::path(RTCSIM_BINARY_DIR) / "e2e" / "method_seam";
    fs::remove_all(out);
    const int code = simulate_main({"tests/configs/tiny.json", "--quiet", "--threads", "2", "--out", out.string(),
                                    "--set", R"(methods=["ref","obb","test-brute"])",
                                    "--set", "workload.width=24", "--set", "workload.height=24"});
    REQUIRE(code == 0);
    const nlohmann::json r = nlohmann::json::parse(read_text_file((out / "report.json").string()));
    const auto& speedups = r.at("speedup_over_ref");
    REQUIRE(speedups.contains("obb"));
    REQUIRE(speedups.contains("test-brute"));
    const double brute = speedups["test-brute"]["turing-per-ray-guess"].get<double>();
    const double obb = speedups["obb"]["turing-per-ray-guess"].get<double>();
    CHECK(obb > 1.0);
    CHECK(brute > 0.0);
    CHECK(brute < 1.0);  // 60 programs per ray cost more than ref's few
    // Every custom primitive is a candidate for every ray.
    const auto& events = r["methods"]["test-brute"]["events"];
    CHECK(events["is_call"]["total"].get<std::uint64_t>() ==
          60 * events["ray"]["total"].get<std::uint64_t>());
    CHECK(r["memory_overhead_percent"].contains("test-brute"));
    // Same hits, ray for ray, as the other methods.
    const std::string ref_hits = read_text_file((out / "hits_ref.bin").string());
    CHECK(!ref_hits.empty());
    CHECK(read_text_file((out / "hits_test-brute.bin").string()) == ref_hits);
    CHECK(read_text_file((out / "hits_obb.bin").string()) == ref_hits);
    // A ratio map per method against the baseline, and summary columns for all three.
    CHECK(fs::exists(out / "ratio_cycles_ref_over_test-brute.png"));
    CHECK(fs::exists(out / "ratio_cycles_ref_over_obb.png"));
    const std::string summary = read_text_file((out / "summary.csv").string());
    CHECK(summary.find("test-brute speedup") != std::string::npos);
    CHECK(summary.find("obb speedup") != std::string::npos);
}

TEST_CASE("method seam: the baseline is named in the config and must be one of its methods") {
    register_brute_force_once();
    const fs::path out = fs::path(RTCSIM_BINARY_DIR) / "e2e" / "method_seam_baseline";
    fs::remove_all(out);
    REQUIRE(simulate_main({"tests/configs/tiny.json", "--quiet", "--out", out.string(), "--set",
                           R"(methods=["ref","test-brute"])", "--set", "baseline=test-brute", "--set",
                           "workload.width=16", "--set", "workload.height=16", "--set", "output.images=false"}) == 0);
    const nlohmann::json r = nlohmann::json::parse(read_text_file((out / "report.json").string()));
    REQUIRE(r.contains("speedup_over_test-brute"));
    CHECK(r["speedup_over_test-brute"]["ref"]["turing-per-ray-guess"].get<double>() > 1.0);
    CHECK(simulate_main({"tests/configs/tiny.json", "--quiet", "--out", out.string(), "--set",
                         R"(methods=["ref","obb"])", "--set", "baseline=test-brute"}) == 2);
    CHECK(simulate_main({"tests/configs/tiny.json", "--quiet", "--out", out.string(), "--set",
                         R"(methods=["ref","no-such-method"])"}) == 2);
    CHECK(simulate_main({"tests/configs/tiny.json", "--quiet", "--out", out.string(), "--set",
                         R"(methods=["ref","ref"])"}) == 2);
}

TEST_CASE("method seam: a preset without a feature a method needs prices it n/a") {
    CostModel m;
    m.features = {"custom_primitives"};
    CHECK(m.missing_feature({"custom_primitives"}).empty());
    CHECK(m.missing_feature({"custom_primitives", "instance_transforms"}) == "instance_transforms");
    CHECK(find_method("obb")->info.needs.size() == 2);
}

}  // namespace RTCSIM_TEST_FILE
