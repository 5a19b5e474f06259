// One box on SIMD lanes (core/box_lanes.h) against the scalar functions it
// stands in for: intersect_lone_box() against intersect_box() (the root over
// one leaf in traverse(), the reference method's one-instance TLAS), and
// safe_inverse_fast() against safe_inverse() (every ray's inverse
// direction). Equal bit for bit, for ordinary rays and for zeros of either
// sign, infinities, NaNs, rays on a slab and empty boxes.
#include "core/box_lanes.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <limits>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

namespace {

std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

// Counts the cases compared and fails on the first that differs in any bit.
struct Compare {
    int compared = 0, hits = 0;
    void operator()(const Aabb& box, const Vec3& origin, const Vec3& direction, float tmin, float tmax) {
        const Vec3 want_inv = safe_inverse(direction), got_inv = safe_inverse_fast(direction);
        for (int k = 0; k < 3; ++k)
            if (bits(got_inv[k]) != bits(want_inv[k])) CHECK(bits(got_inv[k]) == bits(want_inv[k]));
        const float want = intersect_box(box, origin, want_inv, tmin, tmax);
        const float got = intersect_lone_box(box, origin, want_inv, tmin, tmax);
        ++compared;
        if (want != kInfinity) ++hits;
        if (bits(got) != bits(want)) {
            INFO("origin " << origin.x << " " << origin.y << " " << origin.z << ", direction " << direction.x
                           << " " << direction.y << " " << direction.z << ", tmin " << tmin << ", tmax " << tmax);
            CHECK(bits(got) == bits(want));
        }
    }
};

}  // namespace

TEST_CASE("box lanes: the lone-box test and the inverse direction equal the scalar ones bit for bit") {
    Rng rng(23);
    Compare cmp;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 lo = rng.point(-1.0f, 1.0f);
        const Aabb box{lo, lo + rng.point(0.0f, 0.5f)};
        // Rays aimed near the box so that hits, misses and grazes all occur.
        const Vec3 target = lo + rng.point(-0.1f, 0.6f);
        const Vec3 origin = target - rng.direction() * rng.uniform(0.1f, 5.0f);
        const float tmin = (i % 7 == 0) ? rng.uniform(0.0f, 1.0f) : 0.0f;
        const float tmax = (i % 5 == 0) ? kInfinity : rng.uniform(0.2f, 3.0f);
        cmp(box, origin, target - origin, tmin, tmax);
    }
    CHECK(cmp.hits > 2000);
    CHECK(cmp.hits < cmp.compared - 2000);
}

TEST_CASE("box lanes: zeros of either sign, infinities, NaN and empty boxes agree with the scalar path") {
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-38f, -1e-38f, 3e38f, inf, -inf, nan};
    const Aabb boxes[] = {{Vec3(0.0f), Vec3(1.0f)}, {Vec3(-0.0f), Vec3(0.0f)}, Aabb{}};  // unit, point, empty
    Compare cmp;
    for (const Aabb& box : boxes)
        for (float dx : special)
            for (float dy : special)
                for (float dz : {0.0f, -0.0f, 1.0f, -1.0f})
                    for (const Vec3 origin : {Vec3(0.5f, 0.0f, -1.0f), Vec3(-0.0f, 0.5f, 0.5f)})  // on a slab
                        for (float tmax : {inf, 1.5f, nan}) cmp(box, origin, Vec3(dx, dy, dz), 0.0f, tmax);
    CHECK(cmp.compared == 3 * 11 * 11 * 4 * 2 * 3);
    CHECK(cmp.hits > 0);
}

}  // namespace RTCSIM_TEST_FILE
