// The heart of the project: the reference and masquerade methods built from
// the same geometry return the same closest hit for every ray (same primitive,
// same t bit for bit), under both IS schedules, for every primitive kind, with
// and without a mesh; and their all-candidates IS call counts equal brute
// force over the primitives' AABBs and OBBs.
#include "sim/methods_test_util.h"

#include <doctest/doctest.h>

#include <bit>

using namespace rtc;
using namespace rtc::test;


TEST_CASE("methods: ref and obb return the same closest hit for every ray") {
    for (const PrimitiveKind kind : kKinds) {
        for (const bool mesh : {false, true}) {
            for (const int width : {2, 4, 8}) {
                Rng rng(1000 + static_cast<int>(kind) * 10 + mesh * 3 + width);
                const Geometry g = random_geometry(rng, kind, 600, mesh);
                const auto ref = build("ref", g, options(width));
                const auto obb = build("obb", g, options(width));
                CAPTURE(kind_name(kind));
                CAPTURE(mesh);
                CAPTURE(width);
                int hits = 0, mismatches = 0;
                std::uint64_t ref_calls = 0, obb_calls = 0;
                for (int i = 0; i < 1500; ++i) {
                    const Ray ray = scene_ray(rng);
                    for (const IsSchedule schedule : {IsSchedule::Immediate, IsSchedule::Deferred}) {
                        // The paper's phantom program too (the bracketed one is the default).
                        const auto program = kind == PrimitiveKind::Phantom && i % 2 == 1
                                                 ? PhantomProgram::Paper
                                                 : PhantomProgram::Bracketed;
                        CountingSink sr, so;
                        const TraceHit a = trace_any(ref, g, ray, sr, schedule, program);
                        const TraceHit b = trace_any(obb, g, ray, so, schedule, program);
                        const bool same = a.geom == b.geom && a.prim == b.prim &&
                                          std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
                        mismatches += !same;
                        hits += a.hit() && schedule == IsSchedule::Immediate;
                        if (schedule == IsSchedule::Immediate) {
                            ref_calls += sr.ray[Event::IsCall];
                            obb_calls += so.ray[Event::IsCall];
                        }
                        CHECK(sr.ray[Event::ContextSwitch] == sr.ray[Event::IsCall]);
                        CHECK(sr.ray[Event::Ray] == 1);
                    }
                }
                CHECK(mismatches == 0);
                CHECK(hits > 100);
                // The point of the method: far fewer intersection-program calls.
                CHECK(obb_calls < ref_calls);
            }
        }
    }
}

TEST_CASE("methods: deferred and immediate scheduling agree on hits, deferred calls more programs") {
    Rng rng(77);
    const Geometry g = random_geometry(rng, PrimitiveKind::Capsule, 2000, true);
    const auto ref = build("ref", g, options(4));
    std::uint64_t immediate_calls = 0, deferred_calls = 0;
    for (int i = 0; i < 1000; ++i) {
        const Ray ray = scene_ray(rng);
        CountingSink si, sd;
        const TraceHit a = trace_any(ref, g, ray, si, IsSchedule::Immediate);
        const TraceHit b = trace_any(ref, g, ray, sd, IsSchedule::Deferred);
        CHECK(a.prim == b.prim);
        CHECK(a.t == b.t);
        CHECK(sd.ray[Event::IsCall] >= si.ray[Event::IsCall]);
        immediate_calls += si.ray[Event::IsCall];
        deferred_calls += sd.ray[Event::IsCall];
    }
    CHECK(deferred_calls > immediate_calls);
}

TEST_CASE("methods: all-candidates IS calls equal the AABBs (ref) and OBBs (obb) a ray pierces") {
    for (const PrimitiveKind kind : kKinds) {
        Rng rng(500 + static_cast<int>(kind));
        const Geometry g = random_geometry(rng, kind, 800, false);
        const auto ref = build("ref", g, options(4));
        const auto obb = build("obb", g, options(4));
        CAPTURE(kind_name(kind));
        std::uint64_t total_ref = 0, total_obb = 0;
        for (int i = 0; i < 300; ++i) {
            const Ray ray = scene_ray(rng);
            CountingSink sr, so;
            (void)trace_any<TraversalMode::AllCandidates>(ref, g, ray, sr, IsSchedule::Immediate);
            (void)trace_any<TraversalMode::AllCandidates>(obb, g, ray, so, IsSchedule::Immediate);
            std::uint32_t aabbs = 0, obbs = 0;
            const Vec3 inv = safe_inverse(ray.direction);
            std::visit(
                [&](const auto& prims) {
                    for (std::size_t p = 0; p < prims.size(); ++p) {
                        aabbs += intersect_box(bounds(prims[p]), ray.origin, inv, ray.tmin, ray.tmax) < kInfinity;
                        // The same float operations the hardware model performs at
                        // the instance obb builds for primitive p.
                        const Instance inst = make_instance(
                            0, 0, oriented_bounds(prims[p], ObbVariant::Paper).world_from_unit);
                        const Ray o = inst.object_from_world.ray(ray);
                        obbs += intersect_box(kUnitBox, o.origin, safe_inverse(o.direction), o.tmin, o.tmax) < kInfinity;
                    }
                },
                g.prims);
            CHECK(sr.ray[Event::IsCall] == aabbs);
            CHECK(so.ray[Event::IsCall] == obbs);
            total_ref += aabbs;
            total_obb += obbs;
        }
        CHECK(total_obb < total_ref);
        CHECK(total_obb > 0);
    }
}

TEST_CASE("methods: instance counts and structure of each method") {
    Rng rng(3);
    const Geometry g = random_geometry(rng, PrimitiveKind::Capsule, 100, true);
    CHECK(find_method("ref")->instance_count(g) == 2);
    CHECK(find_method("obb")->instance_count(g) == 101);
    const auto obb = build("obb", g, options(4));
    const StructureCounts c = obb->structures();
    CHECK(c.instances == 101);
    CHECK(c.custom_prims == 1);  // the unit-box BLAS
    CHECK(c.triangles == g.triangles.size());
    // Instance i's transform is primitive i's OBB: the capsule's end-cap tips
    // (the points of the capsule farthest along its axis) lie inside it.
    const auto& caps = std::get<std::vector<Capsule>>(g.prims);
    for (std::size_t i = 0; i < caps.size(); ++i) {
        const Obb box{make_instance(0, 0, oriented_bounds(caps[i], ObbVariant::Paper).world_from_unit)
                          .world_from_object};
        const Vec3 axis = caps[i].p1 - caps[i].p0;
        const float len = glm::length(axis);
        const Vec3 dir = len > 0 ? axis / len : Vec3(0, 0, 1);
        CHECK(box.contains(caps[i].p0 - dir * caps[i].radius));
        CHECK(box.contains(caps[i].p1 + dir * caps[i].radius));
    }
}
