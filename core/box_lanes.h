// One ray against one box with x, y, z in the lanes of one SSE register:
// exactly intersect_box() (core/aabb.h), the same float operations in the
// same order per lane, min/max with the same operand order, so NaNs and
// signed zeros resolve alike. A scalar box test is three paths of the same
// work; here it is one, about half the instructions of the scalar call.
// Used where one box is tested alone: a root over one leaf (traverse()) and
// an instance's transformed ray (core/instance_box.h).
#pragma once

#include "core/aabb.h"
#include "core/ray.h"

#include <cstddef>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>

namespace rtc {

// Loads three floats into lanes 0-2 (lane 3 is zero) without reading past
// them. x and y go through memcpy: a Vec3 is only 4-byte aligned, and
// _mm_load_sd dereferences a double (misaligned: UB, and UBSan says so).
[[gnu::always_inline]] inline __m128 load3(const Vec3& v) {
    double xy;
    std::memcpy(&xy, &v.x, sizeof xy);
    return _mm_movelh_ps(_mm_castpd_ps(_mm_set_sd(xy)), _mm_load_ss(&v.z));
}

// Stores lanes 0-2 into a Vec3 (only 4-byte aligned: x and y through memcpy).
[[gnu::always_inline]] inline void store3(__m128 x, Vec3& v) {
    const double xy = _mm_cvtsd_f64(_mm_castps_pd(x));
    std::memcpy(&v.x, &xy, sizeof xy);
    v.z = _mm_cvtss_f32(_mm_movehl_ps(x, x));
}

// A Ray as two 16-byte vectors, (origin, tmin) and (direction, tmax): one
// load or store each, where load3/store3 take three instructions per Vec3.
// A 16-byte load is forwarded from the store buffer only when one store
// wrote all of it, so rays that are loaded this way (core/two_level.h's
// identity path) are written with store_ray.
static_assert(offsetof(Ray, origin) == 0 && offsetof(Ray, tmin) == 12 && offsetof(Ray, direction) == 16 &&
              offsetof(Ray, tmax) == 28 && sizeof(Ray) == 32);
struct RayLanes {
    __m128 origin_tmin, direction_tmax;
    explicit RayLanes(const Ray& ray)
        : origin_tmin(_mm_loadu_ps(reinterpret_cast<const float*>(&ray))),
          direction_tmax(_mm_loadu_ps(reinterpret_cast<const float*>(&ray) + 4)) {}
};

// The ray (origin_tmin, direction_tmax) written in two 16-byte stores.
[[gnu::always_inline]] inline void store_ray(__m128 origin_tmin, __m128 direction_tmax, Ray& ray) {
    std::memcpy(reinterpret_cast<char*>(&ray), &origin_tmin, 16);
    std::memcpy(reinterpret_cast<char*>(&ray) + 16, &direction_tmax, 16);
}

// safe_inverse() on lanes: 1 / d, and +-1e30 (the sign of the zero) where d == 0.
[[nodiscard, gnu::always_inline]] inline __m128 safe_inverse_lanes(__m128 d) {
    const __m128 zero = _mm_cmpeq_ps(d, _mm_setzero_ps());
    const __m128 sign = _mm_and_ps(d, _mm_set1_ps(-0.0f));
    const __m128 big = _mm_or_ps(sign, _mm_set1_ps(1e30f));
    return _mm_or_ps(_mm_and_ps(zero, big), _mm_andnot_ps(zero, _mm_div_ps(_mm_set1_ps(1.0f), d)));
}

// intersect_box(box, origin, inv_dir, tmin, tmax) with origin and inv_dir in
// lanes 0-2 (lane 3 is ignored).
[[nodiscard, gnu::always_inline]] inline float intersect_box_lanes(const Aabb& box, __m128 o, __m128 inv,
                                                                  float tmin, float tmax) {
    // Each corner in one 16-byte load (load3 is three instructions): lo from
    // the box's first 16 bytes (lane 3 is hi.x), hi from the 16 bytes ending
    // with it, rotated (lane 3 is lo.z). Both stay inside the box; lane 3 is
    // ignored below.
    static_assert(offsetof(Aabb, lo) == 0 && offsetof(Aabb, hi) == 12 && sizeof(Aabb) == 24);
    const char* const bytes = reinterpret_cast<const char*>(&box);
    const __m128 lo_hx = _mm_loadu_ps(reinterpret_cast<const float*>(bytes));
    const __m128 lz_hi = _mm_loadu_ps(reinterpret_cast<const float*>(bytes + 8));
    const __m128 hi_lz = _mm_shuffle_ps(lz_hi, lz_hi, _MM_SHUFFLE(0, 3, 2, 1));
    const __m128 t0 = _mm_mul_ps(_mm_sub_ps(lo_hx, o), inv);
    const __m128 t1 = _mm_mul_ps(_mm_sub_ps(hi_lz, o), inv);
    // std::min(a, b) is _mm_min_ps(b, a) and std::max(a, b) is _mm_max_ps(b, a).
    const __m128 lo = _mm_min_ps(t1, t0), hi = _mm_max_ps(t1, t0);  // per axis: min(t0, t1), max(t0, t1)
    const __m128 lo_y = _mm_shuffle_ps(lo, lo, _MM_SHUFFLE(1, 1, 1, 1));
    const __m128 lo_z = _mm_movehl_ps(lo, lo), hi_y = _mm_shuffle_ps(hi, hi, _MM_SHUFFLE(1, 1, 1, 1));
    const __m128 hi_z = _mm_movehl_ps(hi, hi);
    // tnear = max(max(lo.x, lo.y), max(lo.z, tmin)); tfar = min(min(hi.x, hi.y), min(hi.z, tmax)).
    const __m128 tnear = _mm_max_ss(_mm_max_ss(_mm_set_ss(tmin), lo_z), _mm_max_ss(lo_y, lo));
    const __m128 tfar = _mm_min_ss(_mm_min_ss(_mm_set_ss(tmax), hi_z), _mm_min_ss(hi_y, hi));
    const float near = _mm_cvtss_f32(tnear);
    return near <= _mm_cvtss_f32(tfar) * kSlabPad ? near : kInfinity;
}

}  // namespace rtc

#endif

namespace rtc {

// safe_inverse() (core/ray.h) on lanes where there are SSE lanes: one
// division and no branch per component.
[[nodiscard, gnu::always_inline]] inline Vec3 safe_inverse_fast(const Vec3& d) {
#if defined(__SSE2__)
    Vec3 out;
    store3(safe_inverse_lanes(load3(d)), out);
    return out;
#else
    return safe_inverse(d);
#endif
}

// intersect_box() for a box tested alone, on lanes where there are SSE lanes.
[[nodiscard, gnu::always_inline]] inline float intersect_lone_box(const Aabb& box, const Vec3& origin,
                                                                 const Vec3& inv_dir, float tmin,
                                                                 float tmax) {
#if defined(__SSE2__)
    return intersect_box_lanes(box, load3(origin), load3(inv_dir), tmin, tmax);
#else
    return intersect_box(box, origin, inv_dir, tmin, tmax);
#endif
}

}  // namespace rtc
