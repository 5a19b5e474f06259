// The heart of the project: the reference and masquerade methods built from
// the same geometry return the same closest hit for every ray (same primitive,
// same t bit for bit), under both IS schedules, for every primitive kind, with
// and without a mesh; and their all-candidates IS call counts equal brute
// force over the primitives' AABBs and OBBs.
#include "sim/methods_test_util.h"
#include "sim/methods/common/cluster_groups.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

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
    CHECK(find_method("ref")->instance_count(g, options(4)) == 2);
    CHECK(find_method("obb")->instance_count(g, options(4)) == 101);
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

namespace {

MethodOptions cluster_options(int width, ClusterStrategy strategy, int size, ClusterFrame frame) {
    MethodOptions o = options(width);
    o.cluster = {strategy, size, frame};
    return o;
}

bool same_hit(const TraceHit& a, const TraceHit& b) {
    return a.geom == b.geom && a.prim == b.prim &&
           std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
}

}  // namespace

TEST_CASE("methods: cluster returns ref's closest hit for every kind, width, schedule and grouping") {
    // 601 primitives: strand runs of 4 and orientation groups of 3 end with a
    // cluster of one (the masquerade's unit box), groups of 16 with one of 9.
    const ClusterOptions groupings[] = {{ClusterStrategy::Strand, 4, ClusterFrame::Best},
                                        {ClusterStrategy::Orientation, 16, ClusterFrame::Best},
                                        {ClusterStrategy::Orientation, 3, ClusterFrame::Principal}};
    for (const PrimitiveKind kind : kKinds) {
        for (const bool mesh : {false, true}) {
            for (const int width : {2, 4, 8}) {
                Rng rng(3000 + static_cast<int>(kind) * 10 + mesh * 3 + width);
                const Geometry g = random_geometry(rng, kind, 601, mesh);
                const auto ref = build("ref", g, options(width));
                for (const ClusterOptions& grouping : groupings) {
                    const auto cl = build("cluster", g, cluster_options(width, grouping.strategy, grouping.size,
                                                                        grouping.frame));
                    CAPTURE(kind_name(kind));
                    CAPTURE(mesh);
                    CAPTURE(width);
                    CAPTURE(grouping.size);
                    int hits = 0, mismatches = 0;
                    for (int i = 0; i < 800; ++i) {
                        const Ray ray = scene_ray(rng);
                        for (const IsSchedule schedule : {IsSchedule::Immediate, IsSchedule::Deferred}) {
                            CountingSink sr, sc;
                            const TraceHit a = trace_any(ref, g, ray, sr, schedule);
                            const TraceHit b = trace_any(cl, g, ray, sc, schedule);
                            mismatches += !same_hit(a, b);
                            hits += a.hit() && schedule == IsSchedule::Immediate;
                            CHECK(sc.ray[Event::ContextSwitch] == sc.ray[Event::IsCall]);
                        }
                    }
                    CHECK(mismatches == 0);
                    CHECK(hits > 50);
                }
            }
        }
    }
}

TEST_CASE("methods: cluster of size 1 is the masquerade, event for event") {
    for (const PrimitiveKind kind : kKinds) {
        Rng rng(900 + static_cast<int>(kind));
        const Geometry g = random_geometry(rng, kind, 400, true);
        const auto obb = build("obb", g, options(4));
        for (const ClusterStrategy strategy : {ClusterStrategy::Strand, ClusterStrategy::Orientation}) {
            const auto cl = build("cluster", g, cluster_options(4, strategy, 1, ClusterFrame::Best));
            CAPTURE(kind_name(kind));
            const StructureCounts a = obb->structures(), b = cl->structures();
            CHECK(a.tlas_nodes == b.tlas_nodes);
            CHECK(a.blas_nodes == b.blas_nodes);
            CHECK(a.instances == b.instances);
            CHECK(a.custom_prims == b.custom_prims);
            CHECK(a.triangles == b.triangles);
            CHECK(a.blases == b.blases);
            int differing = 0;
            for (int i = 0; i < 500; ++i) {
                const Ray ray = scene_ray(rng);
                for (const IsSchedule schedule : {IsSchedule::Immediate, IsSchedule::Deferred}) {
                    CountingSink so, sc;
                    const TraceHit x = trace_any(obb, g, ray, so, schedule);
                    const TraceHit y = trace_any(cl, g, ray, sc, schedule);
                    differing += !same_hit(x, y) || so.ray.n != sc.ray.n;
                }
            }
            CHECK(differing == 0);
        }
    }
}

