// The instance step on SIMD lanes: a world ray transformed into an instance's
// object space and tested against one object-space box, with x, y, z in the
// lanes of one SSE register instead of three scalar paths.
//
// This is the whole per-instance work of the masquerade (one instance per
// primitive over a one-leaf unit-box BLAS), which a ray repeats for thousands
// of instances in dense scenes. It computes exactly what the scalar path
// computes, `intersect_box(box, a.point(o), safe_inverse(a.vector(d)), ...)`:
// the same float operations in the same order per lane (o - origin first,
// then glm's mat3 * vec3, (c0 * x + c1 * y) + c2 * z; no FMA contraction on the
// default SSE2 target), the same zero mapping of safe_inverse and min/max with
// the same operand order. tests/core/test_core_instance_box.cpp checks it
// bit for bit against the scalar path, zeros of either sign, infinities and
// NaNs included.
#pragma once

#include "core/affine.h"
#include "core/aabb.h"
#include "core/box_lanes.h"
#include "core/ray.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace rtc {

// An instance's object ray as the box test leaves it: origin and direction
// only, unwritten until an entry writes them (a Ray's member initializers
// cost four stores per instance tested, entered or not).
struct ObjectRayParts {
    Vec3 origin, direction;
};

#if defined(__SSE2__)

// A world ray held in lanes for many instance steps: the origin in lanes 0-2
// (each instance subtracts its own origin first), the direction's
// components broadcast.
struct LaneRay {
    __m128 o, dx, dy, dz;
    float tmin;
    explicit LaneRay(const Ray& r)
        : o(load3(r.origin)), dx(_mm_set1_ps(r.direction.x)), dy(_mm_set1_ps(r.direction.y)),
          dz(_mm_set1_ps(r.direction.z)), tmin(r.tmin) {}
};

// The ray's origin and direction in object space, in lanes 0-2: exactly
// a.point(origin) and a.vector(direction).
struct ObjectRayLanes {
    __m128 origin, direction;
};
[[nodiscard, gnu::always_inline]] inline ObjectRayLanes transform(const CentredAffine& a, const LaneRay& r) {
    const __m128 c0 = load3(a.linear[0]), c1 = load3(a.linear[1]), c2 = load3(a.linear[2]);
    const __m128 e = _mm_sub_ps(r.o, load3(a.origin));
    const __m128 ex = _mm_shuffle_ps(e, e, _MM_SHUFFLE(0, 0, 0, 0)), ey = _mm_shuffle_ps(e, e, _MM_SHUFFLE(1, 1, 1, 1)),
                 ez = _mm_shuffle_ps(e, e, _MM_SHUFFLE(2, 2, 2, 2));
    const __m128 o = _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, ex), _mm_mul_ps(c1, ey)), _mm_mul_ps(c2, ez));
    const __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, r.dx), _mm_mul_ps(c1, r.dy)), _mm_mul_ps(c2, r.dz));
    return {o, d};
}

// The object-space ray, exactly a.ray(ray) with tmax = `tmax`, on the lanes:
// the scalar transform (two calls) cost about 60 instructions. (Where two
// NaNs meet in a sum, the result's sign follows an operand order the
// compiler may swap in either path: NaNs agree only as NaNs.)
[[nodiscard, gnu::always_inline]] inline Ray object_ray(const CentredAffine& a, const LaneRay& r, float tmax) {
    const ObjectRayLanes t = transform(a, r);
    Ray out;
    store3(t.origin, out.origin);
    store3(t.direction, out.direction);
    out.tmin = r.tmin;
    out.tmax = tmax;
    return out;
}

// The entry distance of the transformed ray into `box`, or +inf: exactly
// intersect_box(box, a.point(origin), safe_inverse(a.vector(direction)), tmin, tmax).
// When the box is entered, `object` receives the transformed ray's origin and
// direction (exactly a.ray()'s): taking them from here instead of
// transforming again (the scalar a.ray(), two calls) saves about 60
// instructions per instance entered; on a miss `object` is left alone.
[[nodiscard, gnu::always_inline]] inline float intersect_instance_box(const CentredAffine& a, const Aabb& box,
                                                                     const LaneRay& r, float tmax,
                                                                     ObjectRayParts& object) {
    const auto [o, d] = transform(a, r);
    const float near = intersect_box_lanes(box, o, safe_inverse_lanes(d), r.tmin, tmax);
    if (near == kInfinity) return kInfinity;
    store3(o, object.origin);
    store3(d, object.direction);
    return near;
}

#else

struct LaneRay {
    Ray ray;
    explicit LaneRay(const Ray& r) : ray(r) {}
};

[[nodiscard]] inline Ray object_ray(const CentredAffine& a, const LaneRay& r, float tmax) {
    Ray out = a.ray(r.ray);
    out.tmax = tmax;
    return out;
}

[[nodiscard]] inline float intersect_instance_box(const CentredAffine& a, const Aabb& box, const LaneRay& r,
                                                  float tmax, ObjectRayParts& object) {
    const Ray t = a.ray(r.ray);
    const float near = intersect_box(box, t.origin, safe_inverse(t.direction), r.ray.tmin, tmax);
    if (near != kInfinity) object.origin = t.origin, object.direction = t.direction;
    return near;
}

#endif

}  // namespace rtc
