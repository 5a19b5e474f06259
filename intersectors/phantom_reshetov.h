// The paper's phantom program: Reshetov & Luebke 2018, "Phantom Ray-Hair
// Intersector" (Proc. ACM CGIT 1(2), HPG 2018, doi 10.1145/3233307), as
// published, with the early-out bounding cylinder Wald et al. 2020 used
// ("Reshetov's suggested early-out"). Written from the paper's description
// and ../shared/docs/rt-hardware.md section 3; selected by
// PhantomOptions::program = Paper.
//
// Derivation. In the ray-centric frame the ray is the z axis. Near parameter
// t the tube is replaced by its tangent cone: apex line through c = B(t) along
// B'(t) (length L, unit a), radius r(t) growing by k = r'(t)/L per unit of
// axial length. A ray point (0, 0, c.z + s) has axial coordinate
// A = a.z s - b with b = (c.x B'.x + c.y B'.y)/L, and lies on the cone when
//   c.x^2 + c.y^2 + s^2 - A^2 = (r + k A)^2,
// i.e. alpha s^2 + 2 beta s + gamma = 0 with rho = r - k b,
//   alpha = 1 - a.z^2 (1 + k^2), beta = a.z (b - k rho),
//   gamma = c.x^2 + c.y^2 - b^2 - rho^2
// (Reshetov & Luebke's Appendix A; for k = 0 the same quadratic as the public
// code's cylinder). The entry root s = (-beta - sqrt(D))/alpha is the cone
// hit; when the ray misses (D < 0) the "phantom" hit s = -beta/alpha, where
// the cone comes nearest to the ray, keeps the iteration going. The hit's
// axial offset from c, in curve parameter, dt = A/L, is the correction: t
// moves by dt (clamped to +-0.5); when dt changes sign a regula falsi step on
// the last two (t, dt) replaces it, a plain bisection every 4th iteration.
// Converged when the cone hit is real and |dt| < 5e-5 ("In all examples in
// this paper we stop iterations when dt < 5x10^-5"): the hit lies in the
// cross-section plane of B(t), i.e. on the tube. The search starts at the end
// the ray meets first (sign of (P3 - P0).d), gives up when t leaves [0, 1] or
// after 40 iterations, and then retries once from the other end.
//
// The search and the cylinder run against the ray's [tmin, infinity), never
// its tmax; only the answer is compared with tmax. The search is local: cut
// at tmax, a first search that converged just beyond it (the float tmax of a
// hit found by an earlier call of the same primitive is at most half an ulp
// off) retried from the other end and could settle elsewhere on the tube,
// and the cylinder (which does not always contain the curve) could reject a
// hit nearer than tmax. The answer then depended on the tmax a traversal
// happened to call the program with, so methods visiting primitives in
// another order (ref, obb) or calling one primitive more than once (split)
// disagreed on a few fur rays in 10^6 (issue 38, item 6). Now a call
// returns the tmax = infinity answer when its t <= tmax, else nothing:
// every method gets identical hits (tests/intersectors/test_phantom_tmax.cpp).
//
// What this program is not (measured in tests/test_intersect_phantom_paper.cpp):
// the tube is open at both ends (cross-sections, no end spheres); only entry
// roots count, so a ray starting inside the tube misses it; the search is
// local, so it may settle on a farther crossing or none; and the cylinder
// (radius: the larger distance of B(1/3), B(2/3) from the chord, plus r) does
// not always contain a curved curve (an arc bulges 3/4 of its control
// offset at t = 1/2, the cylinder covers 2/3), so it rejects some hits.
// Done in double like the bracketed program (span.h explains why).
#pragma once

#include "core/events.h"
#include "intersectors/bezier.h"
#include "intersectors/hit.h"
#include "intersectors/phantom_curve.h"
#include "intersectors/span.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace rtc {

