// Capsule and cylinder intersectors: hand tables, degenerate input, tmax
// independence and accuracy against the extended-precision reference.
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "core/sinks.h"
#include "reference/accuracy.h"

#include <doctest/doctest.h>

#include <bit>
#include <cstdint>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

struct Case {
    Vec3 o, d;
    float tmin;
    std::optional<float> t;  // expected
};

template <class Prim>
void check_table(const Prim& prim, const std::vector<Case>& cases, Event ev) {
    for (const Case& c : cases) {
        CountingSink sink;
        const Ray ray{c.o, c.tmin, c.d, kInfinity};
        const auto hit = intersect(prim, ray, sink);
        CAPTURE(c.o);
        CAPTURE(c.d);
        CHECK(sink.ray[ev] == 1);
        REQUIRE(hit.has_value() == c.t.has_value());
        if (hit) {
            CHECK(hit->t == doctest::Approx(*c.t).epsilon(1e-6));
            CHECK(glm::length(hit->normal) == doctest::Approx(1.0f).epsilon(1e-6));
            CHECK(hit->u >= 0.0f);
            CHECK(hit->u <= 1.0f);
        }
    }
}

}  // namespace

TEST_CASE("intersect capsule: hand-computed table") {
    // Axis along x from 0 to 4, radius 1.
    const Capsule cap{{0, 0, 0}, {4, 0, 0}, 1.0f};
    check_table(cap,
                {
                    {{2, 0, -5}, {0, 0, 1}, 0, 4.0f},         // side, head on
                    {{2, 0, -5}, {0, 0, 2}, 0, 2.0f},         // unnormalized direction
                    {{-5, 0, 0}, {1, 0, 0}, 0, 4.0f},         // parallel to axis: sphere cap p0
                    {{9, 0, 0}, {-1, 0, 0}, 0, 4.0f},         // cap p1
                    {{-5, 0.6f, 0}, {1, 0, 0}, 0, 5.0f - 0.8f},  // cap off axis: x = -0.8
                    {{2, 0, 0}, {0, 0, 1}, 0, 1.0f},          // inside: exit
                    {{2, 0, -5}, {0, 0, 1}, 4.5f, 6.0f},      // tmin past entry: exit
                    {{2, 0, -5}, {0, 0, 1}, 6.5f, {}},        // tmin past exit
                    {{2, 1.01f, -5}, {0, 0, 1}, 0, {}},       // just outside the silhouette
                    {{2, 0.6f, -5}, {0, 0, 1}, 0, 4.2f},      // z = -0.8
                    {{2, 0, -5}, {0, 0, -1}, 0, {}},          // pointing away
                    {{-5, 1.01f, 0}, {1, 0, 0}, 0, {}},       // parallel, outside
                    {{5.5f, 0, -5}, {0, 0, 1}, 0, {}},        // past the end cap
                    {{4.6f, 0, -5}, {0, 0, 1}, 0, 5.0f - 0.8f},  // end sphere
                },
                Event::IsCapsule);
}

TEST_CASE("intersect cylinder: hand-computed table") {
    const Cylinder cyl{{0, 0, 0}, {4, 0, 0}, 1.0f};
    check_table(cyl,
                {
                    {{2, 0, -5}, {0, 0, 1}, 0, 4.0f},
                    {{-5, 0, 0}, {1, 0, 0}, 0, 5.0f},         // flat cap at x = 0
                    {{9, 0.5f, 0}, {-1, 0, 0}, 0, 5.0f},      // flat cap at x = 4
                    {{-5, 0.6f, 0}, {1, 0, 0}, 0, 5.0f},      // caps are flat
                    {{2, 0, 0}, {0, 0, 1}, 0, 1.0f},          // inside
                    {{-0.5f, 0, -5}, {0, 0, 1}, 0, {}},       // beyond the flat cap
                    {{2, 1.01f, -5}, {0, 0, 1}, 0, {}},
                    {{-5, 1.01f, 0}, {1, 0, 0}, 0, {}},       // parallel outside
                    {{-1, 0, -1}, {1, 0, 1}, 0, 1.0f},        // enters at the cap rim x=0,z=0? no: z=-1+1=0 at t=1, x=0
                },
                Event::IsCylinder);
    // Cap normal is the axis, side normal is radial.
    NullSink sink;
    auto h = intersect(cyl, Ray{{-5, 0.3f, 0}, 0, {1, 0, 0}, kInfinity}, sink);
    REQUIRE(h);
    CHECK(h->normal.x == doctest::Approx(-1.0f));
    CHECK(h->u == 0.0f);
    h = intersect(cyl, Ray{{2, 0, -5}, 0, {0, 0, 1}, kInfinity}, sink);
    REQUIRE(h);
    CHECK(h->normal.z == doctest::Approx(-1.0f));
    CHECK(h->u == doctest::Approx(0.5f));
}

