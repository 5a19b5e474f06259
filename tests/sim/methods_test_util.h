// Helpers shared by the method tests: seeded random primitives of every kind
// (long, thin, randomly oriented), an optional random mesh, build options per
// width and a ray mix (mostly from outside, some from inside the cloud).
#pragma once

#include "core_test_util.h"
#include "core/two_level.h"
#include "sim/methods/method.h"

#include <doctest/doctest.h>

#include <algorithm>

namespace rtc::test {

inline Vec3 thin_offset(Rng& rng, float lo, float hi) { return rng.direction() * rng.uniform(lo, hi); }

// Radii are drawn from [max(lo, min_radius), hi] (the default keeps every
// kind's own range, and so every caller's scene).
inline PrimitiveArray random_prims(Rng& rng, PrimitiveKind kind, int n, float min_radius = 0.0f) {
    const auto radius = [&](float lo, float hi) { return rng.uniform(std::max(lo, min_radius), hi); };
    switch (kind) {
        case PrimitiveKind::Cylinder: {
            std::vector<Cylinder> v;
            for (int i = 0; i < n; ++i) {
                const Vec3 p = rng.point(-1, 1);
                v.push_back({p, p + thin_offset(rng, 0.1f, 0.6f), radius(0.002f, 0.03f)});
            }
            return v;
        }
        case PrimitiveKind::Capsule: {
            std::vector<Capsule> v;
            for (int i = 0; i < n; ++i) {
                const Vec3 p = rng.point(-1, 1);
                v.push_back({p, p + thin_offset(rng, 0.0f, 0.6f), radius(0.002f, 0.03f)});
            }
            return v;
        }
        case PrimitiveKind::Link: {
            std::vector<Link> v;
            for (int i = 0; i < n; ++i) {
                const Vec3 p = rng.point(-1, 1);
                v.push_back({p, radius(0.002f, 0.03f), p + thin_offset(rng, 0.0f, 0.6f),
                             radius(0.002f, 0.03f)});
            }
            return v;
        }
        case PrimitiveKind::Phantom: {
            std::vector<PhantomCurve> v;
            for (int i = 0; i < n; ++i) {
                PhantomCurve c;
                // Hair-like: a mostly straight span with a gentle bend.
                c.cp[0] = rng.point(-1, 1);
                const Vec3 step = thin_offset(rng, 0.05f, 0.2f);
                for (int k = 1; k < 4; ++k) c.cp[k] = c.cp[k - 1] + step + thin_offset(rng, 0.0f, 0.02f);
                for (float& r : c.radius) r = radius(0.003f, 0.02f);
                v.push_back(c);
            }
            return v;
        }
    }
    return {};
}

inline Geometry random_geometry(Rng& rng, PrimitiveKind kind, int n, bool mesh) {
    Geometry g;
    g.kind = kind;
    g.prims = random_prims(rng, kind, n);
    if (mesh)
        for (const auto& t : rtc::test::random_triangles(rng, 150, 0.15f)) g.triangles.push_back({t.a, t.b, t.c});
    return g;
}

inline MethodOptions options(int width) {
    MethodOptions o;
    o.custom_blas.width = o.tlas.width = o.triangle_blas.width = width;
    o.triangle_blas.max_leaf_size = 4;
    return o;
}

inline std::unique_ptr<BuiltMethod> build(std::string_view name, const Geometry& g, const MethodOptions& o) {
    const MethodEntry* m = find_method(name);
    REQUIRE(m != nullptr);
    return m->build(g, o);
}

template <TraversalMode Mode = TraversalMode::Closest>
inline TraceHit trace_any(const std::unique_ptr<BuiltMethod>& m, const Geometry& g, const Ray& ray,
                   CountingSink& sink, IsSchedule schedule, PhantomProgram program = PhantomProgram::Bracketed) {
    TraceOptions o;
    o.schedule = schedule;
    o.phantom.program = program;
    return m->trace(g, ray, o, sink, Mode);
}

inline Ray scene_ray(Rng& rng) {
    // Mostly rays from outside; one in eight starts inside the primitive cloud.
    Ray r = rtc::test::random_ray(rng);
    if (rng.uniform() < 0.125f) r.origin = rng.point(-1, 1);
    return r;
}

inline constexpr PrimitiveKind kKinds[] = {PrimitiveKind::Cylinder, PrimitiveKind::Capsule, PrimitiveKind::Link,
                                    PrimitiveKind::Phantom};

}  // namespace rtc::test
