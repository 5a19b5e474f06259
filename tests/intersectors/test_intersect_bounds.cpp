// Bounds of every kind: sampled surface points lie inside the AABB and every
// OBB variant, near the origin and far from it; every ray an intersector hits
// passes the float AABB and instance OBB tests; OBBs stay invertible for
// degenerate primitives; Tight <= Paper.
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "core/instance_box.h"
#include "core/two_level.h"
#include "core/sinks.h"
#include "reference/accuracy.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// Exactly inside (in double, the point not rounded to float): the AABB, and
// each OBB as the hardware stores it, its float inverse about its float
// centre (CentredAffine): |L (p - c)| <= 1 per axis.
[[nodiscard]] bool obb_contains(const Obb& box, const DVec3& p) {
    const auto unit_from_world = centred_inverse(box.world_from_unit);
    if (!unit_from_world) return false;
    const DVec3 q = glm::dmat3(unit_from_world->linear) * (p - DVec3(unit_from_world->origin));
    return std::abs(q.x) <= 1.0 && std::abs(q.y) <= 1.0 && std::abs(q.z) <= 1.0;
}

template <class Prim>
void check_contains(const Prim& prim, const DVec3& p, long& outside) {
    const Aabb b = bounds(prim);
    bool ok = glm::all(glm::lessThanEqual(DVec3(b.lo), p)) && glm::all(glm::lessThanEqual(p, DVec3(b.hi)));
    for (const ObbVariant v : {ObbVariant::Paper, ObbVariant::Tight}) ok = ok && obb_contains(oriented_bounds(prim, v), p);
    if (!ok) ++outside;
}

}  // namespace

TEST_CASE("intersect bounds: sampled surface points inside AABB and OBBs, near and far from the origin") {
  // Far: 1e3 and 1e5 from the origin, where the thinnest of these primitives
  // (radius down to 1e-7) are far below a float ulp of their position.
  for (const float far : {0.0f, 1e3f, 1e5f}) {
    CAPTURE(far);
    std::mt19937 rng(42);
    long outside = 0, samples = 0;
    for (int i = 0; i < 300; ++i) {
        const Vec3 c(far + test::uniform(rng, -100, 100), test::uniform(rng, -100, 100) - far,
                     test::uniform(rng, -100, 100) + 0.5f * far);
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
            check_contains(cap, axis + double(r) * dir, outside);
            check_contains(link, DVec3(u < 0.5 ? p0 : p1) + double(u < 0.5 ? r : r1) * dir, outside);
            // Cylinder: side and cap rims, around the exact axis.
            const DVec3 exact_w = glm::normalize(DVec3(p1) - DVec3(p0));
            const DVec3 perp = glm::normalize(glm::cross(dir, exact_w));
            if (p0 != p1) {  // else no cylinder: p0 == p1 once len is below an ulp of the position
                check_contains(cyl, axis + double(r) * perp, outside);
                check_contains(cyl, DVec3(k % 2 ? p0 : p1) + double(r) * perp, outside);
            }
            check_contains(curve, bezier(q, u) + bezier(rr, u) * dir, outside);
        }
        // Tight never worse than Paper for curves (it picks its frame by the
        // float fit; 1e5 away the exact extents about the rounded centre can
        // reverse a close call); equal for straight kinds.
        if (far < 1e5f)
            CHECK(oriented_bounds(curve, ObbVariant::Tight).surface_area() <=
                  oriented_bounds(curve, ObbVariant::Paper).surface_area() * 1.0001f);
        CHECK(oriented_bounds(cap, ObbVariant::Tight).surface_area() ==
              oriented_bounds(cap, ObbVariant::Paper).surface_area());
    }
    MESSAGE("bounds at " << far << ": " << outside << " of " << samples * 5 << " surface samples outside");
    CHECK(outside == 0);
  }
}