TEST_CASE("intersect capsule/cylinder: degenerate input") {
    NullSink sink;
    const Ray ray{{0.3f, 0, -5}, 0, {0, 0, 1}, kInfinity};
    // Zero length: the capsule is a sphere.
    const Capsule sphere{{0, 0, 0}, {0, 0, 0}, 1.0f};
    const auto h = intersect(sphere, ray, sink);
    REQUIRE(h);
    CHECK(h->t == doctest::Approx(5.0f - std::sqrt(1.0f - 0.09f)));
    CHECK(glm::length(h->normal) == doctest::Approx(1.0f));
    // Zero radius: never hit, even dead centre.
    CHECK_FALSE(intersect(Capsule{{0, 0, -1}, {0, 0, 1}, 0.0f}, ray, sink));
    CHECK_FALSE(intersect(Capsule{{0, 0, 0}, {0, 0, 0}, 0.0f},
                          Ray{{0, 0, -5}, 0, {0, 0, 1}, kInfinity}, sink));
    CHECK_FALSE(intersect(Cylinder{{0, 0, 0}, {1, 0, 0}, 0.0f}, ray, sink));
    // Zero-length cylinder: a disc without thickness, never hit.
    CHECK_FALSE(intersect(Cylinder{{0, 0, 0}, {0, 0, 0}, 1.0f}, ray, sink));
    // NaN input: flagged, and intersect returns without crashing.
    const float nan = std::nanf("");
    const Capsule bad{{nan, 0, 0}, {1, 0, 0}, 1.0f};
    CHECK_FALSE(is_finite(bad));
    CHECK(is_finite(sphere));
    CHECK_FALSE(is_finite(Cylinder{{0, 0, 0}, {1, 0, 0}, kInfinity}));
    CHECK_FALSE(intersect(bad, ray, sink));
    CHECK_FALSE(intersect(Capsule{{0, 0, 0}, {1, 0, 0}, nan}, ray, sink));
    CHECK_FALSE(intersect(sphere, Ray{{0, 0, -5}, 0, {nan, 0, 1}, kInfinity}, sink));
    CHECK_FALSE(intersect(sphere, Ray{{0, 0, -5}, 0, {0, 0, 0}, kInfinity}, sink));
}

namespace {

struct RandomSegment {
    Vec3 p0, p1;
    float r;
};

RandomSegment random_segment(std::mt19937& rng, float max_ratio) {
    const Vec3 c(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1));
    const float len = test::uniform(rng, 0.5f, 2.0f);
    const Vec3 w = test::random_unit(rng);
    const float ratio = test::log_uniform(rng, 10.0f, max_ratio);
    return {c - 0.5f * len * w, c + 0.5f * len * w, len / ratio};
}

// Aim near the primitive: a point on the extended axis plus up to 2 r across.
Ray random_ray_at(std::mt19937& rng, const RandomSegment& s) {
    const float u = test::uniform(rng, -0.05f, 1.05f);
    const Vec3 target = s.p0 + u * (s.p1 - s.p0) + test::random_unit(rng) * (2.0f * s.r *
                                                    test::uniform(rng, 0.0f, 1.0f));
    return test::aim(rng, target, glm::length(s.p1 - s.p0) * test::uniform(rng, 0.5f, 4.0f));
}

}  // namespace

TEST_CASE("intersect capsule/cylinder: accuracy against the extended-precision reference") {
    std::mt19937 rng(20200817);
    test::AccuracyStats caps, cyls;
    NullSink sink;
    for (int i = 0; i < 4000; ++i) {
        const RandomSegment s = random_segment(rng, 1e4f);
        for (int k = 0; k < 25; ++k) {
            const Ray ray = random_ray_at(rng, s);
            const ref::Real r = s.r;
            {
                const auto hit = intersect(Capsule{s.p0, s.p1, s.r}, ray, sink);
                const auto t_ref = ref::nearest(ref::link(ray, s.p0, r, s.p1, r), 0);
                const bool in = ref::nearest(ref::link(ray, s.p0, r * (1 - 1e-3L), s.p1,
                                                       r * (1 - 1e-3L)), 0).has_value();
                const bool out = ref::nearest(ref::link(ray, s.p0, r * (1 + 1e-3L), s.p1,
                                                        r * (1 + 1e-3L)), 0).has_value();
                caps.add(hit ? std::optional<float>(hit->t) : std::nullopt, t_ref, in != out, ray,
                         s.r);
            }
            {
                const auto hit = intersect(Cylinder{s.p0, s.p1, s.r}, ray, sink);
                const auto t_ref = ref::nearest(ref::cylinder(ray, s.p0, s.p1, r), 0);
                // Grow/shrink: radius by 1e-3 r and the ends by 1e-3 r along the axis.
                const Vec3 e = (s.p1 - s.p0) / glm::length(s.p1 - s.p0) * (1e-3f * s.r);
                const bool in = ref::nearest(ref::cylinder(ray, s.p0 + e, s.p1 - e,
                                                           r * (1 - 1e-3L)), 0).has_value();
                const bool out = ref::nearest(ref::cylinder(ray, s.p0 - e, s.p1 + e,
                                                            r * (1 + 1e-3L)), 0).has_value();
                cyls.add(hit ? std::optional<float>(hit->t) : std::nullopt, t_ref, in != out, ray,
                         s.r);
            }
        }
    }
    MESSAGE(caps.summary("capsule"));
    MESSAGE(cyls.summary("cylinder"));
    for (const auto* st : {&caps, &cyls}) {
        CHECK(st->both_hit > st->rays / 5);  // the sample really exercises hits
        CHECK(st->agreement() >= 0.9999);
        CHECK(st->over_allowed == 0);
    }
}

