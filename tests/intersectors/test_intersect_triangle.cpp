// Watertight triangle test: hand table, shared edges, t independent of tmax.
#include "intersectors/triangle.h"
#include "core/sinks.h"

#include <doctest/doctest.h>

#include <random>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("intersect triangle: hand-computed table") {
    const Triangle tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
    CountingSink sink;
    const auto h = intersect(tri, Ray{{0.5f, 0.5f, -3}, 0, {0, 0, 2}, kInfinity}, sink);
    REQUIRE(h);
    CHECK(h->t == doctest::Approx(1.5f));
    CHECK(std::abs(h->normal.z) == doctest::Approx(1.0f));
    CHECK(h->u == doctest::Approx(0.25f));  // barycentric weight of v1
    CHECK(sink.ray[Event::TriangleTest] == 1);
    // From behind, miss outside, parallel, behind the origin, tmin/tmax filter.
    CHECK(intersect(tri, Ray{{0.5f, 0.5f, 3}, 0, {0, 0, -1}, kInfinity}, sink));
    CHECK_FALSE(intersect(tri, Ray{{1.5f, 1.5f, -3}, 0, {0, 0, 1}, kInfinity}, sink));
    CHECK_FALSE(intersect(tri, Ray{{0.5f, 0.5f, 0}, 0, {1, 0, 0}, kInfinity}, sink));
    CHECK_FALSE(intersect(tri, Ray{{0.5f, 0.5f, -3}, 0, {0, 0, -1}, kInfinity}, sink));
    CHECK_FALSE(intersect(tri, Ray{{0.5f, 0.5f, -3}, 0, {0, 0, 1}, 2.9f}, sink));
    CHECK_FALSE(intersect(tri, Ray{{0.5f, 0.5f, -3}, 3.1f, {0, 0, 1}, kInfinity}, sink));
    CHECK(sink.ray[Event::TriangleTest] == 7);
    // Degenerate and NaN input.
    CHECK_FALSE(intersect(Triangle{{0, 0, 0}, {1, 1, 0}, {2, 2, 0}},
                          Ray{{1, 1, -1}, 0, {0, 0, 1}, kInfinity}, sink));
    CHECK_FALSE(is_finite(Triangle{{0, 0, std::nanf("")}, {1, 0, 0}, {0, 1, 0}}));
    CHECK(is_finite(tri));
    CHECK(bounds(tri).lo == Vec3(0.0f));
    CHECK(bounds(tri).hi == Vec3(2, 2, 0));
}

TEST_CASE("intersect triangle: watertight along a shared edge, t independent of tmax") {
    // Two triangles sharing the diagonal of a skewed quad; rays aimed exactly
    // at points of the shared edge must hit at least one of them.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    NullSink sink;
    int hits = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 a(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        const Vec3 b = a + Vec3(u(rng), u(rng), u(rng)), d = a + Vec3(u(rng), u(rng), u(rng));
        const Triangle t0{a, b, c}, t1{a, c, d};
        const float s = 0.5f * (u(rng) + 1.0f);
        const Vec3 on_edge = a + s * (c - a);
        Ray ray{Vec3(u(rng), u(rng), u(rng)) * 4.0f, 0, Vec3(0), kInfinity};
        ray.direction = on_edge - ray.origin;
        const auto h0 = intersect(t0, ray, sink), h1 = intersect(t1, ray, sink);
        // Seen from the origin, b and d on opposite sides of the edge's plane
        // through the origin: the pair covers the edge, so a gap would show up
        // as "neither" (when on the same side, the edge is a silhouette).
        const DVec3 o(ray.origin), m = glm::cross(DVec3(a) - o, DVec3(c) - o);
        if (glm::dot(m, DVec3(b) - o) * glm::dot(m, DVec3(d) - o) < 0.0) CHECK((h0 || h1));
        for (const auto& [tri, h] : {std::pair{t0, h0}, std::pair{t1, h1}}) {
            if (!h) continue;
            ++hits;
            Ray r2 = ray;
            r2.tmax = h->t;
            const auto again = intersect(tri, r2, sink);
            REQUIRE(again);
            CHECK(again->t == h->t);
        }
    }
    CHECK(hits > 10000);
}

}  // namespace RTCSIM_TEST_FILE
