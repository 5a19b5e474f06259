// Strands -> primitives: per-segment kinds, B-spline -> Bezier conversion of
// phantom curves (end handling, subdivision), strand indices, bad factors.
#include "core/input_error.h"
#include "scenes/convert.h"
#include "scenes/generators/random.h"

#include <doctest/doctest.h>

#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {
Strands random_strand(SceneRng& rng, std::uint32_t n) {
    Strands s;
    for (std::uint32_t i = 0; i < n; ++i) {
        s.points.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        s.radii.push_back(static_cast<float>(rng.uniform(0.01, 0.1)));
    }
    s.offsets.push_back(n);
    return s;
}
float dist(const Vec3& a, const Vec3& b) { return glm::length(a - b); }
}  // namespace

TEST_CASE("scene convert: per-segment kinds keep points and radii") {
    Strands s;
    s.points = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(5, 0, 0), Vec3(6, 0, 0)};
    s.radii = {0.1f, 0.3f, 0.5f, 1.0f, 2.0f};
    s.offsets = {0, 3, 5};
    const auto cyl = std::get<std::vector<Cylinder>>(to_primitives(s, PrimitiveKind::Cylinder));
    REQUIRE(cyl.size() == 3);
    CHECK(cyl[1].p0 == Vec3(0, 1, 0));
    CHECK(cyl[1].radius == doctest::Approx(0.4f));  // mean of 0.3 and 0.5
    const auto cap = std::get<std::vector<Capsule>>(to_primitives(s, PrimitiveKind::Capsule));
    CHECK(cap[2].p1 == Vec3(6, 0, 0));
    CHECK(cap[2].radius == doctest::Approx(1.5f));
    const auto link = std::get<std::vector<Link>>(to_primitives(s, PrimitiveKind::Link));
    CHECK(link[0].r0 == 0.1f);
    CHECK(link[0].r1 == 0.3f);
    CHECK(primitive_strands(s, PrimitiveKind::Link) == std::vector<std::uint32_t>{0, 0, 1});
    CHECK(primitive_strands(s, PrimitiveKind::Phantom, 2) ==
          std::vector<std::uint32_t>{0, 0, 0, 0, 1, 1});
}

TEST_CASE("scene convert: Bezier form reproduces the B-spline segment") {
    SceneRng rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        std::array<Vec3, 4> p;
        for (auto& q : p) q = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const PhantomCurve c = bspline::to_bezier(p, {0.1f, 0.2f, 0.3f, 0.4f});
        for (float t = 0.0f; t <= 1.0f; t += 0.125f)
            CHECK(dist(bspline::bezier_point(c, t), bspline::eval(p, t)) < 1e-5f);
        // Linear radii stay linear: r(t) = 0.2 + 0.1 t on this segment.
        CHECK(bspline::bezier_radius(c, 0.5f) == doctest::Approx(0.25f));
    }
}

TEST_CASE("scene convert: phantom curves cover the strand from first to last point") {
    SceneRng rng(11);
    for (std::uint32_t n : {2u, 3u, 4u, 9u}) {
        const Strands s = random_strand(rng, n);
        const auto curves = std::get<std::vector<PhantomCurve>>(to_primitives(s, PrimitiveKind::Phantom));
        REQUIRE(curves.size() == n - 1);
        CHECK(dist(curves.front().cp[0], s.points.front()) < 1e-6f);
        CHECK(dist(curves.back().cp[3], s.points.back()) < 1e-6f);
        CHECK(curves.front().radius[0] == doctest::Approx(s.radii.front()));
        CHECK(curves.back().radius[3] == doctest::Approx(s.radii.back()));
        for (std::size_t i = 0; i + 1 < curves.size(); ++i)  // C0 continuity
            CHECK(dist(curves[i].cp[3], curves[i + 1].cp[0]) < 1e-5f);
        if (n == 2) {  // a two-point strand is the straight segment itself
            const Vec3 mid = 0.5f * (s.points[0] + s.points[1]);
            CHECK(dist(bspline::bezier_point(curves[0], 0.5f), mid) < 1e-6f);
        }
    }
}

TEST_CASE("scene convert: subdivided curves reproduce the parent curve") {
    SceneRng rng(3);
    const Strands s = random_strand(rng, 6);
    const auto parent = std::get<std::vector<PhantomCurve>>(to_primitives(s, PrimitiveKind::Phantom, 1));
    for (int k : {2, 4, 8}) {
        CAPTURE(k);
        const auto sub = std::get<std::vector<PhantomCurve>>(to_primitives(s, PrimitiveKind::Phantom, k));
        REQUIRE(sub.size() == parent.size() * static_cast<std::size_t>(k));
        for (std::size_t i = 0; i < sub.size(); ++i) {
            const PhantomCurve& whole = parent[i / k];
            const float t0 = static_cast<float>(i % k) / static_cast<float>(k);
            for (float u = 0.0f; u <= 1.0f; u += 0.25f) {
                const float t = t0 + u / static_cast<float>(k);
                CHECK(dist(bspline::bezier_point(sub[i], u), bspline::bezier_point(whole, t)) < 1e-5f);
                CHECK(bspline::bezier_radius(sub[i], u) ==
                      doctest::Approx(bspline::bezier_radius(whole, t)).epsilon(1e-4));
            }
        }
    }
}

TEST_CASE("scene convert: bad subdivision factors are rejected") {
    SceneRng rng(1);
    const Strands s = random_strand(rng, 3);
    CHECK_THROWS_AS((void)to_primitives(s, PrimitiveKind::Phantom, 3), InputError);
    CHECK_THROWS_AS((void)to_primitives(s, PrimitiveKind::Phantom, 16), InputError);
    CHECK_THROWS_AS((void)to_primitives(s, PrimitiveKind::Phantom, 0), InputError);
    CHECK_THROWS_WITH_AS((void)to_primitives(s, PrimitiveKind::Capsule, 2),
                         doctest::Contains("only to phantom"), InputError);
    CHECK(primitive_count(to_primitives(s, PrimitiveKind::Phantom, 8)) == 16);
}

}  // namespace RTCSIM_TEST_FILE
