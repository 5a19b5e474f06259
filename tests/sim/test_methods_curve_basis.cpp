// Every method returns ref's closest hit (same primitive, same t bit for bit)
// on a small curly scene of the Bezier basis (scenes/scene.h: CurveBasis,
// Wald et al. 2020's curves: one cubic per three links of the control
// polygon the capsules and links lie on), for capsules, links and phantom
// curves at every pre-subdivision, both IS schedules and both phantom
// programs; and the geometry's per-strand runs follow the curves.
#include "scenes/generators/hair_gen.h"
#include "sim/methods/common/geometry.h"
#include "sim/methods_test_util.h"

#include <doctest/doctest.h>

#include <bit>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using namespace rtc::test;

namespace {

// 24 strands of 31 points (10 cubics, 30 links each) curling in a lock that
// fills scene_ray's [-1, 1] cube; 3 turns, so every cubic bends by 108 deg.
Scene bezier_lock(std::uint32_t points = 31) {
    HairDesc d;
    d.emitter = HairEmitter::Lock;
    d.lock_center = Vec3(0.0f, 0.7f, 0.0f);
    d.lock_radius = 0.3f;
    d.style = HairStyle::Curly;
    d.strands = 24;
    d.points_per_strand = points;
    d.length = 1.4f;
    d.radius = 0.012f;
    d.tip_radius = 0.006f;
    d.curl_radius = 0.15f;
    d.curl_turns = 3.0f;
    d.lean = 0.1f;
    d.basis = CurveBasis::Bezier;
    return make_hair(d);
}

bool same_hit(const TraceHit& a, const TraceHit& b) {
    return a.geom == b.geom && a.prim == b.prim &&
           std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
}

}  // namespace

TEST_CASE("methods: every method returns ref's closest hit on a Bezier-basis curly lock") {
    const Scene scene = bezier_lock();
    struct Prims {
        PrimitiveKind kind;
        int subdivision;
        std::size_t count;
    };
    const Prims cases[] = {{PrimitiveKind::Capsule, 1, 24 * 30}, {PrimitiveKind::Link, 1, 24 * 30},
                           {PrimitiveKind::Phantom, 1, 24 * 10}, {PrimitiveKind::Phantom, 2, 24 * 20},
                           {PrimitiveKind::Phantom, 4, 24 * 40}, {PrimitiveKind::Phantom, 8, 24 * 80}};
    // Not dots: its hits approximate the curves (test_methods_dots.cpp).
    const char* methods[] = {"obb", "leaf-obb", "split", "lss", "obb-nodes", "obb-quantized", "cluster"};
    for (const Prims& c : cases) {
        const Geometry g = make_geometry(scene, c.kind, c.subdivision);
        REQUIRE(g.primitive_count() == c.count);
        CHECK(g.strand_first.size() == 24);  // one run of primitives per strand
        for (const int width : {2, 4}) {
            const auto ref = build("ref", g, options(width));
            for (const char* name : methods) {
                if (!not_applicable_reason(*find_method(name), g).empty()) continue;  // lss: no curves
                CAPTURE(kind_name(c.kind));
                CAPTURE(c.subdivision);
                CAPTURE(width);
                CAPTURE(name);
                const auto m = build(name, g, options(width));
                Rng rng(77 + width);
                int hits = 0, mismatches = 0;
                for (int i = 0; i < 300; ++i) {
                    const Ray ray = scene_ray(rng);
                    for (const IsSchedule schedule : {IsSchedule::Immediate, IsSchedule::Deferred}) {
                        const auto program = i % 2 ? PhantomProgram::Paper : PhantomProgram::Bracketed;
                        CountingSink sr, sm;
                        const TraceHit a = trace_any(ref, g, ray, sr, schedule, program);
                        const TraceHit b = trace_any(m, g, ray, sm, schedule, program);
                        mismatches += !same_hit(a, b);
                        hits += a.hit() && schedule == IsSchedule::Immediate;
                    }
                }
                CHECK(mismatches == 0);
                CHECK(hits > 20);
            }
        }
    }
}

}  // namespace RTCSIM_TEST_FILE
