// Embree 3's two hair BVHs (sim/bench/embree_hair.h), started for real on a
// small procedural hair scene: both must find the same closest hits on the
// simulator's rays (the aligned side with rtcsim's capsule test, the oriented
// side with Embree's own round linear curve test, so within float tolerance),
// the aligned side exactly ref's, and the setting must really have changed
// which BVH Embree built, as its own statistics say. Skipped with a message
// where bench was built without Embree.
#include "sim/bench/bench_run.h"
#include "sim/bench/embree_bench.h"
#include "sim/bench/embree_hair.h"

#include <doctest/doctest.h>

#include <cmath>
#include <variant>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("embree hair: Embree's verbose statistics are read per BVH, aligned and oriented nodes apart") {
    const std::string printed =
        "building BVH8<triangle4v> using avx::BVH8BuilderSAH ...\n"
        "  total            : sah =   1.500 (100.00%), #bytes =    0.10 MB (100.00%), #nodes =      20 ( 80.00% filled)\n"
        "  getAABBNodes     : sah =   1.000 ( 66.00%), #bytes =    0.05 MB ( 50.00%), #nodes =       5 (100.00% filled)\n"
        "  leaves           : sah =   0.500 ( 33.00%), #bytes =    0.05 MB ( 50.00%), #nodes =      15 ( 90.00% filled)\n"
        "building BVH8<curve8v> using avx::BVH8HairBuilderSAH ...\n"
        "finished BVH8<curve8v> : 30.8402ms, 0.648505 Mprim/s, 0.0167626 GB/s\n"
        "  total            : sah =  20.352 (100.00%), #bytes =    0.52 MB (100.00%), #nodes =    3258 ( 89.23% filled)\n"
        "  getAABBNodes     : sah =   2.461 ( 12.09%), #bytes =    0.00 MB (  0.45%), #nodes =       9 (100.00% filled)\n"
        "  ungetAABBNodes   : sah =   8.382 ( 41.18%), #bytes =    0.26 MB ( 49.92%), #nodes =     576 ( 69.12% filled)\n"
        "  leaves           : sah =   9.510 ( 46.72%), #bytes =    0.26 MB ( 49.64%), #nodes =    2673 ( 93.53% filled)\n"
        "  total : used =   0.538 MB, free =   0.098 MB, wasted =   0.001 MB, total =   0.636 MB\n";
    const std::vector<EmbreeBvhStats> s = parse_embree_statistics(printed);
    REQUIRE(s.size() == 2);
    CHECK(s[0].primitive == "triangle4v");
    CHECK(s[0].aligned_nodes == 5);
    CHECK(s[0].oriented_nodes == 0);
    CHECK(s[1].primitive == "curve8v");
    CHECK(s[1].builder == "avx::BVH8HairBuilderSAH");
    CHECK(s[1].aligned_nodes == 9);
    CHECK(s[1].oriented_nodes == 576);
    CHECK(s[1].leaves == 2673);
    CHECK(s[1].sah == doctest::Approx(20.352));
    CHECK(s[1].bytes == doctest::Approx(0.52e6));
}

TEST_CASE("embree hair: the oriented and the aligned BVH find the same closest hits and are the BVHs asked for") {
    if (!embree_built()) {
        MESSAGE("skipped: bench was built without Embree 3 (apt-get install libembree-dev, then configure again)");
        return;
    }
    // 2,000 wavy strands of 8 capsules on a sphere, with the sphere's mesh, seen
    // by the auto camera; path rays too (1 bounce), so secondary rays start on
    // hair and mesh.
    const nlohmann::json config = {
        {"scene", {{"type", "hair"}, {"emitter", "sphere"}, {"style", "wavy"}, {"strands", 2000},
                   {"points_per_strand", 9}, {"length", 0.5}, {"radius", 0.006}, {"seed", 7}, {"with_mesh", true}}},
        {"primitives", {{"kind", "capsule"}}},
        {"methods", {"ref"}},
        {"workload", {{"type", "camera"}, {"camera", "auto"}, {"width", 48}, {"height", 48}, {"spp", 1},
                      {"bounces", 1}}}};
    const LoadedRun run = load_run({"hair", config});
    const auto& capsules = std::get<std::vector<Capsule>>(run.geometry.prims);
    REQUIRE(capsules.size() == 2000 * 8);
    REQUIRE_FALSE(run.geometry.triangles.empty());
    FrameOptions record;
    record.progress = false;
    record.threads = 2;
    record.record_rays = record.record_hits = true;
    const FrameResult ref =
        find_method("ref")->build(run.geometry, run.config.build)->run(run.geometry, run.frame, run.config.trace, record);
    REQUIRE(ref.rays.size() > 48 * 48);

    // Built on one thread: with two, Embree builds the mesh's and the hair's
    // BVHs at once and their verbose statistics interleave, so a line can be
    // read as the other BVH's (the sanitizer build once saw the aligned
    // hair BVH's node count land in the mesh's).
    const EmbreeHairScene aligned(capsules, run.geometry.triangles, HairBvh::Aligned, 1);
    const EmbreeHairScene oriented(capsules, run.geometry.triangles, HairBvh::Oriented, 1);
    // The setting changed the BVH: user primitives in aligned nodes only, and
    // curves in Embree's hair BVH with oriented nodes.
    CHECK(aligned.hair_stats().primitive == "object");
    CHECK(aligned.hair_stats().oriented_nodes == 0);
    CHECK(aligned.hair_stats().aligned_nodes > 0);
    CHECK(oriented.hair_stats().primitive.rfind("curve", 0) == 0);
    CHECK(oriented.hair_stats().oriented_nodes > 0);
    CHECK(oriented.embree_bytes() > 0);

    std::vector<HairHit> a(ref.rays.size()), o(ref.rays.size());
    const std::uint64_t tests = aligned.trace(ref.rays, a, 2);
    CHECK(oriented.trace(ref.rays, o, 2) == 0);
    CHECK(tests > 0);
    std::size_t hair_hits = 0, ref_differs = 0, one_side = 0, far = 0;
    for (std::size_t i = 0; i < ref.rays.size(); ++i) {
        // The aligned side runs rtcsim's capsule test: ref's hits (up to a
        // box edge each side rounds its own way, and the mesh's triangle
        // test, Embree's own in float).
        ref_differs += ref.hits[i].hit() != a[i].hit() ||
                       (a[i].hit() && std::abs(ref.hits[i].t - a[i].t) > 1e-5f * a[i].t);
        hair_hits += a[i].hit() && a[i].prim != HairHit::kMeshPrim;
        if (a[i].hit() != o[i].hit()) {
            ++one_side;
        } else if (a[i].hit()) {
            far += std::abs(a[i].t - o[i].t) > 1e-3f * a[i].t;
        }
    }
    CAPTURE(ref.rays.size());
    CAPTURE(one_side);
    CAPTURE(far);
    CHECK(hair_hits > ref.rays.size() / 10);  // the check is not vacuous: many rays meet the hair
    CHECK(ref_differs <= 2);
    // Embree's float curve test against rtcsim's double one: grazing rays only.
    CHECK(static_cast<double>(one_side + far) <= 0.005 * static_cast<double>(ref.rays.size()));
}

}  // namespace RTCSIM_TEST_FILE
