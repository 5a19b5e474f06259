// Extended-precision references for the straight primitives (tests only).
//
// Deliberately a different formulation from intersectors/span.h: textbook
// quadratics a s^2 + 2 b s + c = 0 in world coordinates, no origin shift, in
// long double (64-bit mantissa on x86), so the two share no code path and the
// reference's own rounding is ~2^11 times below the float targets. Every shape
// is convex; its ray interval is the hull of its pieces' intervals.
#pragma once

#include "core/ray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace rtc::ref {

using Real = long double;
struct V3 {
    Real x, y, z;
};
inline V3 v3(const Vec3& v) { return {v.x, v.y, v.z}; }
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(Real s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Real dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline constexpr Real kInf = std::numeric_limits<Real>::infinity();

struct Interval {
    Real lo = kInf, hi = -kInf;
    [[nodiscard]] bool empty() const { return !(lo <= hi); }
};
inline Interval hull(Interval a, Interval b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)};
}
inline Interval meet(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)}; }

// Roots of a s^2 + 2 b s + c <= 0 as an interval (a > 0), or all/nothing.
inline Interval quad_inside(Real a, Real b, Real c) {
    if (a <= 0) return c <= 0 ? Interval{-kInf, kInf} : Interval{};
    const Real h = b * b - a * c;
    if (h < 0) return {};
    const Real sq = std::sqrt(h);
    return {(-b - sq) / a, (-b + sq) / a};
}

inline Interval sphere(V3 o, V3 d, V3 m, Real r) {
    const V3 om = o - m;
    return quad_inside(dot(d, d), dot(om, d), dot(om, om) - r * r);
}

inline Interval slab(V3 o, V3 d, V3 a, V3 w, Real lo, Real hi) {
    const Real z0 = dot(o - a, w), dz = dot(d, w);
    if (dz == 0) return (z0 >= lo && z0 <= hi) ? Interval{-kInf, kInf} : Interval{};
    const Real s0 = (lo - z0) / dz, s1 = (hi - z0) / dz;
    return {std::min(s0, s1), std::max(s0, s1)};
}

// Solid cone around the line a + z w with radius g0 + g1 z, restricted by the
// caller to a slab where the radius stays positive.
inline Interval cone(V3 o, V3 d, V3 a, V3 w, Real g0, Real g1) {
    const V3 oa = o - a;
    const Real oz = dot(oa, w), dz = dot(d, w);
    const Real ga = g0 + g1 * oz, gb = g1 * dz;  // radius along the ray: ga + gb s
    const Real qa = dot(d, d) - dz * dz - gb * gb;
    const Real qb = dot(oa, d) - oz * dz - ga * gb;
    const Real qc = dot(oa, oa) - oz * oz - ga * ga;
    if (std::abs(qa) <= 1e-30L * dot(d, d)) {
        if (qb == 0) return qc <= 0 ? Interval{-kInf, kInf} : Interval{};
        const Real s = -qc / (2 * qb);
        return qb > 0 ? Interval{-kInf, s} : Interval{s, kInf};
    }
    const Real h = qb * qb - qa * qc;
    if (h < 0) return qa > 0 ? Interval{} : Interval{-kInf, kInf};
    const Real sq = std::sqrt(h);
    const Real s0 = (-qb - sq) / qa, s1 = (-qb + sq) / qa;
    if (qa > 0) return {s0, s1};
    // Inside outside the roots: two half-lines; the caller's slab keeps one.
    return {-kInf, kInf};  // refined by the caller (see link())
}

// Convex hull of spheres (p0, r0) and (p1, r1): the link; r0 == r1 is the capsule.
inline Interval link(V3 o, V3 d, V3 p0, Real r0, V3 p1, Real r1) {
    Interval out = hull(sphere(o, d, p0, r0), sphere(o, d, p1, r1));
    const V3 ab = p1 - p0;
    const Real l = std::sqrt(dot(ab, ab));
    if (!(l > std::abs(r0 - r1))) return out;
    const V3 w = (1 / l) * ab;
    const Real nz = (r0 - r1) / l, nr = std::sqrt(1 - nz * nz);
    const Real z0 = r0 * nz, z1 = l + r1 * nz;  // tangent planes
    const Real g1 = -nz / nr, g0 = r0 / nr;      // cone radius g0 + g1 z
    const Interval sl = slab(o, d, p0, w, z0, z1);
    if (sl.empty()) return out;
    Interval c = cone(o, d, p0, w, g0, g1);
    if (c.lo == -kInf && c.hi == kInf && !sl.empty()) {
        // Two half-lines (or everything): test which part of the slab is inside
        // by bisection-free sampling of the two slab ends and their roots.
        const V3 oa = o - p0;
        const Real oz = dot(oa, w), dz = dot(d, w);
        const Real ga = g0 + g1 * oz, gb = g1 * dz;
        const Real qa = dot(d, d) - dz * dz - gb * gb, qb = dot(oa, d) - oz * dz - ga * gb,
                   qc = dot(oa, oa) - oz * oz - ga * ga;
        auto f = [&](Real s) { return (qa * s + 2 * qb) * s + qc; };
        const Real h = qb * qb - qa * qc;
        if (h >= 0 && qa < 0) {
            const Real sq = std::sqrt(h);
            const Real s0 = (-qb + sq) / qa, s1 = (-qb - sq) / qa;  // s0 <= s1
            const Interval a{-kInf, s0}, b{s1, kInf};
            const Interval ma = meet(a, sl), mb = meet(b, sl);
            c = hull(ma.empty() ? Interval{} : ma, mb.empty() ? Interval{} : mb);
        } else {
            c = f(0.5L * (sl.lo + sl.hi)) <= 0 ? sl : Interval{};
        }
    }
    const Interval body = meet(c, sl);
    if (!body.empty()) out = hull(out, body);
    return out;
}

inline Interval link(const Ray& ray, const Vec3& p0, Real r0, const Vec3& p1, Real r1) {
    return link(v3(ray.origin), v3(ray.direction), v3(p0), r0, v3(p1), r1);
}

// Finite cylinder with flat caps.
inline Interval cylinder(const Ray& ray, const Vec3& p0f, const Vec3& p1f, Real r) {
    const V3 o = v3(ray.origin), d = v3(ray.direction), p0 = v3(p0f), p1 = v3(p1f);
    const V3 ab = p1 - p0;
    const Real l = std::sqrt(dot(ab, ab));
    if (!(l > 0) || !(r > 0)) return {};
    const V3 w = (1 / l) * ab;
    const V3 dxw = cross(d, w), oxw = cross(o - p0, w);
    const Interval side = quad_inside(dot(dxw, dxw), dot(dxw, oxw), dot(oxw, oxw) - r * r);
    return meet(side, slab(o, d, p0, w, 0, l));
}

// Nearest end of an interval at or after tmin (rays of the tests have tmax = inf).
inline std::optional<Real> nearest(const Interval& iv, Real tmin) {
    if (iv.empty()) return std::nullopt;
    if (iv.lo >= tmin) return iv.lo;
    if (iv.hi >= tmin) return iv.hi;
    return std::nullopt;
}

}  // namespace rtc::ref
