// Bounds of every kind: sampled surface points lie inside the AABB and every
// OBB variant; OBBs stay invertible for degenerate primitives; Tight <= Paper.
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "core/sinks.h"
#include "reference/accuracy.h"

#include <doctest/doctest.h>

#include <chrono>

using namespace rtc;

namespace {

// Inside up to float rounding: the OBB test in unit-box coordinates is exact
// to ~1e-6 here (the OBB is already padded by 2^-10 of each half-extent).
template <class Prim>
void check_contains(const Prim& prim, const Vec3& p, long& outside) {
    bool ok = bounds(prim).contains(p);
    for (const ObbVariant v : {ObbVariant::Paper, ObbVariant::Tight})
        ok = ok && oriented_bounds(prim, v).contains(p, 0.0f);
    if (!ok) ++outside;
}

}  // namespace

TEST_CASE("intersect bounds: sampled surface points inside AABB and OBBs") {
    std::mt19937 rng(42);
    long outside = 0, samples = 0;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c(test::uniform(rng, -100, 100), test::uniform(rng, -100, 100),
                     test::uniform(rng, -100, 100));
        const float len = test::log_uniform(rng, 1e-3f, 10.0f);
        const Vec3 w = test::random_unit(rng);
        const float r = len / test::log_uniform(rng, 1.0f, 1e4f);
        const Vec3 p0 = c - 0.5f * len * w, p1 = c + 0.5f * len * w;
        const float r1 = r * test::uniform(rng, 0.2f, 3.0f);
        const Capsule cap{p0, p1, r};
        const Cylinder cyl{p0, p1, r};
        const Link link{p0, r, p1, r1};
        PhantomCurve curve;
        curve.cp = {p0, p0 + len / 3 * w + 0.3f * len * test::random_unit(rng),
                    p0 + 2 * len / 3 * w + 0.3f * len * test::random_unit(rng), p1};
        curve.radius = {r, r1, r, r1};
        const std::array<DVec3, 4> q{DVec3(curve.cp[0]), DVec3(curve.cp[1]), DVec3(curve.cp[2]),
                                     DVec3(curve.cp[3])};
        const std::array<double, 4> rr{r, r1, r, r1};
        for (int k = 0; k < 200; ++k, ++samples) {
            const double u = test::uniform(rng, 0, 1);
            const DVec3 dir(test::random_unit(rng));
            const DVec3 axis = DVec3(p0) + u * (DVec3(p1) - DVec3(p0));
            check_contains(cap, Vec3(axis + double(r) * dir), outside);
            check_contains(link, Vec3(DVec3(u < 0.5 ? p0 : p1) + double(u < 0.5 ? r : r1) * dir),
                           outside);
            // Cylinder: side and cap rims.
            const DVec3 perp = glm::normalize(glm::cross(dir, DVec3(w)));
            check_contains(cyl, Vec3(axis + double(r) * perp), outside);
            check_contains(cyl, Vec3(DVec3(k % 2 ? p0 : p1) + double(r) * perp), outside);
            check_contains(curve, Vec3(bezier(q, u) + bezier(rr, u) * dir), outside);
        }
        // Tight never worse than Paper for curves; equal for straight kinds.
        CHECK(oriented_bounds(curve, ObbVariant::Tight).surface_area() <=
              oriented_bounds(curve, ObbVariant::Paper).surface_area() * 1.0001f);
        CHECK(oriented_bounds(cap, ObbVariant::Tight).surface_area() ==
              oriented_bounds(cap, ObbVariant::Paper).surface_area());
    }
    MESSAGE("bounds: " << outside << " of " << samples * 5 << " surface samples outside");
    CHECK(outside == 0);
}

TEST_CASE("intersect bounds: degenerate primitives give invertible, finite OBBs") {
    const Vec3 z(0.0f), p(5, -3, 2);
    PhantomCurve point{{p, p, p, p}, {0, 0, 0, 0}};
    const Obb boxes[] = {oriented_bounds(Capsule{z, z, 0}), oriented_bounds(Capsule{p, p, 1}),
                         oriented_bounds(Cylinder{p, p, 0}), oriented_bounds(Link{p, 0, p, 0}),
                         oriented_bounds(Link{z, 1, Vec3(1, 0, 0), 0}),
                         oriented_bounds(point), oriented_bounds(point, ObbVariant::Tight)};
    for (const Obb& b : boxes) {
        CHECK(b.world_from_unit.inverse().has_value());
        for (int i = 0; i < 3; ++i) CHECK(glm::length(b.half_axis(i)) > 0.0f);
        CHECK(b.bounds().finite());
    }
    CHECK(oriented_bounds(point).contains(p, 0.0f));
    CHECK(bounds(Capsule{p, p, 1}).contains(p + Vec3(1, 0, 0)));
}

TEST_CASE("intersect timing: ns per call (reported, loosely bounded)") {
    std::mt19937 rng(3);
    std::vector<Capsule> caps;
    std::vector<Ray> rays;
    for (int i = 0; i < 1024; ++i) {
        const Vec3 c(test::uniform(rng, -1, 1), test::uniform(rng, -1, 1), test::uniform(rng, -1, 1));
        const Vec3 w = test::random_unit(rng);
        caps.push_back({c - 0.2f * w, c + 0.2f * w, 0.01f});
        rays.push_back(test::aim(rng, c + 0.02f * test::random_unit(rng), 3.0f));
    }
    NullSink sink;
    int hits = 0;
    const auto t0 = std::chrono::steady_clock::now();
    constexpr int kRounds = 200;
    for (int k = 0; k < kRounds; ++k) {
        const std::size_t shift = std::size_t(k) % rays.size();  // mixes hits and misses
        for (std::size_t i = 0; i < caps.size(); ++i)
            hits += intersect(caps[i], rays[(i + shift) & 1023], sink).has_value();
    }
    const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0)
                          .count() / (kRounds * double(caps.size()));
    MESSAGE("capsule intersect: " << ns << " ns per call (" << hits << " hits)");
    CHECK(ns < 1000.0);  // loose: only catches a pathological slowdown
}
