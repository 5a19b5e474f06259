// Link intersector: hand table, degenerate input, agreement with the capsule,
// tmax independence and accuracy against the extended-precision reference.
#include "intersectors/capsule.h"
#include "intersectors/link.h"
#include "core/sinks.h"
#include "reference/accuracy.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("intersect link: hand-computed table") {
    // Cone stump from (0,0,0) r 2 to (4,0,0) r 1: n_z = 1/4, n_rho = sqrt(15)/4,
    // radius g(z) = (2 - z/4) / n_rho between the tangent planes z = 0.5 and 4.25.
    const Link k{{0, 0, 0}, 2.0f, {4, 0, 0}, 1.0f};
    const double nr = std::sqrt(15.0) / 4.0;
    struct Case {
        Vec3 o, d;
        float tmin;
        std::optional<double> t;
    };
    const Case cases[] = {
        {{2, 0, -5}, {0, 0, 1}, 0, 5.0 - 1.5 / nr},              // cone, head on
        {{2, 0, -5}, {0, 0, 4}, 0, (5.0 - 1.5 / nr) / 4},        // unnormalized
        {{-5, 0, 0}, {1, 0, 0}, 0, 3.0},                         // along the axis: sphere 0
        {{9, 0, 0}, {-1, 0, 0}, 0, 4.0},                         // sphere 1
        {{-5, 1.9f, 0}, {1, 0, 0}, 0, 5.0 - std::sqrt(4.0 - double(1.9f) * 1.9f)},
        {{2, 0, 0}, {0, 0, 1}, 0, 1.5 / nr},                     // inside: exit
        {{2, 0, -5}, {0, 0, -1}, 0, {}},                         // pointing away
        {{4, 0, -5}, {0, 0, 1}, 0, 5.0 - 1.0 / nr},              // z = 4 < 4.25: cone, g = 1/nr
        {{4.9f, 0, -5}, {0, 0, 1}, 0, 5.0 - std::sqrt(1.0 - double(0.9f) * 0.9f)},  // sphere 1
        {{2, 1.6f, -5}, {0, 0, 1}, 0, {}},                       // outside the silhouette
        {{5.1f, 0, -5}, {0, 0, 1}, 0, {}},                       // past sphere 1
        {{2, 0, -5}, {0, 0, 1}, 5.5f, 5.0 + 1.5 / nr},           // tmin past entry
    };
    for (const Case& c : cases) {
        CountingSink sink;
        const auto h = intersect(k, Ray{c.o, c.tmin, c.d, kInfinity}, sink);
        CAPTURE(c.o);
        CHECK(sink.ray[Event::IsLink] == 1);
        REQUIRE(h.has_value() == c.t.has_value());
        if (!h) continue;
        CHECK(h->t == doctest::Approx(*c.t).epsilon(1e-6));
        CHECK(glm::length(h->normal) == doctest::Approx(1.0f).epsilon(1e-6));
    }
    // Cone normal: n_rho radial + n_z axial.
    NullSink sink;
    const auto h = intersect(k, Ray{{2, 0, -5}, 0, {0, 0, 1}, kInfinity}, sink);
    REQUIRE(h);
    CHECK(h->normal.x == doctest::Approx(0.25f));
    CHECK(h->normal.z == doctest::Approx(-nr));
    CHECK(h->u == doctest::Approx(0.5f));
}

