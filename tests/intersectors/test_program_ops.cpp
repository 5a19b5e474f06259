// Operation counts of the intersection programs (core/ops.h): each call
// counts the tally of the path it took, so a cheap reject is cheap, a hit
// costs more than a miss that solved, and phantom iterations add up.
#include "core/ops.h"
#include "core/sinks.h"
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

Ops ops_of(const RayCounts& c) {
    const auto n = [&](Event e) { return static_cast<std::uint16_t>(c[e]); };
    return {n(Event::OpFma), n(Event::OpDiv), n(Event::OpSqrt), n(Event::OpBranch), n(Event::OpLoad)};
}

template <class Prim, class... Options>
Ops call_ops(const Prim& prim, const Ray& ray, bool expect_hit, const Options&... options) {
    CountingSink sink;
    const auto hit = intersect(prim, ray, sink, options...);
    CHECK(hit.has_value() == expect_hit);
    return ops_of(sink.ray);
}

Ray ray_from(const Vec3& origin, const Vec3& direction) {
    Ray r;
    r.origin = origin;
    r.direction = direction;
    return r;
}

// Every class at least as large: a path that does more work.
bool at_most(const Ops& a, const Ops& b) {
    return a.fma <= b.fma && a.div <= b.div && a.sqrt <= b.sqrt && a.branch <= b.branch && a.load <= b.load;
}

}  // namespace

TEST_CASE("capsule program: each path counts its own tally, rejects the cheapest") {
    const Capsule cap{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0.01f};
    const Vec3 down{0.0f, 0.0f, -1.0f};
    // Far from the capsule's bounding sphere: the first reject.
    const Ops sphere = call_ops(cap, ray_from({5.0f, 0.0f, 1.0f}, down), false);
    // Inside the bounding sphere but 0.1 off the axis line: the axis reject.
    const Ops axis = call_ops(cap, ray_from({0.5f, 0.1f, 1.0f}, down), false);
    // Through the middle: a hit.
    const Ops hit = call_ops(cap, ray_from({0.5f, 0.0f, 1.0f}, down), true);
    // Towards the capsule but beyond tmax: solved, then missed.
    Ray short_ray = ray_from({0.5f, 0.0f, 1.0f}, down);
    short_ray.tmax = 0.5f;
    const Ops solved = call_ops(cap, short_ray, false);
    CHECK(sphere == detail::kCapsuleSphereReject);
    CHECK(axis == detail::kCapsuleAxisReject);
    CHECK(solved == detail::kCapsuleSolved);
    CHECK(hit == detail::kCapsuleHit);
    CHECK(at_most(sphere, axis));
    CHECK(at_most(axis, solved));
    CHECK(at_most(solved, hit));
    CHECK(sphere.div == 0);  // the cheap rejects have no division or root (capsule.h)
    CHECK(sphere.sqrt == 0);
    CHECK(hit.load == 2);    // 28 B of capsule
    // A degenerate capsule costs only its entry.
    CHECK(call_ops(Capsule{{0, 0, 0}, {1, 0, 0}, 0.0f}, ray_from({0.5f, 0.0f, 1.0f}, down), false) ==
          detail::kCapsuleEntry);
}

TEST_CASE("cylinder and link programs: reject < solved < hit") {
    const Vec3 down{0.0f, 0.0f, -1.0f};
    const Cylinder cyl{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0.01f};
    CHECK(call_ops(cyl, ray_from({5.0f, 0.0f, 1.0f}, down), false) == kCylinderSphereReject);
    CHECK(call_ops(cyl, ray_from({0.5f, 0.1f, 1.0f}, down), false) == kCylinderSolved);
    CHECK(call_ops(cyl, ray_from({0.5f, 0.0f, 1.0f}, down), true) == kCylinderHit);
    CHECK(at_most(kCylinderSphereReject, kCylinderSolved));
    CHECK(at_most(kCylinderSolved, kCylinderHit));

    const Link link{{0.0f, 0.0f, 0.0f}, 0.02f, {1.0f, 0.0f, 0.0f}, 0.01f};
    CHECK(call_ops(link, ray_from({5.0f, 0.0f, 1.0f}, down), false) == detail::kLinkSphereReject);
    CHECK(call_ops(link, ray_from({0.5f, 0.1f, 1.0f}, down), false) == detail::kLinkSolved);
    CHECK(call_ops(link, ray_from({0.5f, 0.0f, 1.0f}, down), true) == detail::kLinkHit);
    CHECK(at_most(detail::kLinkSphereReject, detail::kLinkSolved));
    CHECK(at_most(detail::kLinkSolved, detail::kLinkHit));
}

TEST_CASE("phantom programs: operations add up per iteration and bracket test") {
    const PhantomCurve curve{{Vec3{0.0f, 0.0f, 0.0f}, Vec3{0.3f, 0.2f, 0.0f}, Vec3{0.6f, -0.2f, 0.0f},
                              Vec3{1.0f, 0.0f, 0.0f}},
                             {0.02f, 0.02f, 0.02f, 0.02f}};
    const Ray ray = ray_from({0.5f, 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f});
    SUBCASE("bracketed") {
        CountingSink sink;
        (void)intersect(curve, ray, sink, PhantomOptions{});
        const RayCounts& c = sink.ray;
        REQUIRE(c[Event::PhantomIteration] > 0);
        // Every iteration and bracket test is in the counts, on top of the
        // per-call parts, whatever the call's path.
        const std::uint32_t base = c[Event::OpFma] - detail::kPhantomIteration.fma * c[Event::PhantomIteration] -
                                   detail::kPhantomBracketTest.fma * c[Event::PhantomBracketTest];
        const std::uint32_t fixed = detail::kPhantomEntry.fma + detail::kPhantomSetup.fma +
                                    detail::kPhantomEarlyOut.fma + detail::kPhantomBracketSetup.fma;
        CHECK((base == fixed || base == fixed + detail::kPhantomHit.fma));
        CHECK(c[Event::OpLoad] == 4);
    }
    SUBCASE("paper") {
        PhantomOptions paper;
        paper.program = PhantomProgram::Paper;
        CountingSink sink;
        (void)intersect(curve, ray, sink, paper);
        const RayCounts& c = sink.ray;
        REQUIRE(c[Event::PhantomPaperIteration] > 0);
        const std::uint32_t fixed = detail::kPhantomEntry.fma + detail::kReshetovCylinder.fma +
                                    detail::kReshetovSetup.fma +
                                    detail::kReshetovSecondEnd.fma * c[Event::PhantomSecondEnd];
        const std::uint32_t base = c[Event::OpFma] - detail::kReshetovIteration.fma * c[Event::PhantomPaperIteration];
        CHECK((base == fixed || base == fixed + detail::kReshetovHit.fma));
    }
    SUBCASE("a rejected call counts no iteration") {
        CountingSink sink;
        (void)intersect(curve, ray_from({0.5f, 5.0f, 1.0f}, {0.0f, 0.0f, -1.0f}), sink, PhantomOptions{});
        CHECK(sink.ray[Event::PhantomEarlyReject] == 1);
        CHECK(ops_of(sink.ray) == detail::kPhantomEntry + detail::kPhantomSetup + detail::kPhantomEarlyOut);
    }
}

TEST_CASE("a sink that does not count pays nothing for operations") {
    NullSink null;
    const Capsule cap{{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, 0.01f};
    CHECK(intersect(cap, ray_from({0.5f, 0.0f, 1.0f}, {0.0f, 0.0f, -1.0f}), null).has_value());
}

}  // namespace RTCSIM_TEST_FILE
