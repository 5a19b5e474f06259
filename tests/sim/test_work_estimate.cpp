// The work estimate's memory model: the methods' own terms (MethodEntry::
// footprint) on top of the per-primitive figure, from the config alone.
// (That the estimate bounds a measured peak: python/tests/test_estimate_bound.py.)
#include "sim/app/run_all.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

const std::string kFur = "configs/runs/cluster_fur20m.json";

// The estimate of the 20 M fur's config, its sweep replaced by one cluster size.
WorkEstimate fur(const std::vector<std::string>& sets) {
    WorkLimits forced;
    forced.force = true;  // see the figures, whatever they are
    std::vector<std::string> all{"sweep={}"};
    all.insert(all.end(), sets.begin(), sets.end());
    return plan_config_text(kFur, read_text_file(kFur), all, forced).work;
}

}  // namespace

TEST_CASE("work estimate: cluster's own BLASes and obb's instances are counted, over the limit not") {
    const double prims = 5e6 * 4;  // 5 M strands of 5 points
    // Two methods, as below (pixels count per method); split has no footprint of its own.
    const double ref = fur({"methods=[\"ref\",\"split\"]"}).memory_bytes;
    // Size 2: 10 M clusters, each its own BLAS (16 KiB of fragmented heap, measured 13.5 KB) and instance.
    const WorkEstimate two = fur({"cluster.size=2"});
    CHECK(two.memory_bytes - ref == doctest::Approx(prims / 2 * (200 + 16384)));
    CHECK(two.memory_key == "/cluster/size");
    CHECK(two.memory_detail == "cluster's structures over 2e+07 primitives in clusters of 2");
    CHECK(fur({"cluster.size=4"}).memory_bytes - ref == doctest::Approx(prims / 4 * (200 + 5120)));
    CHECK(fur({"cluster.size=16"}).memory_bytes - ref == doctest::Approx(prims / 16 * (200 + 1536)));
    // Size 1 would be 20 M instances, over the 2^24 limit: not built, nothing counted.
    CHECK(fur({"cluster.size=1"}).memory_bytes == doctest::Approx(ref));
    CHECK(fur({"methods=[\"ref\",\"obb\"]"}).memory_bytes == doctest::Approx(ref));
    // Under the limit the masquerade's instances count: 200 B each.
    CHECK(fur({"methods=[\"ref\",\"obb\"]", "scene.strands=1000000"}).memory_bytes -
              fur({"methods=[\"ref\",\"split\"]", "scene.strands=1000000"}).memory_bytes ==
          doctest::Approx(4e6 * 200));
    // Strand clusters stop at their strand's end: up to one more per strand.
    CHECK(fur({"cluster.size=16", "cluster.strategy=\"strand\""}).memory_bytes - ref ==
          doctest::Approx((prims / 16 + 5e6) * (200 + 1536)));
}

TEST_CASE("work estimate: the shipped 20 M fur sweep fits 16 GiB, and size 2 is refused naming its key") {
    WorkLimits sixteen;
    sixteen.max_memory = 16.0 * 1024 * 1024 * 1024;
    const RunPlan plan = plan_config_text(kFur, read_text_file(kFur), {}, sixteen);  // throws if it does not fit
    CHECK(plan.work.memory_bytes <= sixteen.max_memory);
    CHECK_THROWS_WITH_AS(static_cast<void>(plan_config_text(kFur, read_text_file(kFur),
                                                            {"sweep={\"cluster.size\":[1,2,8]}"}, sixteen)),
                         doctest::Contains("of memory (cluster's structures over 2e+07 primitives in clusters of 2) "
                                           "exceed --max-memory 16 GiB"),
                         InputError);
}

TEST_CASE("work estimate: phantom curves count by the curve basis") {
    // 5 M strands of 5 points: 4 links each, so 4 B-spline curves or 2 Bezier
    // cubics (one full, one degree-elevated link); capsules 4 either way.
    const std::string phantom = "primitives={\"kind\": \"phantom\", \"subdivision\": 2}";
    CHECK(fur({phantom}).primitives == doctest::Approx(5e6 * 4 * 2));
    CHECK(fur({phantom, "scene.curve_basis=\"bezier\""}).primitives == doctest::Approx(5e6 * 2 * 2));
    CHECK(fur({"primitives={\"kind\": \"capsule\"}", "scene.curve_basis=\"bezier\""}).primitives ==
          doctest::Approx(5e6 * 4));
}

}  // namespace RTCSIM_TEST_FILE