namespace detail {

inline constexpr double kReshetovEpsilon = 5e-5;  // |dt| at convergence (paper, section 4)
inline constexpr double kReshetovMaxStep = 0.5;   // |dt| clamp per iteration

// Does the ray's [tmin, infinity) meet the capped cylinder around the chord
// P0-P3 (radius: the larger distance of B(1/3) and B(2/3) from the chord line,
// plus the largest radius; extended by that radius beyond both ends)? A
// chord of zero length has no axis: a sphere around P0 through the farthest
// control point, grown by the radius, stands in.
[[nodiscard]] inline bool reshetov_cylinder(const PhantomCurve& pc, const Ray& ray, double rmax) {
    const std::array<DVec3, 4> p = {DVec3(pc.cp[0]), DVec3(pc.cp[1]), DVec3(pc.cp[2]), DVec3(pc.cp[3])};
    const DVec3 o(ray.origin), d(ray.direction), oc = o - p[0];
    double lo = ray.tmin, hi = kDInf;  // not tmax: see the top
    const DVec3 axis = p[3] - p[0];
    const double len = glm::length(axis);
    DVec3 w(0.0);
    double R = 0.0;
    if (len > 0.0) {
        w = axis / len;
        for (const double u : {1.0 / 3.0, 2.0 / 3.0}) {
            const DVec3 v = bezier(p, u) - p[0];
            R = std::max(R, glm::length(v - glm::dot(v, w) * w));
        }
        // Slab between the caps: axial coordinate in [-rmax, len + rmax].
        const double y0 = glm::dot(oc, w), dy = glm::dot(d, w);
        if (dy != 0.0) {
            const double ta = (-rmax - y0) / dy, tb = (len + rmax - y0) / dy;
            lo = std::max(lo, std::min(ta, tb)), hi = std::min(hi, std::max(ta, tb));
        } else if (y0 < -rmax || y0 > len + rmax) {
            return false;
        }
    } else {
        for (const DVec3& q : p) R = std::max(R, glm::length(q - p[0]));
    }
    R += rmax;
    // Inside the infinite cylinder (or the sphere: w = 0): |op + t dp|^2 <= R^2.
    const DVec3 op = oc - glm::dot(oc, w) * w, dp = d - glm::dot(d, w) * w;
    const double a = glm::dot(dp, dp), b = glm::dot(op, dp), c = glm::dot(op, op) - R * R;
    if (a > 0.0) {
        const double h = b * b - a * c;
        if (!(h >= 0.0)) return false;
        const double sq = std::sqrt(h);
        lo = std::max(lo, (-b - sq) / a), hi = std::min(hi, (-b + sq) / a);
    } else if (c > 0.0) {
        return false;
    }
    return lo <= hi;
}

struct TangentCone {
    double s = 0.0;     // ray distance of the (phantom) hit, from c.z
    double dt = 0.0;    // its axial offset from c, in curve parameter
    bool real = false;  // the ray meets the cone (else s is the phantom hit)
};

// The ray (z axis) against the cone tangent to the tube at c = B(t) with
// derivative dc (|dc| > 0), radius r and radius derivative dr (see the top).
[[nodiscard]] inline TangentCone tangent_cone(const DVec3& c, const DVec3& dc, double r, double dr) {
    const double L = glm::length(dc);
    const double az = dc.z / L, b = (c.x * dc.x + c.y * dc.y) / L, k = dr / L;
    const double rho = r - k * b;
    const double alpha = 1.0 - az * az * (1.0 + k * k);
    const double beta = az * (b - k * rho);
    const double gamma = c.x * c.x + c.y * c.y - b * b - rho * rho;
    TangentCone cone;
    if (alpha > 1e-12) {  // else the ray runs along the axis: aim at c itself (s = 0)
        const double disc = beta * beta - alpha * gamma;
        cone.real = disc >= 0.0;
        cone.s = (-beta - (cone.real ? std::sqrt(disc) : 0.0)) / alpha;
    }
    cone.dt = (az * cone.s - b) / L;
    return cone;
}

// Unit outward normal of that cone at ray distance s from c.z (in the frame).
[[nodiscard]] inline DVec3 tangent_cone_normal(const DVec3& c, const DVec3& dc, double dr, double s) {
    const double L = glm::length(dc);
    const DVec3 a = dc / L, w(-c.x, -c.y, s);
    const DVec3 radial = w - glm::dot(w, a) * a;
    const double rl = glm::length(radial);
    return (rl > 0.0 ? radial / rl : DVec3(0.0)) - (dr / L) * a;
}

struct ReshetovHit {
    double s = 0.0;  // distance along the unit ray direction
    double u = 0.0;  // curve parameter
    DVec3 normal{0.0};
};

// One search from curve end `t` (0 or 1) for a hit at s >= smin (no upper
// bound: see the top); adds its iterations to `iterations`.
[[nodiscard]] inline std::optional<ReshetovHit> reshetov_search(
    const RccCurve& c, double t, double smin, int max_iterations,
    std::uint32_t& iterations) {
    double t_prev = t, dt_prev = 0.0, dt_last = 0.0;
    for (int i = 0; i < max_iterations; ++i) {
        ++iterations;
        const DVec3 p = bezier(c.q, t);
        DVec3 dp = bezier_derivative(c.q, t);
        if (!(glm::dot(dp, dp) > 0.0)) {  // a zero end tangent: the direction of a short chord
            dp = (bezier(c.q, std::min(t + 1e-3, 1.0)) - bezier(c.q, std::max(t - 1e-3, 0.0))) * 500.0;
            if (!(glm::dot(dp, dp) > 0.0)) return std::nullopt;  // the curve is a point: no tube
        }
        const double dr = bezier_derivative(c.r, t);
        const TangentCone cone = tangent_cone(p, dp, bezier(c.r, t), dr);
        if (cone.real && std::abs(cone.dt) < kReshetovEpsilon) {
            const double s = p.z + cone.s;
            if (!(s >= smin)) return std::nullopt;
            return ReshetovHit{s, t, tangent_cone_normal(p, dp, dr, cone.s)};
        }
        const double dt = std::clamp(cone.dt, -kReshetovMaxStep, kReshetovMaxStep);
        dt_prev = dt_last, dt_last = dt;
        double t_next = t + dt;
        if (dt_prev * dt_last < 0.0)  // the root lies between the last two t: regula falsi
            t_next = i % 4 == 0 ? 0.5 * (t_prev + t)
                                : (dt_last * t_prev - dt_prev * t) / (dt_last - dt_prev);
        t_prev = t, t = t_next;
        if (!(t >= 0.0 && t <= 1.0)) return std::nullopt;  // off the curve (or NaN)
    }
    return std::nullopt;
}

// The paper program's own operations (conventions: core/ops.h).
// The capped bounding cylinder: oc and the axis (6), its length (3 and a
// sqrt) and test, w (a reciprocal, 3), its radius from B(1/3) and B(2/3)
// (2 x 28 with a sqrt each), the cap slab (10, a reciprocal, a branch), R
// (1), the infinite cylinder (op and dp 18, a, b, c 11, h 2, its tests, a
// sqrt, the span 4 and a reciprocal), the final compare.
inline constexpr Ops kReshetovCylinder{.fma = 118, .div = 4, .sqrt = 4, .branch = 6};
// The frame's extras: smin (1; no smax, the search ignores tmax), which end
// the ray meets first (a compare).
inline constexpr Ops kReshetovSetup = kPhantomSetup + Ops{.fma = 1, .branch = 1};
// One iteration: B(t) (18), B'(t) (12), |B'|^2 (3) and its test, r and r' (12);
// the tangent cone (|B'| 3 and a sqrt, its reciprocal, az, b, k, rho, alpha,
// beta, gamma 20, a test, the discriminant 2 and a sqrt, s 2 and a division,
// dt 2); the convergence test (3, 2 branches), the clamp (2), the sign test
// (1, a branch), the step (1), the range test (2 branches), the loop's branch.
inline constexpr Ops kReshetovIteration{.fma = 79, .div = 2, .sqrt = 2, .branch = 8};
// The restart from the other end: t = 1 - t (1), the loop's branch.
inline constexpr Ops kReshetovSecondEnd{.fma = 2, .branch = 1};
// A hit: its range tests (2), the cone's normal (26, 3 reciprocals, 2 sqrts),
// then kPhantomReport.
inline constexpr Ops kReshetovHit = kPhantomReport + Ops{.fma = 26, .div = 3, .sqrt = 2, .branch = 2};

}  // namespace detail

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect_reshetov(const PhantomCurve& pc, const Ray& ray,
                                                    Sink& sink, const PhantomOptions& opt) {
    sink.on(Event::IsPhantom);
    count_ops(sink, detail::kPhantomEntry);
    if (!is_finite(pc) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
    const double rmax = max_radius(pc);
    if (!(glm::length(DVec3(ray.direction)) > 0.0) || !(rmax > 0.0)) return std::nullopt;
    if (opt.early_out) {
        sink.on(Event::PhantomCylinderTest);
        count_ops(sink, detail::kReshetovCylinder);
        if (!detail::reshetov_cylinder(pc, ray, rmax)) return std::nullopt;
    }
    sink.on(Event::PhantomSetup);
    count_ops(sink, detail::kReshetovSetup);
    const detail::RccCurve rcc = detail::to_ray_frame(pc, ray);
    const double smin = double(ray.tmin) * rcc.dlen;
    // Start at the end the ray meets first; on failure retry from the other.
    double start = rcc.q[3].z - rcc.q[0].z > 0.0 ? 0.0 : 1.0;
    std::uint32_t iterations = 0;
    std::optional<detail::ReshetovHit> hit;
    for (int end = 0; end < 2 && !hit; ++end, start = 1.0 - start) {
        if (end == 1) {
            sink.on(Event::PhantomSecondEnd);
            count_ops(sink, detail::kReshetovSecondEnd);
        }
        hit = detail::reshetov_search(rcc, start, smin, opt.paper_max_iterations, iterations);
    }
    sink.add(Event::PhantomPaperIteration, iterations);
    count_ops(sink, detail::kReshetovIteration, iterations);
    if (!hit) return std::nullopt;
    count_ops(sink, detail::kReshetovHit);
    const float t = static_cast<float>(hit->s / rcc.dlen);
    if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;
    return Hit{t, detail::from_ray_frame(rcc, hit->normal, ray), static_cast<float>(hit->u)};
}

}  // namespace rtc
