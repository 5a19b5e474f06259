// Capsule (Quilez, ShaderToy Xt3SzX): segment p0-p1 swept by a sphere of one
// radius; the primitive of Wald et al. 2020's hair and streamline scenes.
//
// Derivation. The capsule is convex and is the union of three convex pieces:
// the finite cylinder {|x - axis| <= r, 0 <= axial <= L} and the two end
// spheres. The ray meets each piece in an interval; since the capsule is convex
// the union of those intervals is one interval [s_in, s_out]: its ends are the
// smallest entry and largest exit. The nearest hit in [tmin, tmax] is s_in, or
// s_out when the ray starts inside. All of it is solved in double around the
// point of the ray closest to the capsule's centre (see span.h for why). The
// normal is (hit - nearest axis point) / r, whichever piece was hit.
//
// Bounds: AABB of the end spheres; OBB (Wald et al. 2020): axis p0-p1 extended
// by r at both ends, half-width r across; Tight == Paper.
#pragma once

#include "core/box_lanes.h"
#include "core/events.h"
#include "core/obb.h"
#include "core/ops.h"
#include "intersectors/frame.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"
#include "intersectors/span.h"

#include <cstddef>
#include <optional>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace rtc {

struct Capsule {
    Vec3 p0{0.0f};
    Vec3 p1{0.0f};
    float radius = 0.0f;
};

[[nodiscard]] inline bool is_finite(const Capsule& c) {
    return is_finite(c.p0) && is_finite(c.p1) && std::isfinite(c.radius);
}

[[nodiscard]] inline Aabb bounds(const Capsule& c) {
    const double r = std::max(c.radius, 0.0f);
    return outward_bounds(glm::min(DVec3(c.p0), DVec3(c.p1)) - r, glm::max(DVec3(c.p0), DVec3(c.p1)) + r);
}

[[nodiscard]] inline Obb oriented_bounds(const Capsule& c, ObbVariant = ObbVariant::Paper) {
    const float r = std::max(c.radius, 0.0f);
    return segment_obb(c.p0, c.p1, r, r);
}