namespace {

// Counts the rays that hit `prim` (its own intersector, in double) but that
// the float AABB slab test (ref's) or the instance's float transform and
// unit-box test (obb's, core/instance_box.h) would cull before the hit.
template <class Prim>
void check_rays(const Prim& prim, const DVec3& surface_point, std::mt19937& rng, long& hits, long& culled) {
    const Obb obb = oriented_bounds(prim);
    const Instance inst = make_instance(0, 0, obb.world_from_unit);
    const Aabb box = bounds(prim);
    NullSink sink;
    for (int k = 0; k < 8; ++k) {
        // Aimed at the surface point (grazing often) from 1e-3 to 1 away.
        const DVec3 dir(test::random_unit(rng));
        const double dist = test::log_uniform(rng, 1e-3f, 1.0f);
        Ray ray;
        ray.origin = Vec3(surface_point - dist * dir);
        ray.direction = Vec3(dir * double(test::uniform(rng, 0.5f, 2.0f)));
        const auto h = intersect(prim, ray, sink);
        if (!h) continue;
        ++hits;
        ObjectRayParts parts;
        // A BVH node is entered when the slab test answers (tmax = the hit's
        // t, the least it can be when this hit is the closest); an instance
        // also needs its entry at or before tmax (core/two_level.h).
        const bool aabb = intersect_box(box, ray.origin, safe_inverse(ray.direction), ray.tmin, h->t) < kInfinity;
        const bool oriented = intersect_instance_box(inst.object_from_world, kUnitBox, LaneRay(ray), h->t, parts) <= h->t;
        culled += !(aabb && oriented);
    }
}

}  // namespace

TEST_CASE("intersect bounds: a ray that hits passes the float AABB and OBB tests, near and far from the origin") {
    // Radius 1e-3 to 0.03: at 1e5 the thinnest are an eighth of a float ulp.
    for (const float far : {0.0f, 1e3f, 1e5f}) {
        CAPTURE(far);
        std::mt19937 rng(7);
        long hits = 0, culled = 0;
        for (int i = 0; i < 400; ++i) {
            const float x = test::uniform(rng, -1, 1), y = test::uniform(rng, -1, 1), z = test::uniform(rng, -1, 1);
            const Vec3 c = Vec3(far, -far, 0.5f * far) + Vec3(x, y, z);
            const Vec3 w = test::random_unit(rng);
            const float len = test::uniform(rng, 0.0f, 0.5f), r = test::log_uniform(rng, 1e-3f, 0.03f);
            const Vec3 p0 = c - 0.5f * len * w, p1 = c + 0.5f * len * w;
            const double u = test::uniform(rng, 0, 1);
            const DVec3 dir(test::random_unit(rng));
            const DVec3 axis = DVec3(p0) + u * (DVec3(p1) - DVec3(p0));
            check_rays(Capsule{p0, p1, r}, axis + double(r) * dir, rng, hits, culled);
            const float r1 = r * test::uniform(rng, 0.2f, 3.0f);
            check_rays(Link{p0, r, p1, r1}, DVec3(u < 0.5 ? p0 : p1) + double(u < 0.5 ? r : r1) * dir, rng, hits,
                       culled);
            PhantomCurve curve;
            curve.cp = {p0, p0 + len / 3 * w + 0.3f * len * test::random_unit(rng),
                        p0 + 2 * len / 3 * w + 0.3f * len * test::random_unit(rng), p1};
            curve.radius = {r, r1, r, r1};
            const std::array<DVec3, 4> q{DVec3(curve.cp[0]), DVec3(curve.cp[1]), DVec3(curve.cp[2]),
                                         DVec3(curve.cp[3])};
            const std::array<double, 4> rr{r, r1, r, r1};
            check_rays(curve, bezier(q, u) + bezier(rr, u) * dir, rng, hits, culled);
        }
        MESSAGE("rays at " << far << ": " << culled << " of " << hits << " hits culled by a box");
        CHECK(hits > 2000);
        CHECK(culled == 0);
    }
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

}  // namespace RTCSIM_TEST_FILE