TEST_CASE("intersect capsule/cylinder: t does not depend on tmax") {
    std::mt19937 rng(7);
    NullSink sink;
    int hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const RandomSegment s = random_segment(rng, 1e3f);
        Ray ray = random_ray_at(rng, s);
        const Capsule cap{s.p0, s.p1, s.r};
        const Cylinder cyl{s.p0, s.p1, s.r};
        for (int kind = 0; kind < 2; ++kind) {
            ray.tmax = kInfinity;
            const auto a = kind == 0 ? intersect(cap, ray, sink) : intersect(cyl, ray, sink);
            if (!a) continue;
            ++hits;
            ray.tmax = a->t;
            const auto b = kind == 0 ? intersect(cap, ray, sink) : intersect(cyl, ray, sink);
            REQUIRE(b);
            CHECK(b->t == a->t);
            ray.tmax = std::nextafter(a->t, 0.0f);
            CHECK_FALSE((kind == 0 ? intersect(cap, ray, sink) : intersect(cyl, ray, sink)));
        }
    }
    CHECK(hits > 500);
}

#if defined(__AVX2__)
namespace {

// Equal bit for bit, or both NaN (a NaN's payload may follow operand order).
bool same(double a, double b) {
    return (std::isnan(a) && std::isnan(b)) || std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same(const DVec3& a, const DVec3& b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

// Any float: mostly ordinary values, sometimes a random bit pattern (NaN,
// infinities, subnormals, huge), sometimes a signed zero.
float any_float(std::mt19937& rng) {
    switch (rng() % 8) {
    case 0: return std::bit_cast<float>(static_cast<std::uint32_t>(rng()));
    case 1: return (rng() & 1) ? 0.0f : -0.0f;
    default: return test::uniform(rng, -3.0f, 3.0f);
    }
}

}  // namespace

TEST_CASE("intersect capsule: the cheap rejects on AVX2 lanes are the scalar ones, bit for bit") {
    std::mt19937 rng(20261126);
    NullSink sink;
    int compared = 0, rejected = 0, hits = 0;
    const auto check = [&](const Capsule& cap, const Ray& ray) {
        const detail::CapsuleFrame s = detail::capsule_frame_scalar(cap, ray);
        const detail::CapsuleLanes l = detail::capsule_frame_lanes(cap, ray);
        CAPTURE(cap.p0);
        CAPTURE(cap.p1);
        CAPTURE(ray.origin);
        CAPTURE(ray.direction);
        REQUIRE(same(s.a, detail::to_dvec3(l.a)));
        REQUIRE(same(s.ba, detail::to_dvec3(l.ba)));
        REQUIRE(same(s.d, detail::to_dvec3(l.d)));
        REQUIRE(same(s.oc, detail::to_dvec3(l.oc)));
        REQUIRE(same(s.len2, l.len2));
        REQUIRE(same(s.dd, l.dd));
        REQUIRE(same(s.od, l.od));
        REQUIRE(same(s.oo, l.oo));
        const detail::CapsuleAxis sx = detail::capsule_axis(s), lx = detail::capsule_axis(l);
        REQUIRE(same(sx.nn, lx.nn));
        REQUIRE(same(sx.on, lx.on));
        // And intersect(), which takes the lanes, answers as the scalar
        // frame's rejects and hit do.
        const double r = cap.radius;
        std::optional<Hit> expected;
        if (r > 0.0 && !detail::capsule_rejects(s, r)) expected = detail::capsule_hit(ray, s, r);
        const auto got = intersect(cap, ray, sink);
        REQUIRE(got.has_value() == expected.has_value());
        if (got) {
            CHECK(std::bit_cast<std::uint32_t>(got->t) == std::bit_cast<std::uint32_t>(expected->t));
            CHECK(got->normal == expected->normal);
            ++hits;
        }
        rejected += r > 0.0 && detail::capsule_rejects(s, r);
        ++compared;
    };
    for (int i = 0; i < 20000; ++i) {
        const RandomSegment s = random_segment(rng, 1e4f);
        check({s.p0, s.p1, s.r}, random_ray_at(rng, s));
        const Capsule odd{{any_float(rng), any_float(rng), any_float(rng)},
                          {any_float(rng), any_float(rng), any_float(rng)},
                          std::abs(any_float(rng))};
        const Ray ray{{any_float(rng), any_float(rng), any_float(rng)}, 0.0f,
                      {any_float(rng), any_float(rng), any_float(rng)}, kInfinity};
        check(odd, ray);
        check({odd.p0, odd.p0, odd.radius}, ray);  // zero length
    }
    CHECK(compared == 60000);
    CHECK(hits > 2000);      // the sample reaches the hit test
    CHECK(rejected > 2000);  // and the rejects
}
#endif

}  // namespace RTCSIM_TEST_FILE
