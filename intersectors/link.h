// Link (Han et al. 2019, "Ray Tracing Generalized Tube Primitives: Method and
// Applications", their sphere-truncated-cone-stump): the convex hull of two
// spheres (p0, r0) and (p1, r1), equivalently the sweep of a sphere whose
// radius varies linearly along p0-p1.
//
// Derivation. In the plane of the axis (axial z from p0, radial rho), the
// outer tangent of the two circles has unit normal n = (n_z, n_rho) with
// n_z = (r0 - r1) / l, n_rho = sqrt(1 - n_z^2) (l = |p1 - p0|); it touches
// sphere 0 at z = r0 n_z and sphere 1 at z = l + r1 n_z. Between those two
// planes the surface is the cone n_z z + n_rho rho = r0, i.e. radius
// g(z) = (r0 - n_z z) / n_rho, and outside them it is the spheres. The cone's
// apex lies outside that slab (g > 0 inside it), so within the slab the double
// cone |x_perp|^2 <= g(z)^2 is the solid cone: its ray interval is one
// interval, or two half-lines of which the slab keeps one. The link is convex,
// so its interval is the hull of the intervals of the two spheres and the
// cone-in-slab. When l <= |r0 - r1| one sphere contains the other and the cone
// vanishes. Solved in double around the ray point closest to the centre
// (span.h). Normals: sphere (hit - centre) / r; cone n_rho radial + n_z axis.
//
// Bounds: AABB of the two spheres; OBB (Wald et al. 2020): as a capsule of
// radius max(r0, r1); Tight == Paper.
#pragma once

#include "core/events.h"
#include "core/obb.h"
#include "core/ops.h"
#include "intersectors/frame.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"
#include "intersectors/span.h"

#include <optional>

