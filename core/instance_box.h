// The instance step on SIMD lanes: a world ray transformed into an instance's
// object space and tested against one object-space box, with x, y, z in the
// lanes of one SSE register instead of three scalar paths.
//
// This is the whole per-instance work of the masquerade (one instance per
// primitive over a one-leaf unit-box BLAS), which a ray repeats for thousands
// of instances in dense scenes. It computes exactly what the scalar path
// computes, `intersect_box(box, a.point(o), safe_inverse(a.vector(d)), ...)`:
// the same float operations in the same order per lane (glm's mat3 * vec3 is
// (c0 * x + c1 * y) + c2 * z, then + translation; no FMA contraction on the
// default SSE2 target), the same zero mapping of safe_inverse and min/max with
// the same operand order. tests/core/test_core_instance_box.cpp checks it
// bit for bit against the scalar path, zeros of either sign, infinities and
// NaNs included.
#pragma once

#include "core/affine.h"
#include "core/aabb.h"
#include "core/ray.h"

#include <cstring>

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

// A world ray held in lanes for many instance steps: each component broadcast.
struct LaneRay {
    __m128 ox, oy, oz, dx, dy, dz;
    float tmin;
    explicit LaneRay(const Ray& r)
        : ox(_mm_set1_ps(r.origin.x)), oy(_mm_set1_ps(r.origin.y)), oz(_mm_set1_ps(r.origin.z)),
          dx(_mm_set1_ps(r.direction.x)), dy(_mm_set1_ps(r.direction.y)), dz(_mm_set1_ps(r.direction.z)),
          tmin(r.tmin) {}
};

// Loads three floats into lanes 0-2 (lane 3 is zero) without reading past
// them. x and y go through memcpy: a Vec3 is only 4-byte aligned, and
// _mm_load_sd dereferences a double (misaligned: UB, and UBSan says so).
[[gnu::always_inline]] inline __m128 load3(const Vec3& v) {
    double xy;
    std::memcpy(&xy, &v.x, sizeof xy);
    return _mm_movelh_ps(_mm_castpd_ps(_mm_set_sd(xy)), _mm_load_ss(&v.z));
}

// The ray's origin and direction in object space, in lanes 0-2: exactly
// a.point(origin) and a.vector(direction).
struct ObjectRayLanes {
    __m128 origin, direction;
};
[[nodiscard, gnu::always_inline]] inline ObjectRayLanes transform(const Affine& a, const LaneRay& r) {
    const __m128 c0 = load3(a.linear[0]), c1 = load3(a.linear[1]), c2 = load3(a.linear[2]);
    const __m128 o = _mm_add_ps(
        _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, r.ox), _mm_mul_ps(c1, r.oy)), _mm_mul_ps(c2, r.oz)),
        load3(a.translation));
    const __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(c0, r.dx), _mm_mul_ps(c1, r.dy)), _mm_mul_ps(c2, r.dz));
    return {o, d};
}

// Stores lanes 0-2 into a Vec3 (only 4-byte aligned: x and y through memcpy).
[[gnu::always_inline]] inline void store3(__m128 x, Vec3& v) {
    const double xy = _mm_cvtsd_f64(_mm_castps_pd(x));
    std::memcpy(&v.x, &xy, sizeof xy);
    v.z = _mm_cvtss_f32(_mm_movehl_ps(x, x));
}

// The object-space ray, exactly a.ray(ray) with tmax = `tmax`, on the lanes:
// the scalar transform (two calls) cost about 60 instructions. (Where two
// NaNs meet in a sum, the result's sign follows an operand order the
// compiler may swap in either path: NaNs agree only as NaNs.)
[[nodiscard, gnu::always_inline]] inline Ray object_ray(const Affine& a, const LaneRay& r, float tmax) {
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
[[nodiscard, gnu::always_inline]] inline float intersect_instance_box(const Affine& a, const Aabb& box,
                                                                     const LaneRay& r, float tmax,
                                                                     ObjectRayParts& object) {
    const auto [o, d] = transform(a, r);
    // safe_inverse: 1 / d, and +-1e30 (the sign of the zero) where d == 0.
    const __m128 zero = _mm_cmpeq_ps(d, _mm_setzero_ps());
    const __m128 sign = _mm_and_ps(d, _mm_set1_ps(-0.0f));
    const __m128 big = _mm_or_ps(sign, _mm_set1_ps(1e30f));
    const __m128 inv = _mm_or_ps(_mm_and_ps(zero, big), _mm_andnot_ps(zero, _mm_div_ps(_mm_set1_ps(1.0f), d)));
    const __m128 t0 = _mm_mul_ps(_mm_sub_ps(load3(box.lo), o), inv);
    const __m128 t1 = _mm_mul_ps(_mm_sub_ps(load3(box.hi), o), inv);
    // std::min(a, b) is _mm_min_ps(b, a) and std::max(a, b) is _mm_max_ps(b, a).
    const __m128 lo = _mm_min_ps(t1, t0), hi = _mm_max_ps(t1, t0);  // per axis: min(t0, t1), max(t0, t1)
    const __m128 lo_y = _mm_shuffle_ps(lo, lo, _MM_SHUFFLE(1, 1, 1, 1));
    const __m128 lo_z = _mm_movehl_ps(lo, lo), hi_y = _mm_shuffle_ps(hi, hi, _MM_SHUFFLE(1, 1, 1, 1));
    const __m128 hi_z = _mm_movehl_ps(hi, hi);
    // tnear = max(max(lo.x, lo.y), max(lo.z, tmin)); tfar = min(min(hi.x, hi.y), min(hi.z, tmax)).
    const __m128 tnear = _mm_max_ss(_mm_max_ss(_mm_set_ss(r.tmin), lo_z), _mm_max_ss(lo_y, lo));
    const __m128 tfar = _mm_min_ss(_mm_min_ss(_mm_set_ss(tmax), hi_z), _mm_min_ss(hi_y, hi));
    const float near = _mm_cvtss_f32(tnear);
    if (!(near <= _mm_cvtss_f32(tfar) * kSlabPad)) return kInfinity;
    store3(o, object.origin);
    store3(d, object.direction);
    return near;
}

#else

struct LaneRay {
    Ray ray;
    explicit LaneRay(const Ray& r) : ray(r) {}
};

[[nodiscard]] inline Ray object_ray(const Affine& a, const LaneRay& r, float tmax) {
    Ray out = a.ray(r.ray);
    out.tmax = tmax;
    return out;
}

[[nodiscard]] inline float intersect_instance_box(const Affine& a, const Aabb& box, const LaneRay& r,
                                                  float tmax, ObjectRayParts& object) {
    const Ray t = a.ray(r.ray);
    const float near = intersect_box(box, t.origin, safe_inverse(t.direction), r.ray.tmin, tmax);
    if (near != kInfinity) object.origin = t.origin, object.direction = t.direction;
    return near;
}

#endif

}  // namespace rtc