TEST_CASE("methods: cluster instance counts, structures and groups") {
    Rng rng(5);
    const Geometry g = random_geometry(rng, PrimitiveKind::Capsule, 100, true);
    const MethodEntry* m = find_method("cluster");
    REQUIRE(m != nullptr);
    for (const int size : {1, 7, 16, 100, 1000}) {
        for (const ClusterStrategy strategy : {ClusterStrategy::Strand, ClusterStrategy::Orientation}) {
            CAPTURE(size);
            const MethodOptions o = cluster_options(4, strategy, size, ClusterFrame::Best);
            const std::uint64_t clusters = (100 + size - 1) / size;
            CHECK(m->instance_count(g, o) == clusters + 1);
            const StructureCounts c = m->build(g, o)->structures();
            CHECK(c.instances == clusters + 1);
            CHECK(c.triangles == g.triangles.size());
            // Every primitive in a BLAS of its own cluster, or all share the unit box.
            CHECK(c.custom_prims == (size == 1 ? 1u : 100u));
            CHECK(c.blases == (size == 1 ? 2u : clusters + 1));
        }
    }
    // Strand runs never bridge two strands.
    Geometry strands = g;
    strands.strand_first = {0, 5, 7, 40};
    const MethodOptions runs = cluster_options(4, ClusterStrategy::Strand, 4, ClusterFrame::Best);
    CHECK(m->instance_count(strands, runs) == 2 + 1 + 9 + 15 + 1);
    CHECK(m->build(strands, runs)->structures().instances == 2 + 1 + 9 + 15 + 1);
    const Clusters split = group_strand(100, strands.strand_first, 4);
    CHECK(split.first == std::vector<std::uint32_t>{0, 4, 5, 7, 11, 15, 19, 23, 27, 31, 35, 39, 40, 44, 48, 52,
                                                    56, 60, 64, 68, 72, 76, 80, 84, 88, 92, 96, 100});
    // The orientation groups: a permutation, k each but the last, sorted inside.
    const auto& caps = std::get<std::vector<Capsule>>(g.prims);
    const Clusters groups = group_orientation(std::span<const Capsule>(caps), 7, 2);
    REQUIRE(groups.count() == 15);
    std::vector<std::uint32_t> seen = groups.members;
    std::sort(seen.begin(), seen.end());
    for (std::uint32_t i = 0; i < 100; ++i) CHECK(seen[i] == i);
    for (std::size_t c = 0; c < groups.count(); ++c) {
        CHECK(groups.first[c] == c * 7);
        CHECK(std::is_sorted(groups.members.begin() + groups.first[c], groups.members.begin() + groups.first[c + 1]));
    }
    CHECK(groups.members == group_orientation(std::span<const Capsule>(caps), 7, 1).members);
}

TEST_CASE("methods: cluster frames follow the primitives, orientation groups stay compact") {
    // Thin parallel segments tilted 45 degrees, scattered in a cube in random
    // order: AABBs are loose, boxes in a frame along the segments are tight.
    // The orientation strategy splits space too, so its clusters stay small
    // and aligned; strand runs of scattered primitives make clusters as large
    // as the cube, which every ray enters.
    Geometry g;
    g.kind = PrimitiveKind::Capsule;
    std::vector<Capsule> caps;
    Rng rng(11);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 p = rng.point(-1, 1);
        caps.push_back({p, p + Vec3(0.1f, 0.1f, 0.0f), 0.002f});
    }
    g.prims = caps;
    const auto ref = build("ref", g, options(4));
    const auto obb = build("obb", g, options(4));
    const auto strand = build("cluster", g, cluster_options(4, ClusterStrategy::Strand, 8, ClusterFrame::Best));
    const auto orient = build("cluster", g, cluster_options(4, ClusterStrategy::Orientation, 8, ClusterFrame::Best));
    std::uint64_t calls[4] = {}, transforms[4] = {};
    for (int i = 0; i < 1000; ++i) {
        const Ray ray = scene_ray(rng);
        CountingSink s[4];
        const TraceHit h = trace_any(ref, g, ray, s[0], IsSchedule::Immediate);
        CHECK(same_hit(h, trace_any(obb, g, ray, s[1], IsSchedule::Immediate)));
        CHECK(same_hit(h, trace_any(strand, g, ray, s[2], IsSchedule::Immediate)));
        CHECK(same_hit(h, trace_any(orient, g, ray, s[3], IsSchedule::Immediate)));
        for (int k = 0; k < 4; ++k) {
            calls[k] += s[k].ray[Event::IsCall];
            transforms[k] += s[k].ray[Event::InstanceTransform];
        }
    }
    CHECK(calls[1] < calls[0] / 2);
    CHECK(calls[3] < calls[0] / 2);
    CHECK(transforms[3] * 4 < transforms[2]);
}

}  // namespace RTCSIM_TEST_FILE
