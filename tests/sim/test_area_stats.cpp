// The figure-9 area sums (sim/run/area_stats.h): summed on several threads in
// fixed blocks, they equal themselves bit for bit at every thread count and
// agree with a plain serial sum (the slow reference) to rounding.
#include "intersectors/capsule.h"
#include "sim/run/area_stats.h"

#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("area_stats: the same sums on 1, 2 and 3 threads, and the serial sum's to rounding") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Capsule> caps(10'000);  // three blocks of 4096, the last partial
    for (Capsule& c : caps) {
        c.p0 = {u(rng), u(rng), u(rng)};
        c.p1 = c.p0 + Vec3{u(rng), u(rng), u(rng)} * 0.1f;
        c.radius = 0.01f * (1.5f + u(rng));
    }
    caps[17].p1 = caps[17].p0;  // a degenerate (zero-length) one among them
    const PrimitiveArray prims = caps;
    const AreaStats one = area_stats(prims, 1);
    for (unsigned threads : {2u, 3u}) {
        const AreaStats s = area_stats(prims, threads);
        CHECK(s.aabb == one.aabb);
        CHECK(s.obb_paper == one.obb_paper);
        CHECK(s.obb_tight == one.obb_tight);
    }
    double aabb = 0.0, paper = 0.0, tight = 0.0;
    for (const Capsule& c : caps) {
        aabb += bounds(c).surface_area();
        paper += oriented_bounds(c, ObbVariant::Paper).surface_area();
        tight += oriented_bounds(c, ObbVariant::Tight).surface_area();
    }
    CHECK(one.aabb == doctest::Approx(aabb).epsilon(1e-12));
    CHECK(one.obb_paper == doctest::Approx(paper).epsilon(1e-12));
    CHECK(one.obb_tight == doctest::Approx(tight).epsilon(1e-12));
    CHECK(one.aabb > 0.0);
    CHECK(area_stats(PrimitiveArray{std::vector<Capsule>{}}, 2).aabb == 0.0);
}

}  // namespace RTCSIM_TEST_FILE
