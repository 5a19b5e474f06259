// Results do not move with the scene's position (issue 38, item 4): the same
// primitives and rays translated 1e3 from the origin give the same event
// counts and AABB/OBB area ratio to 1 %, and 1e5 from the origin (where a
// radius of 0.01 is about an ulp) every method still returns ref's hits.
#include "methods_test_util.h"
#include "sim/run/area_stats.h"

#include <bit>
#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using namespace rtc::test;

namespace {

Geometry translated(const Geometry& g, const Vec3& offset) {
    Geometry out = g;
    std::visit(
        [&](auto& prims) {
            for (auto& p : prims) {
                if constexpr (std::is_same_v<std::decay_t<decltype(p)>, PhantomCurve>) {
                    for (Vec3& q : p.cp) q += offset;
                } else {
                    p.p0 += offset, p.p1 += offset;
                }
            }
        },
        out.prims);
    return out;
}

struct Traced {
    EventTotals events;
    std::vector<TraceHit> hits;
};

Traced trace_all(std::string_view method, const Geometry& g, const std::vector<Ray>& rays) {
    const auto m = build(method, g, options(4));
    Traced out;
    for (const Ray& ray : rays) {
        CountingSink sink;
        out.hits.push_back(trace_any(m, g, ray, sink, IsSchedule::Immediate));
        out.events.add(sink.ray);
    }
    return out;
}

std::vector<Ray> moved(std::vector<Ray> rays, const Vec3& offset) {
    for (Ray& r : rays) r.origin += offset;
    return rays;
}

// The scene: 200 primitives of radius >= 0.01 in [-1, 1]^3, a copy
// moved by `offset`, and rays through the unmoved one.
struct MovedScene {
    Geometry near, far;
    std::vector<Ray> rays;
};

MovedScene moved_scene(int seed, PrimitiveKind kind, const Vec3& offset, int ray_count) {
    Rng rng(seed);
    MovedScene s;
    s.near.kind = kind;
    s.near.prims = random_prims(rng, kind, 200, /*min_radius=*/0.01f);
    s.far = translated(s.near, offset);
    for (int i = 0; i < ray_count; ++i) s.rays.push_back(scene_ray(rng));
    return s;
}

}  // namespace

TEST_CASE("methods: event counts and the AABB/OBB area ratio stay within 1 % when the scene moves 1e3 from the origin") {
    const Vec3 offset(1000.0f, -1000.0f, 1000.0f);
    for (const PrimitiveKind kind : {PrimitiveKind::Capsule, PrimitiveKind::Phantom}) {
        CAPTURE(kind_name(kind));
        const MovedScene scene = moved_scene(38 + static_cast<int>(kind), kind, offset, 3000);
        const Geometry &g = scene.near, &far = scene.far;
        const std::vector<Ray>& rays = scene.rays;

        const double ratio = area_stats(g.prims, 1).ratio_paper(), ratio_far = area_stats(far.prims, 1).ratio_paper();
        CAPTURE(ratio);
        CAPTURE(ratio_far);
        CHECK(std::abs(ratio_far / ratio - 1.0) < 0.01);

        for (const std::string_view method : {"ref", "obb"}) {
            CAPTURE(method);
            const Traced near = trace_all(method, g, rays), moved_run = trace_all(method, far, moved(rays, offset));
            CHECK(near.events[Event::IsCall] > 1000);
            for (std::size_t e = 0; e < kEventCount; ++e) {
                const double a = static_cast<double>(near.events.n[e]), b = static_cast<double>(moved_run.events.n[e]);
                CAPTURE(kEventNames[e]);
                CAPTURE(a);
                CAPTURE(b);
                CHECK(std::abs(b - a) <= 0.01 * a);
            }
        }
    }
}

TEST_CASE("methods: 1e5 from the origin every method still returns ref's hit for every ray") {
    const Vec3 offset(1e5f, 1e5f, -1e5f);
    for (const PrimitiveKind kind : {PrimitiveKind::Capsule, PrimitiveKind::Phantom}) {
        CAPTURE(kind_name(kind));
        const MovedScene scene = moved_scene(380 + static_cast<int>(kind), kind, offset, 2000);
        const Geometry& far = scene.far;
        const std::vector<Ray> rays = moved(scene.rays, offset);
        const Traced ref = trace_all("ref", far, rays);
        int hits = 0;
        for (const TraceHit& h : ref.hits) hits += h.hit();
        CHECK(hits > 200);
        for (const std::string_view method : {"obb", "leaf-obb", "split"}) {
            CAPTURE(method);
            const Traced other = trace_all(method, far, rays);
            int mismatches = 0;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                const TraceHit &a = ref.hits[i], &b = other.hits[i];
                const bool same = a.geom == b.geom && a.prim == b.prim &&
                                  std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
                if (!same && mismatches == 0)
                    MESSAGE("ray " << i << ": ref prim " << a.prim << " t " << a.t << ", " << method << " prim " << b.prim
                                   << " t " << b.t);
                mismatches += !same;
            }
            CHECK(mismatches == 0);
        }
    }
}

}  // namespace RTCSIM_TEST_FILE