namespace rtc {

struct Link {
    Vec3 p0{0.0f};
    float r0 = 0.0f;
    Vec3 p1{0.0f};
    float r1 = 0.0f;
};

[[nodiscard]] inline bool is_finite(const Link& k) {
    return is_finite(k.p0) && is_finite(k.p1) && std::isfinite(k.r0) && std::isfinite(k.r1);
}

[[nodiscard]] inline Aabb bounds(const Link& k) {
    const double r0 = std::max(k.r0, 0.0f), r1 = std::max(k.r1, 0.0f);
    const DVec3 p0(k.p0), p1(k.p1);
    return outward_bounds(glm::min(p0 - r0, p1 - r1), glm::max(p0 + r0, p1 + r1));
}

[[nodiscard]] inline Obb oriented_bounds(const Link& k, ObbVariant = ObbVariant::Paper) {
    const float r = std::max({k.r0, k.r1, 0.0f});
    return segment_obb(k.p0, k.p1, r, r);
}

namespace detail {

// Ray interval of the solid cone |x_perp| <= ga + gb s (radius along the ray)
// restricted to `slab`: f(s) = A s^2 + 2 B s + C <= 0.
[[nodiscard]] inline Span cone_in_slab(double a_, double b_, double c_, double dd,
                                       const Span& slab) {
    constexpr int kCone = 0;
    if (slab.empty()) return {};
    if (!(std::abs(a_) > 1e-14 * dd)) {  // a generator direction: f is linear
        if (b_ == 0.0) return c_ <= 0.0 ? overlap(Span{-kDInf, kDInf, kCone, kCone}, slab) : Span{};
        const double s = -c_ / (2.0 * b_);
        return overlap(b_ > 0.0 ? Span{-kDInf, s, kCone, kCone} : Span{s, kDInf, kCone, kCone},
                       slab);
    }
    const double h = b_ * b_ - a_ * c_;
    if (!(h >= 0.0)) return a_ > 0.0 ? Span{} : slab;
    const double q = -(b_ + std::copysign(std::sqrt(h), b_));
    double s0 = q != 0.0 ? q / a_ : 0.0, s1 = q != 0.0 ? c_ / q : 0.0;
    if (s0 > s1) std::swap(s0, s1);
    if (a_ > 0.0) return overlap(Span{s0, s1, kCone, kCone}, slab);
    const Span lo = overlap(Span{-kDInf, s0, kCone, kCone}, slab);
    const Span hi = overlap(Span{s1, kDInf, kCone, kCone}, slab);
    return hull(lo.empty() ? Span{} : lo, hi.empty() ? Span{} : hi);
}

// The link program's operations per path (conventions: core/ops.h).
// Entry: the link's 32 B (2 loads), the radii's clamps (2) and test (2).
inline constexpr Ops kLinkEntry{.fma = 2, .branch = 2, .load = 2};
// The bounding-sphere reject: c (6), the local ray (12, a division, a
// branch), a and ba (6), l (3 and a sqrt), reach (2), d.d > 0, o.o (3),
// reach^2 (1), the compare.
inline constexpr Ops kLinkSphereReject = kLinkEntry + Ops{.fma = 33, .div = 1, .sqrt = 1, .branch = 3};
// The solve: two end spheres (30, 4 divisions, 2 sqrts, 2 branches and 2
// radius tests) and their hull (2); w (a reciprocal, 3, a branch); the cone's
// test (2, a branch), nz (1, a division), nr (3, a sqrt), o - a (3), oz and
// dz (6), o_perp and d_perp (12), ga and gb (4, 2 divisions), the slab (4, 2
// divisions, 2 branches), the quadratic's coefficients (12); cone_in_slab
// (its tests 2 and 5 branches, h 2, q 2 and a sqrt, the roots 2 divisions,
// overlaps and hull 6); the final hull (2), the pick (1, 3 branches).
inline constexpr Ops kLinkSolved = kLinkSphereReject + Ops{.fma = 101, .div = 11, .sqrt = 4, .branch = 17};
// A hit adds: the point (3), z (6), the piece's branches (2), the cone's
// normal (radial 9, its length 3 and a sqrt, a reciprocal, the scale 6, + nz
// w 3), the normal's normalisation (3, a branch, a sqrt, a reciprocal, 3),
// u (a division, clamp 2, a branch).
inline constexpr Ops kLinkHit = kLinkSolved + Ops{.fma = 38, .div = 3, .sqrt = 2, .branch = 5};

}  // namespace detail

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const Link& k, const Ray& ray, Sink& sink) {
    sink.on(Event::IsLink);
    const double r0 = std::max(double(k.r0), 0.0), r1 = std::max(double(k.r1), 0.0);
    if (!(r0 > 0.0 || r1 > 0.0)) {  // no volume (NaN lands here too)
        count_ops(sink, detail::kLinkEntry);
        return std::nullopt;
    }
    const DVec3 p0(k.p0), p1(k.p1);
    const DVec3 c = 0.5 * (p0 + p1);
    const LocalRay lr = local_ray(ray, c);
    const DVec3 a = p0 - c, ba = p1 - p0;
    const double l = std::sqrt(glm::dot(ba, ba));
    const double reach = 0.5 * l + std::max(r0, r1);
    if (!(lr.dd > 0.0) || !(glm::dot(lr.o, lr.o) <= reach * reach)) {
        count_ops(sink, detail::kLinkSphereReject);
        return std::nullopt;
    }

    enum Part { kCone = 0, kSphere0 = 1, kSphere1 = 2 };
    Span span = hull(r0 > 0.0 ? sphere_span(lr, a, r0, kSphere0) : Span{},
                     r1 > 0.0 ? sphere_span(lr, -a, r1, kSphere1) : Span{});
    const DVec3 w = l > 0.0 ? ba / l : DVec3(0.0, 0.0, 1.0);
    double nz = 0.0, nr = 1.0;
    if (l > std::abs(r0 - r1)) {
        nz = (r0 - r1) / l;
        nr = std::sqrt((1.0 - nz) * (1.0 + nz));
        const DVec3 oa = lr.o - a;
        const double oz = glm::dot(oa, w), dz = glm::dot(lr.d, w);
        const DVec3 o_perp = oa - oz * w, d_perp = lr.d - dz * w;
        const double ga = (r0 - nz * oz) / nr, gb = -nz * dz / nr;
        const Span slab = slab_span(oz, dz, r0 * nz, l + r1 * nz, kCone, kCone);
        span = hull(span, detail::cone_in_slab(glm::dot(d_perp, d_perp) - gb * gb,
                                               glm::dot(o_perp, d_perp) - ga * gb,
                                               glm::dot(o_perp, o_perp) - ga * ga, lr.dd, slab));
    }
    SpanPick hit;
    if (!pick(span, lr, ray, hit)) {
        count_ops(sink, detail::kLinkSolved);
        return std::nullopt;
    }
    count_ops(sink, detail::kLinkHit);

    const DVec3 p = lr.o + hit.s * lr.d;
    const double z = glm::dot(p - a, w);
    DVec3 n;
    if (hit.part == kSphere0) {
        n = p - a;
    } else if (hit.part == kSphere1) {
        n = p + a;  // sphere 1 is centred at -a relative to the midpoint
    } else {
        const DVec3 radial = p - a - z * w;
        const double rr = glm::dot(radial, radial);
        n = (rr > 0.0 ? nr * radial / std::sqrt(rr) : DVec3(0.0)) + nz * w;
    }
    const double nn = glm::dot(n, n);
    const Vec3 normal = nn > 0.0 ? Vec3(n / std::sqrt(nn)) : Vec3(w);
    const double u = l > 0.0 ? std::clamp(z / l, 0.0, 1.0) : 0.0;
    return Hit{hit.t, normal, static_cast<float>(u)};
}

}  // namespace rtc
