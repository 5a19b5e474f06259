// Ray-parameter intervals of the convex pieces the straight primitives are
// made of (sphere, infinite cylinder, slab), computed in double.
//
// Why double: a float intersector loses about one ulp of the primitive's
// length or position in every coordinate it forms (p1 - p0, o - p0, the
// projections on the axis), i.e. an error of ~6e-8 L perpendicular to a
// primitive of length L. At length/radius 10^4 that is ~1e-3 r, right at the
// accuracy target. On the CPU that runs the simulator double costs about the
// same as float, and the simulator's job is to decide hits correctly; what the
// GPU would pay is priced by events, not by this arithmetic.
//
// Robustness (Haines et al. 2019, "Precision Improvements for Ray/Sphere
// Intersection", Ray Tracing Gems ch. 7): the ray origin is first moved to the
// point of the ray closest to the primitive's centre (`LocalRay`), so every
// quadratic below is solved on numbers of the primitive's size, not of the
// ray's length; discriminants are formed as r^2 - (distance of closest
// approach)^2 rather than b^2 - 4ac.
#pragma once

#include "core/ray.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtc {

inline constexpr double kDInf = std::numeric_limits<double>::infinity();

// The ray re-expressed around a centre point c: point(s) = o + s d is the ray
// at parameter t = t0 + s, relative to c.
struct LocalRay {
    DVec3 o;
    DVec3 d;
    double dd;  // |d|^2
    double t0;
};

// From its parts, for a caller that has them already: d, oc = origin - c,
// dd = d.d and od = oc.d.
// Always inlined: once GCC kept local_ray(ray, c) out of line, the
// cylinder program (fig3_bundles' ref) ran 7 % more instructions.
[[nodiscard, gnu::always_inline]] inline LocalRay local_ray(const DVec3& d, const DVec3& oc, double dd, double od) {
    const double t0 = dd > 0.0 ? -od / dd : 0.0;
    return {oc + t0 * d, d, dd, t0};
}

[[nodiscard, gnu::always_inline]] inline LocalRay local_ray(const Ray& ray, const DVec3& c) {
    const DVec3 d(ray.direction);
    const DVec3 oc = DVec3(ray.origin) - c;
    return local_ray(d, oc, glm::dot(d, d), glm::dot(oc, d));
}

// A closed interval [lo, hi] of the local parameter s; empty when lo > hi.
// `part_lo` / `part_hi` say which surface piece bounds it (for normals).
struct Span {
    double lo = kDInf;
    double hi = -kDInf;
    int part_lo = -1;
    int part_hi = -1;

    [[nodiscard]] bool empty() const { return !(lo <= hi); }
};

[[nodiscard]] inline Span full_span() { return {-kDInf, kDInf, -1, -1}; }

// Union of two overlapping convex pieces of one convex shape (its hull).
[[nodiscard]] inline Span hull(const Span& a, const Span& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    Span s = a;
    if (b.lo < s.lo) s.lo = b.lo, s.part_lo = b.part_lo;
    if (b.hi > s.hi) s.hi = b.hi, s.part_hi = b.part_hi;
    return s;
}

[[nodiscard]] inline Span overlap(const Span& a, const Span& b) {
    Span s = a;
    if (b.lo > s.lo) s.lo = b.lo, s.part_lo = b.part_lo;
    if (b.hi < s.hi) s.hi = b.hi, s.part_hi = b.part_hi;
    return s;
}

// Sphere of radius r whose centre is at `m` relative to the local origin.
[[nodiscard]] inline Span sphere_span(const LocalRay& r, const DVec3& m, double radius, int part) {
    const DVec3 om = r.o - m;
    const double s_mid = -glm::dot(om, r.d) / r.dd;
    const DVec3 perp = om + s_mid * r.d;
    const double h = radius * radius - glm::dot(perp, perp);
    if (!(h >= 0.0)) return {};
    const double half = std::sqrt(h / r.dd);
    return {s_mid - half, s_mid + half, part, part};
}

// Infinite cylinder of radius r around the line through `a` with unit axis w.
// Parallel rays (no perpendicular motion) are inside everywhere or nowhere.
[[nodiscard]] inline Span cylinder_span(const LocalRay& r, const DVec3& a, const DVec3& w,
                                        double radius, int part) {
    const DVec3 oa = r.o - a;
    const DVec3 o_perp = oa - glm::dot(oa, w) * w;
    const DVec3 d_perp = r.d - glm::dot(r.d, w) * w;
    const double dp = glm::dot(d_perp, d_perp);
    const double r2 = radius * radius;
    if (!(dp > 1e-24 * r.dd)) {
        if (glm::dot(o_perp, o_perp) <= r2) return {-kDInf, kDInf, part, part};
        return {};
    }
    const double s_mid = -glm::dot(o_perp, d_perp) / dp;
    const DVec3 closest = o_perp + s_mid * d_perp;
    const double h = r2 - glm::dot(closest, closest);
    if (!(h >= 0.0)) return {};
    const double half = std::sqrt(h / dp);
    return {s_mid - half, s_mid + half, part, part};
}

// Slab lo <= z0 + s dz <= hi of an axial coordinate.
[[nodiscard]] inline Span slab_span(double z0, double dz, double lo, double hi, int part_lo,
                                    int part_hi) {
    if (dz == 0.0) {
        if (z0 >= lo && z0 <= hi) return full_span();
        return {};
    }
    const double s_lo = (lo - z0) / dz, s_hi = (hi - z0) / dz;
    if (s_lo <= s_hi) return {s_lo, s_hi, part_lo, part_hi};
    return {s_hi, s_lo, part_hi, part_lo};
}

// The nearest end of the span within [tmin, tmax], as a float ray parameter.
// The float t is fixed before the interval check, so tmax only filters and
// never changes the value (two traversal orders get bit-identical t).
struct SpanPick {
    float t;
    double s;
    int part;
};
[[nodiscard]] inline bool pick(const Span& span, const LocalRay& r, const Ray& ray, SpanPick& out) {
    if (span.empty()) return false;
    const float t_lo = static_cast<float>(r.t0 + span.lo);
    if (t_lo >= ray.tmin) {
        if (!(t_lo <= ray.tmax)) return false;
        out = {t_lo, span.lo, span.part_lo};
        return true;
    }
    const float t_hi = static_cast<float>(r.t0 + span.hi);
    if (!(t_hi >= ray.tmin && t_hi <= ray.tmax)) return false;
    out = {t_hi, span.hi, span.part_hi};
    return true;
}

}  // namespace rtc