TEST_CASE("intersect link: degenerate input") {
    NullSink sink;
    const Ray ray{{0.3f, 0, -5}, 0, {0, 0, 1}, kInfinity};
    const float expect = 5.0f - std::sqrt(1.0f - 0.09f);
    // Zero length, and one sphere inside the other: the bigger sphere.
    for (const Link& k : {Link{{0, 0, 0}, 1.0f, {0, 0, 0}, 0.5f},
                          Link{{0, 0, 0}, 0.5f, {0, 0, 0}, 1.0f},
                          Link{{0, 0, 0}, 1.0f, {0.2f, 0, 0}, 0.5f}}) {
        const auto h = intersect(k, ray, sink);
        REQUIRE(h);
        CHECK(h->t == doctest::Approx(expect));
    }
    // Zero radius: never hit; one zero radius: a rounded cone to a point.
    CHECK_FALSE(intersect(Link{{0, 0, -1}, 0.0f, {0, 0, 1}, 0.0f}, ray, sink));
    CHECK_FALSE(intersect(Link{{0.3f, 0, -1}, 0.0f, {0.3f, 0, 1}, 0.0f}, ray, sink));
    const auto tip = intersect(Link{{0, 0, 0}, 1.0f, {4, 0, 0}, 0.0f},
                               Ray{{9, 0, 0}, 0, {-1, 0, 0}, kInfinity}, sink);
    REQUIRE(tip);
    CHECK(tip->t == doctest::Approx(5.0f));
    const float nan = std::nanf("");
    CHECK_FALSE(is_finite(Link{{0, 0, 0}, nan, {1, 0, 0}, 1.0f}));
    CHECK_FALSE(is_finite(Link{{0, 0, 0}, 1.0f, {1, -kInfinity, 0}, 1.0f}));
    CHECK(is_finite(Link{{0, 0, 0}, 1.0f, {1, 0, 0}, 1.0f}));
    CHECK_FALSE(intersect(Link{{0, 0, 0}, nan, {1, 0, 0}, nan}, ray, sink));
    CHECK_FALSE(intersect(Link{{nan, 0, 0}, 1.0f, {1, 0, 0}, 1.0f}, ray, sink));
}

TEST_CASE("intersect link: accuracy, capsule agreement, t independent of tmax") {
    std::mt19937 rng(20190611);
    test::AccuracyStats stats;
    NullSink sink;
    long same_as_capsule = 0, capsule_pairs = 0, tmax_checked = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 c(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1),
                     test::uniform(rng, -1, 1));
        const float len = test::uniform(rng, 0.5f, 2.0f);
        const Vec3 w = test::random_unit(rng);
        const float r0 = len / test::log_uniform(rng, 10.0f, 1e4f);
        const float r1 = (i % 4 == 0) ? r0 : r0 * test::log_uniform(rng, 0.2f, 5.0f);
        const Link k{c - 0.5f * len * w, r0, c + 0.5f * len * w, r1};
        const float rmax = std::max(r0, r1);
        for (int j = 0; j < 25; ++j) {
            const Vec3 target = k.p0 + test::uniform(rng, -0.05f, 1.05f) * (k.p1 - k.p0) +
                                test::random_unit(rng) * (2.0f * rmax * test::uniform(rng, 0, 1));
            Ray ray = test::aim(rng, target, len * test::uniform(rng, 0.5f, 4.0f));
            const auto hit = intersect(k, ray, sink);
            const auto t_ref = ref::nearest(ref::link(ray, k.p0, r0, k.p1, r1), 0);
            const ref::Real lo = 1 - 1e-3L, hi = 1 + 1e-3L;
            const bool in = ref::nearest(ref::link(ray, k.p0, r0 * lo, k.p1, r1 * lo), 0).has_value();
            const bool out = ref::nearest(ref::link(ray, k.p0, r0 * hi, k.p1, r1 * hi), 0).has_value();
            // Tolerances are relative to the smaller radius (the thinner end).
            stats.add(hit ? std::optional<float>(hit->t) : std::nullopt, t_ref, in != out, ray,
                      std::min(r0, r1));
            if (r0 == r1) {
                const auto h2 = intersect(Capsule{k.p0, k.p1, r0}, ray, sink);
                ++capsule_pairs;
                if (hit.has_value() == h2.has_value() && (!hit || std::abs(hit->t - h2->t) <=
                                                                      1e-6f * hit->t))
                    ++same_as_capsule;
            }
            if (hit && j % 5 == 0) {
                ray.tmax = hit->t;
                const auto again = intersect(k, ray, sink);
                REQUIRE(again);
                CHECK(again->t == hit->t);
                ++tmax_checked;
            }
        }
    }
    MESSAGE(stats.summary("link"));
    MESSAGE("link vs capsule (r0 == r1): " << same_as_capsule << " / " << capsule_pairs
                                           << " agree");
    CHECK(stats.both_hit > stats.rays / 5);
    CHECK(stats.agreement() >= 0.9999);
    CHECK(stats.over_allowed == 0);
    CHECK(capsule_pairs - same_as_capsule <= capsule_pairs / 10000);
    CHECK(tmax_checked > 1000);
}

}  // namespace RTCSIM_TEST_FILE