namespace detail {

// The capsule's nearest hit once the cheap rejects have passed, from the ray
// around the capsule's centre (its reject test's parts: no recomputation).
// Always inside a call of its own (capsule_hit, capsule_hit_lanes): inlined
// into the rejects, its registers made every rejected call dearer (case 1
// ref, 83 calls per ray, mostly rejected: +2.4 % per ray).
[[gnu::always_inline]] inline std::optional<Hit> capsule_solve(const Ray& ray, const LocalRay& lr, const DVec3& a,
                                                             const DVec3& ba, double len2, double r) {
    Span span = hull(sphere_span(lr, a, r, 1), sphere_span(lr, -a, r, 2));
    DVec3 w(0.0);
    if (len2 > 0.0) {
        const double len = std::sqrt(len2);
        w = ba / len;
        const DVec3 oa = lr.o - a;
        const Span body = overlap(cylinder_span(lr, a, w, r, 0),
                                  slab_span(glm::dot(oa, w), glm::dot(lr.d, w), 0.0, len, 0, 0));
        span = hull(span, body);
    }
    SpanPick hit;
    if (!pick(span, lr, ray, hit)) return std::nullopt;

    const DVec3 p = lr.o + hit.s * lr.d;
    const double u = len2 > 0.0 ? std::clamp(glm::dot(p - a, ba) / len2, 0.0, 1.0) : 0.0;
    const DVec3 n = p - (a + u * ba);
    const double nn = glm::dot(n, n);
    const Vec3 normal = nn > 0.0 ? Vec3(n / std::sqrt(nn)) : Vec3(0.0f, 0.0f, 1.0f);
    return Hit{hit.t, normal, static_cast<float>(u)};
}

[[gnu::noinline]] inline std::optional<Hit> capsule_hit(const Ray& ray, const LocalRay& lr, const DVec3& a,
                                                      const DVec3& ba, double len2, double r) {
    return capsule_solve(ray, lr, a, ba, len2, r);
}

// The numbers the capsule's cheap rejects and its hit are made of, in double:
// the capsule around its centre c and the ray relative to it.
struct CapsuleFrame {
    DVec3 a;          // p0 - c
    DVec3 ba;         // p1 - p0
    DVec3 d;          // the ray's direction
    DVec3 oc;         // the ray's origin - c
    double len2, dd;  // ba.ba, d.d
    double od, oo;    // oc.d, oc.oc
};

// The second reject's numbers, n.n and oc.n with n = d x ba: made only for
// the calls the first reject passes.
struct CapsuleAxis {
    double nn, on;
};

// With glm, one component at a time: the reference the lanes version below
// must match bit for bit (tests/intersectors/test_intersect_straight.cpp).
[[nodiscard]] inline CapsuleFrame capsule_frame_scalar(const Capsule& cap, const Ray& ray) {
    const DVec3 p0(cap.p0), p1(cap.p1);
    const DVec3 c = 0.5 * (p0 + p1);
    CapsuleFrame f;
    f.a = p0 - c;
    f.ba = p1 - p0;
    f.d = DVec3(ray.direction);
    f.oc = DVec3(ray.origin) - c;
    f.len2 = glm::dot(f.ba, f.ba);
    f.dd = glm::dot(f.d, f.d);
    f.od = glm::dot(f.oc, f.d);
    f.oo = glm::dot(f.oc, f.oc);
    return f;
}

[[nodiscard]] inline CapsuleAxis capsule_axis(const CapsuleFrame& f) {
    const DVec3 n = glm::cross(f.d, f.ba);
    return {glm::dot(n, n), glm::dot(f.oc, n)};
}

#if defined(__AVX2__)
// capsule_frame_scalar's operations on (x, y, z) lanes of 256-bit vectors:
// each sum, difference and product is the scalar one, and each dot product
// adds its three products in glm's order, (x + y) + z, so every field is bit
// for bit the scalar one (no fused multiply-add: CMakeLists.txt). Six dot
// products by two transposes instead of one component at a time: the rejects
// are most of a capsule program's instructions (case 1 ref: 83 programs per
// ray, nearly all rejected).
struct CapsuleLanes {
    __m256d a, ba, d, oc;
    double len2, dd, od, oo;
};

// Lanes 0-2 of v.
[[nodiscard, gnu::always_inline]] inline DVec3 to_dvec3(__m256d v) {
    double x[4];
    _mm256_storeu_pd(x, v);
    return {x[0], x[1], x[2]};
}

// capsule_hit from the lanes: a call of its own that takes the vectors in
// registers, so that the rejects' path keeps no 32-byte vector in memory
// (as an aligned stack slot it cost every call a realigned frame). The solve
// is inlined here: as a second call (capsule_hit) it cost case 2 ref, whose
// programs mostly pass the rejects, 11 instructions per ray.
[[gnu::noinline]] inline std::optional<Hit> capsule_hit_lanes(const Ray& ray, __m256d a, __m256d ba, __m256d d,
                                                             __m256d oc, double dd, double od, double len2,
                                                             double r) {
    return capsule_solve(ray, local_ray(to_dvec3(d), to_dvec3(oc), dd, od), to_dvec3(a), to_dvec3(ba), len2, r);
}

[[nodiscard, gnu::always_inline]] inline CapsuleLanes capsule_frame_lanes(const Capsule& cap, const Ray& ray) {
    // The capsule's points in one 16-byte load each: in the struct each is
    // followed by a fourth float (p1, radius), which lands in lane 3, a lane
    // no sum, test or stored vector uses. The ray's in two loads (8 + 4
    // bytes): the caller has just stored it with a new tmax, and a 16-byte
    // load over both stores cannot take their data from the store buffer
    // (with it, case 1 ref ran 12 % fewer instructions but 19 % slower).
    static_assert(offsetof(Capsule, p1) == 12 && offsetof(Capsule, radius) == 24);
    const auto widen = [](const Vec3& v) { return _mm256_cvtps_pd(_mm_loadu_ps(&v.x)); };
    const auto widen_ray = [](const Vec3& v) { return _mm256_cvtps_pd(load3(v)); };
    // The sums of lanes 0-2 of p, q, r and s: (x + y) + z of each.
    const auto sums4 = [](__m256d p, __m256d q, __m256d r, __m256d s) {
        const __m256d xz_pq = _mm256_unpacklo_pd(p, q), yw_pq = _mm256_unpackhi_pd(p, q);
        const __m256d xz_rs = _mm256_unpacklo_pd(r, s), yw_rs = _mm256_unpackhi_pd(r, s);
        const __m256d x = _mm256_permute2f128_pd(xz_pq, xz_rs, 0x20), y = _mm256_permute2f128_pd(yw_pq, yw_rs, 0x20);
        const __m256d z = _mm256_permute2f128_pd(xz_pq, xz_rs, 0x31);
        return _mm256_add_pd(_mm256_add_pd(x, y), z);
    };
    const auto high = [](__m128d v) { return _mm_cvtsd_f64(_mm_unpackhi_pd(v, v)); };
    CapsuleLanes f;
    const __m256d p0 = widen(cap.p0), p1 = widen(cap.p1);
    const __m256d c = _mm256_mul_pd(_mm256_set1_pd(0.5), _mm256_add_pd(p0, p1));
    f.a = _mm256_sub_pd(p0, c);
    f.ba = _mm256_sub_pd(p1, p0);
    f.d = widen_ray(ray.direction);
    f.oc = _mm256_sub_pd(widen_ray(ray.origin), c);
    const __m256d s = sums4(_mm256_mul_pd(f.ba, f.ba), _mm256_mul_pd(f.d, f.d), _mm256_mul_pd(f.oc, f.d),
                            _mm256_mul_pd(f.oc, f.oc));
    const __m128d s_lo = _mm256_castpd256_pd128(s), s_hi = _mm256_extractf128_pd(s, 1);
    f.len2 = _mm_cvtsd_f64(s_lo);
    f.dd = high(s_lo);
    f.od = _mm_cvtsd_f64(s_hi);
    f.oo = high(s_hi);
    return f;
}

[[nodiscard, gnu::always_inline]] inline CapsuleAxis capsule_axis(const CapsuleLanes& f) {
    // n = d x ba = d.yzx ba.zxy - ba.yzx d.zxy, glm::cross's products and order.
    const auto yzx = [](__m256d v) { return _mm256_permute4x64_pd(v, _MM_SHUFFLE(3, 0, 2, 1)); };
    const auto zxy = [](__m256d v) { return _mm256_permute4x64_pd(v, _MM_SHUFFLE(3, 1, 0, 2)); };
    const __m256d n = _mm256_sub_pd(_mm256_mul_pd(yzx(f.d), zxy(f.ba)), _mm256_mul_pd(yzx(f.ba), zxy(f.d)));
    // (x + y) + z of n.n and of oc.n.
    const __m256d nn = _mm256_mul_pd(n, n), on = _mm256_mul_pd(f.oc, n);
    const __m256d xz = _mm256_unpacklo_pd(nn, on), yw = _mm256_unpackhi_pd(nn, on);
    const __m128d t = _mm_add_pd(_mm_add_pd(_mm256_castpd256_pd128(xz), _mm256_castpd256_pd128(yw)),
                                 _mm256_extractf128_pd(xz, 1));
    return {_mm_cvtsd_f64(t), _mm_cvtsd_f64(_mm_unpackhi_pd(t, t))};
}
#endif

[[nodiscard, gnu::always_inline]] inline auto capsule_frame(const Capsule& cap, const Ray& ray) {
#if defined(__AVX2__)
    return capsule_frame_lanes(cap, ray);
#else
    return capsule_frame_scalar(cap, ray);
#endif
}

[[nodiscard, gnu::always_inline]] inline std::optional<Hit> capsule_hit(const Ray& ray, const CapsuleFrame& f,
                                                                     double r) {
    return capsule_hit(ray, local_ray(f.d, f.oc, f.dd, f.od), f.a, f.ba, f.len2, r);
}
#if defined(__AVX2__)
[[nodiscard, gnu::always_inline]] inline std::optional<Hit> capsule_hit(const Ray& ray, const CapsuleLanes& f,
                                                                     double r) {
    return capsule_hit_lanes(ray, f.a, f.ba, f.d, f.oc, f.dd, f.od, f.len2, r);
}
#endif

// Cheap rejects without a division or square root (most calls miss).
// 1. The ray line's squared distance to the centre times |d|^2 is
//    |oc|^2 |d|^2 - (oc.d)^2; the capsule lies within L/2 + r of the centre,
//    and (L/2 + r)^2 <= 2 (L^2/4 + r^2) avoids the square root of L^2.
// 2. Long thin capsules pass the sphere test for most rays: reject too when
//    the ray's line stays farther than r from the axis line (the capsule lies
//    within the infinite cylinder of radius r around it): |oc.n| / |n| > r
//    with n = d x ba. Only when the angle between them is not tiny
//    (sin^2 > 1e-6), so the error of oc.n is below ~1e-12 |oc| |n|; the
//    threshold adds 2e-6 r^2 and 1e-16 |oc|^2 (as (a + b)^2 <= (1 + k) a^2 +
//    (1 + 1/k) b^2 with k = 1e-6), so it only rejects rays the exact test
//    misses by far more than rounding.
// Which of the two rejects ends the call: 0 none (the ray may hit), 1 the
// sphere test, 2 the axis test.
template <class Frame>
[[nodiscard, gnu::always_inline]] inline int capsule_reject_by(const Frame& f, double r) {
    const double reach2 = 2.0 * (0.25 * f.len2 + r * r);
    if (!(f.dd > 0.0) || !(f.oo * f.dd - f.od * f.od <= reach2 * f.dd)) return 1;
    const CapsuleAxis x = capsule_axis(f);
    return x.nn > 1e-6 * f.dd * f.len2 && x.on * x.on > x.nn * (r * r * (1.0 + 2e-6) + 1e-16 * f.oo) ? 2 : 0;
}

template <class Frame>
[[nodiscard, gnu::always_inline]] inline bool capsule_rejects(const Frame& f, double r) {
    return capsule_reject_by(f, r) != 0;
}

// The capsule program's operations per path (conventions: core/ops.h).
// Entry: the capsule's 28 B (2 loads), the radius test.
inline constexpr Ops kCapsuleEntry{.branch = 1, .load = 2};
// The frame: c = (p0 + p1) / 2 (6), a, ba, oc (9), len2, dd, od, oo (12); the
// sphere reject: reach2 (3), d.d > 0, |oc|^2 |d|^2 - (oc.d)^2 (2), reach2 |d|^2
// (1), the compare.
inline constexpr Ops kCapsuleSphereReject = kCapsuleEntry + Ops{.fma = 33, .branch = 2};
// The axis reject: n = d x ba (6), n.n and oc.n (6), the angle test (2, a
// compare), (oc.n)^2 (1), the threshold (3) times n.n (1), the compare.
inline constexpr Ops kCapsuleAxisReject = kCapsuleSphereReject + Ops{.fma = 19, .branch = 2};
// The solve: the local ray (t0 a division and a branch, o 3); two end spheres
// (each: o - m 3, s_mid 3 and a division, perp 3, h 4, a branch, the half
// width a division and a sqrt, both ends 2) and their hull (2); the body
// (len a sqrt, w a reciprocal and 3, o - a 3, the infinite cylinder's span 31
// with 2 divisions, a sqrt and 2 branches, the slab's 8 with 2 divisions and
// 2 branches, overlap and hull 4, a branch on len2); the pick (1, 3 branches).
inline constexpr Ops kCapsuleSolved = kCapsuleAxisReject + Ops{.fma = 85, .div = 10, .sqrt = 4, .branch = 11};
// A hit adds: the point (3), u = (p - a).ba / len2 (6 and a division),
// its clamp (2), n = p - (a + u ba) (6), n.n (3) and a branch, the normal's
// normalisation (a sqrt, a reciprocal, 3).
inline constexpr Ops kCapsuleHit = kCapsuleSolved + Ops{.fma = 23, .div = 2, .sqrt = 1, .branch = 1};

}  // namespace detail

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const Capsule& cap, const Ray& ray, Sink& sink) {
    sink.on(Event::IsCapsule);
    const double r = cap.radius;
    if (!(r > 0.0)) {  // zero radius: no surface (and NaN lands here)
        count_ops(sink, detail::kCapsuleEntry);
        return std::nullopt;
    }
    const auto f = detail::capsule_frame(cap, ray);
    if (const int by = detail::capsule_reject_by(f, r)) {
        count_ops(sink, by == 1 ? detail::kCapsuleSphereReject : detail::kCapsuleAxisReject);
        return std::nullopt;
    }
    auto hit = detail::capsule_hit(ray, f, r);
    count_ops(sink, hit ? detail::kCapsuleHit : detail::kCapsuleSolved);
    return hit;
}

}  // namespace rtc
