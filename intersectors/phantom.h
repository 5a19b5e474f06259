// The bracketed phantom program: this project's variant of Reshetov & Luebke
// 2018, "Phantom Ray-Hair Intersector" (Proc. ACM CGIT 1(2), HPG 2018), for
// the cubic Bezier swept by a sphere whose radius is the cubic Bezier of the
// four radius values (phantom_curve.h). The paper's own program is in
// phantom_reshetov.h; `intersect` runs the one PhantomOptions selects.
//
// Derivation. Work in the ray-centric frame (RCC): origin at the ray origin,
// z along the unit ray direction, x and y from a Duff et al. basis, so the ray
// is the z axis and s (distance along it) = t |d|. Near curve parameter t the
// swept surface is approximated by the cone enveloping the spheres along the
// tangent line: centre c = B(t), unit axis a = B'(t)/|B'(t)|, radius
// r(zeta) = r + k zeta with slope k = r'(t)/|B'(t)|. As for the link, the
// envelope has radius (r + k zeta)/sqrt(1 - k^2) and touches the sphere
// centred at axial zeta_c at axial zeta_c - k (r + k zeta_c). Each iteration
// intersects the ray with that cone (a quadratic in s), finds which sphere
// centre zeta_c the hit point belongs to and moves t by zeta_c / |B'(t)|
// (when the ray misses the cone, t moves down g(t) = x^2 + y^2 - r^2, which
// is <= 0 exactly where sphere t meets the ray, the z axis). Converged when
// |zeta_c| <= 1e-6 r; a secant step on zeta_c/|B'| replaces the plain step
// once two iterates exist (rays running along the tube make the plain step
// oscillate slowly).
//
// The iteration is local, so where it starts decides which crossing it finds.
// Reshetov starts at t = 0 and t = 1; a ray crossing the tube twice or passing
// near a tip can then settle on the farther crossing or none. Instead the
// curve is cut into kPhantomBrackets sub-curves, each bounded by a capsule
// around its chord grown by the chord's sag (h^2/8 max|B''| for the centre,
// h^2/8 max(-r'') for the radius: B'' and r'' are linear, so their extremes
// are at the sub-curve's ends). The capsule entry is a lower bound on any
// crossing of that sub-curve, so sub-curves are searched nearest bound first,
// each search confined to its parameter range and started at the chord point
// nearest the capsule entry, and the rest are skipped once a hit is nearer
// than their bound (within 1e-5 r). A search that finds nothing in a capsule
// the ray enters is retried on the two halves (kPhantomSplits levels): the
// ray may run along a curly sub-curve with several local minima of g. The
// two end spheres close the sweep (the shape is the union of the spheres,
// as the reference's link chain is) and let consecutive segments join.
// Reshetov's early out tests the ray against a cylinder around the chord
// P0-P3 bounding the curve (convex hull property).
// Done in double for the same reason as span.h.
#pragma once

#include "core/events.h"
#include "core/obb.h"
#include "intersectors/bezier.h"
#include "intersectors/span.h"
#include "intersectors/frame.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"
#include "intersectors/phantom_curve.h"
#include "intersectors/phantom_reshetov.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace rtc {

namespace detail {

inline constexpr int kPhantomBrackets = 4;  // sub-curves searched separately (see intersect)
inline constexpr int kPhantomSplits = 3;    // halvings of a bracket whose search found nothing

struct PhantomCandidate {
    double s = kDInf;  // distance along the unit ray direction
    double u = 0.0;    // curve parameter
    DVec3 normal{0.0}; // in the ray-centric frame
};

// Entry (or, from inside, exit) of the sphere (m, r) along the z axis.
inline void sphere_candidate(const DVec3& m, double r, double u, double smin,
                             PhantomCandidate& best) {
    const double h = r * r - (m.x * m.x + m.y * m.y);
    if (!(r > 0.0) || !(h >= 0.0)) return;
    const double half = std::sqrt(h);
    double s = m.z - half;
    if (!(s >= smin)) s = m.z + half;
    if (!(s >= smin) || !(s < best.s)) return;
    best = {s, u, DVec3(0.0, 0.0, s) - m};
}

// One root search from parameter t, kept inside [t_lo, t_hi] (its bracket);
// returns the number of iterations run.
inline int phantom_search(const std::array<DVec3, 4>& q, const std::array<double, 4>& rr,
                          double t, double t_lo, double t_hi, double smin, int max_iterations,
                          PhantomCandidate& best) {
    int it = 0;
    double t_prev = t, f_prev = 0.0;
    bool have_prev = false;
    while (it < max_iterations) {
        ++it;
        const DVec3 c = bezier(q, t);
        DVec3 dc = bezier_derivative(q, t);
        double dcl2 = glm::dot(dc, dc);
        if (!(dcl2 > 0.0)) {  // coincident control points: use a short chord
            dc = (bezier(q, std::min(t + 1e-3, 1.0)) - bezier(q, std::max(t - 1e-3, 0.0))) * 500.0;
            dcl2 = glm::dot(dc, dc);
            if (!(dcl2 > 0.0)) return it;  // the curve is a point: end spheres cover it
        }
        const double dcl = std::sqrt(dcl2);
        const DVec3 a = dc / dcl;
        const double r = std::max(bezier(rr, t), 0.0);
        const double k = std::clamp(bezier_derivative(rr, t) / dcl, -0.999, 0.999);
        const double nk = std::sqrt((1.0 - k) * (1.0 + k));
        const double ca = glm::dot(c, a);
        const DVec3 cp = c - ca * a;  // c minus its axial part: no |c|^2 cancellation
        const double rho0 = (r - k * ca) / nk, rho1 = k * a.z / nk;
        const double qa = a.x * a.x + a.y * a.y - rho1 * rho1;
        const double qb = -cp.z - rho0 * rho1;
        const double qc = glm::dot(cp, cp) - rho0 * rho0;
        const double h = qb * qb - qa * qc;
        bool on_cone = false;
        double s = 0.0;
        if (qa > 1e-12 && h >= 0.0) {
            const double sq = std::sqrt(h);
            s = (-qb - sq) / qa;
            if (!(s >= smin)) s = (-qb + sq) / qa;
            on_cone = s >= smin;
        }
        if (!on_cone) {
            // Off the local cone: move towards the sphere that comes nearest to
            // being hit, i.e. down g(t) = x^2 + y^2 - r^2 (the ray is the z
            // axis, so sphere t is hit iff g(t) <= 0). Newton on g' where g is
            // convex, else a fixed downhill step: aiming at the ray's closest
            // approach instead can settle on a local maximum of the distance
            // or ignore the radius.
            const DVec3 ddc = bezier_second_derivative(q, t);
            const double dr = bezier_derivative(rr, t), ddr = bezier_second_derivative(rr, t);
            const double g1 = c.x * dc.x + c.y * dc.y - r * dr;
            const double g2 = dc.x * dc.x + dc.y * dc.y + c.x * ddc.x + c.y * ddc.y - dr * dr - r * ddr;
            const double step = 0.25 * (t_hi - t_lo);
            const double dt = g2 > 0.0 ? std::clamp(-g1 / g2, -step, step) : (g1 > 0.0 ? -step : step);
            if (std::abs(dt) * dcl <= 1e-6 * r) return it;  // nearest sphere still missed
            const double t_new = std::clamp(t + dt, t_lo, t_hi);
            if (t_new == t) return it;
            t = t_new, have_prev = false;
            continue;
        }
        const double zeta = s * a.z - ca;
        const double zeta_c = (zeta + k * r) / (1.0 - k * k);
        const double t_raw = t + zeta_c / dcl;
        if (std::abs(zeta_c) <= 1e-6 * r) {
            if (t_raw >= 0.0 && t_raw <= 1.0 && s < best.s) {
                const DVec3 radial = DVec3(0.0, 0.0, s) - c - zeta * a;
                const double rl = glm::length(radial);
                const DVec3 n = (rl > 0.0 ? nk * radial / rl : DVec3(0.0)) - k * a;
                best = {s, t_raw, n};
            }
            return it;
        }
        // The plain step t + zeta_c/|B'| oscillates slowly when the ray runs
        // nearly along the tube (contraction ~ -0.7 seen): a secant step on
        // the step itself, f(t) = zeta_c/|B'|, converges superlinearly there
        // and is exact where f is linear.
        const double f = zeta_c / dcl;
        double t_next = t_raw;
        if (have_prev && f != f_prev) {
            const double sec = t - f * (t - t_prev) / (f - f_prev);
            if (std::isfinite(sec)) t_next = sec;
        }
        t_prev = t, f_prev = f, have_prev = true;
        const double t_new = std::clamp(t_next, t_lo, t_hi);
        if (t_new == t) return it;  // pushed off the bracket: its neighbour (or end sphere) decides
        t = t_new;
    }
    return it;
}

// Interval [lo, hi] of the z axis (the ray in the ray-centric frame) inside the
// capsule of radius R around segment a-b; false when the axis misses it. Exact
// for the convex capsule: the hull of its end spheres and its body (infinite
// cylinder within the slab between the end planes).
inline bool capsule_z(const DVec3& a, const DVec3& b, double R, double& lo, double& hi) {
    lo = kDInf, hi = -kDInf;
    for (const DVec3& m : {a, b}) {
        const double h = R * R - (m.x * m.x + m.y * m.y);
        if (h >= 0.0) {
            const double half = std::sqrt(h);
            lo = std::min(lo, m.z - half), hi = std::max(hi, m.z + half);
        }
    }
    const DVec3 w = b - a;
    const double len = glm::length(w);
    const double sin2 = (w.x * w.x + w.y * w.y) / (len * len);
    if (len > 0.0 && sin2 > 1e-14) {  // (a ray along the axis meets the body only between the spheres)
        const DVec3 wn = w / len;
        const DVec3 m = -a;                             // ray point at s = 0, from a
        const double y0 = glm::dot(m, wn);              // its axial coordinate
        const DVec3 mp = m - y0 * wn;                   // its offset from the axis
        const DVec3 ep = DVec3(0.0, 0.0, 1.0) - wn.z * wn;  // offset per unit s
        const double qb = glm::dot(mp, ep), qc = glm::dot(mp, mp) - R * R;
        const double h = qb * qb - sin2 * qc;
        if (h >= 0.0) {
            const double sq = std::sqrt(h);
            double b0 = (-qb - sq) / sin2, b1 = (-qb + sq) / sin2;
            if (wn.z != 0.0) {
                const double z0 = -y0 / wn.z, z1 = (len - y0) / wn.z;
                b0 = std::max(b0, std::min(z0, z1)), b1 = std::min(b1, std::max(z0, z1));
            } else if (y0 < 0.0 || y0 > len) {
                b0 = kDInf, b1 = -kDInf;
            }
            if (b0 <= b1) lo = std::min(lo, b0), hi = std::max(hi, b1);
        }
    }
    return lo <= hi;
}

// The bracketed program's own operations (conventions: core/ops.h).
// The bounding-cylinder early out: the axis (3), its length (3 and a sqrt)
// and test, w (a reciprocal, 3), the two inner points' deviations (2 x 16
// with a sqrt each), |e_z x w| (3 and a sqrt), the distance (5 and a
// division), zmax (5), the final compare (3, 2 branches).
inline constexpr Ops kPhantomEarlyOut{.fma = 57, .div = 2, .sqrt = 4, .branch = 4};
// Before the brackets: the end spheres (2 x 10, each a sqrt, a division and
// 3 branches), B'' and r'' at both ends (16), the scale (13) and pad (1).
inline constexpr Ops kPhantomBracketSetup{.fma = 50, .div = 2, .sqrt = 2, .branch = 6};
// One bracket's capsule test: B and r at both ends (2 x 25), the sag bound
// (2 x 10 with a sqrt each, the radius sag 10, grow 4), capsule_z (the end
// spheres 12 with 2 sqrts, the body: w and its length 6 and a sqrt, sin^2 4
// and a division, wn a reciprocal and 3, y0, mp, ep, qb, qc 23, h 3 and a
// sqrt, the roots 4 and 2 divisions, the caps 6 and 2 divisions), its
// tests, and the start point (8 and a division).
inline constexpr Ops kPhantomBracketTest{.fma = 155, .div = 7, .sqrt = 7, .branch = 10};
// One iteration of phantom_search: B (18), B' (12), |B'|^2 (3) and its test,
// |B'| (a sqrt) and its reciprocal, a (3), r and r'/|B'| (14, a division),
// nk (3, a sqrt, a reciprocal), ca and cp (9), rho0, rho1 (5), the quadratic
// (13), its tests (2 branches), the root (2, a sqrt, a division) and its
// test, zeta and zeta_c (6, a division), t_raw (2), the convergence test (a
// branch), the secant step (5, a division, 2 branches), the clamp (2) and the
// test against t.
inline constexpr Ops kPhantomIteration{.fma = 98, .div = 6, .sqrt = 3, .branch = 8};
// A hit: the normal in the frame (radial 6, its length 3 and a sqrt, the
// scale 6 and a reciprocal, - k a 3), then kPhantomReport.
inline constexpr Ops kPhantomHit = kPhantomReport + Ops{.fma = 18, .div = 1, .sqrt = 1};

}  // namespace detail

// Runs the program `opt` selects (see phantom_curve.h).
template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const PhantomCurve& pc, const Ray& ray, Sink& sink,
                                           const PhantomOptions& opt = {}) {
    if (opt.program == PhantomProgram::Paper) return intersect_reshetov(pc, ray, sink, opt);
    sink.on(Event::IsPhantom);
    count_ops(sink, detail::kPhantomEntry);
    if (!is_finite(pc) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
    const double rmax = max_radius(pc);
    if (!(glm::length(DVec3(ray.direction)) > 0.0) || !(rmax > 0.0)) return std::nullopt;

    sink.on(Event::PhantomSetup);
    count_ops(sink, detail::kPhantomSetup);
    const detail::RccCurve rcc = detail::to_ray_frame(pc, ray);
    const std::array<DVec3, 4>& q = rcc.q;
    const std::array<double, 4>& rr = rcc.r;
    const double dlen = rcc.dlen;
    const double smin = double(ray.tmin) * dlen;

    if (opt.early_out) {
        sink.on(Event::PhantomEarlyOut);
        count_ops(sink, detail::kPhantomEarlyOut);
        const DVec3 axis = q[3] - q[0];
        const double len = glm::length(axis);
        double dev = 0.0, dist;
        if (len > 0.0) {
            const DVec3 w = axis / len;
            for (int i = 1; i < 3; ++i) {
                const DVec3 v = q[i] - q[0];
                dev = std::max(dev, glm::length(v - glm::dot(v, w) * w));
            }
            const double nn = std::sqrt(w.x * w.x + w.y * w.y);  // |e_z x w|
            dist = nn > 1e-9 ? std::abs(q[0].x * w.y - q[0].y * w.x) / nn
                             : std::sqrt(q[0].x * q[0].x + q[0].y * q[0].y);
        } else {
            for (int i = 1; i < 4; ++i) dev = std::max(dev, glm::length(q[i] - q[0]));
            dist = std::sqrt(q[0].x * q[0].x + q[0].y * q[0].y);
        }
        const double zmax = std::max({q[0].z, q[1].z, q[2].z, q[3].z}) + rmax;
        if (dist > (dev + rmax) * (1.0 + 1e-9) || zmax < smin) {
            sink.on(Event::PhantomEarlyReject);
            return std::nullopt;
        }
    }

    // Brackets: the curve cut into kPhantomBrackets sub-curves, each inside a
    // capsule around its chord grown by the chord's sag. The capsule entry is
    // a lower bound on any crossing of that sub-curve's sweep, so the
    // brackets are searched nearest first and the rest are skipped once a hit
    // is nearer than their bound (within 1e-5 r): the result is the nearest
    // crossing, not whichever one a search from the ends happens to reach.
    detail::PhantomCandidate best;
    detail::sphere_candidate(q[0], rr[0], 0.0, smin, best);
    detail::sphere_candidate(q[3], rr[3], 1.0, smin, best);
    // B'' and r'' are linear in t, so their extremes on a bracket are at its ends.
    const DVec3 d0 = q[2] - 2.0 * q[1] + q[0], d1 = q[3] - 2.0 * q[2] + q[1];
    const double e0 = rr[2] - 2.0 * rr[1] + rr[0], e1 = rr[3] - 2.0 * rr[2] + rr[1];
    double scale = rmax;
    for (const DVec3& p : q) scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const double pad = 1e-12 * scale;  // rounding of the frame and the Bezier sums
    struct Bracket {
        double lo, t0, t1, t_start;
        int depth;
    };
    // At most kN roots plus two halves per failed search (each split removes one).
    constexpr int kN = detail::kPhantomBrackets, kDepth = detail::kPhantomSplits;
    std::array<Bracket, kN + 2 * kN * kDepth> br;
    int nb = 0;
    std::uint32_t bracket_tests = 0;
    // Capsule test of sub-curve [t0, t1]; pushes it when the ray may meet it.
    auto push = [&](double t0, double t1, int depth) {
        ++bracket_tests;
        const DVec3 pa = bezier(q, t0), pb = bezier(q, t1);
        const double ra = std::max(bezier(rr, t0), 0.0), rb = std::max(bezier(rr, t1), 0.0);
        const double sc = 6.0 * std::max(glm::length((1.0 - t0) * d0 + t0 * d1),
                                         glm::length((1.0 - t1) * d0 + t1 * d1));
        const double sr = 6.0 * std::max({-((1.0 - t0) * e0 + t0 * e1), -((1.0 - t1) * e0 + t1 * e1), 0.0});
        // |B - chord| <= h^2/8 max|B''|, r - chord(r) <= h^2/8 max(-r'').
        const double h = t1 - t0;
        const double grow = h * h / 8.0 * (sc + sr);
        double lo, hi;
        if (!detail::capsule_z(pa, pb, std::max(ra, rb) * (1.0 + 1e-9) + grow + pad, lo, hi) ||
            !(hi >= smin))
            return;
        // Start at the chord point nearest the capsule entry (on the ray).
        const DVec3 w = pb - pa;
        const double w2 = glm::dot(w, w);
        const double u = w2 > 0.0
            ? std::clamp(glm::dot(DVec3(0.0, 0.0, std::max(lo, smin)) - pa, w) / w2, 0.0, 1.0)
            : 0.5;
        br[nb++] = {lo, t0, t1, t0 + u * h, depth};
    };
    for (int i = 0; i < kN; ++i) push(double(i) / kN, double(i + 1) / kN, 0);
    const double eps = 1e-5 * rmax;
    int iterations = 0;
    while (nb > 0) {
        int m = 0;  // nearest bound first (first of equals: deterministic)
        for (int i = 1; i < nb; ++i)
            if (br[i].lo < br[m].lo) m = i;
        const Bracket b = br[m];
        br[m] = br[--nb];
        if (!(b.lo < best.s - eps)) break;
        const double before = best.s;
        iterations += detail::phantom_search(q, rr, b.t_start, b.t0, b.t1, smin,
                                             opt.max_iterations, best);
        // A search that found nothing nearer in a bracket the ray enters may
        // have settled in the wrong one of several local minima (a ray
        // running along a curly curve): halve the bracket and try again.
        if (best.s == before && b.depth < kDepth) {
            const double tm = 0.5 * (b.t0 + b.t1);
            push(b.t0, tm, b.depth + 1);
            push(tm, b.t1, b.depth + 1);
        }
    }
    sink.add(Event::PhantomIteration, static_cast<std::uint32_t>(iterations));
    sink.add(Event::PhantomBracketTest, bracket_tests);
    count_ops(sink, detail::kPhantomBracketSetup);
    count_ops(sink, detail::kPhantomBracketTest, bracket_tests);
    count_ops(sink, detail::kPhantomIteration, static_cast<std::uint32_t>(iterations));

    if (!(best.s < kDInf)) return std::nullopt;
    count_ops(sink, detail::kPhantomHit);
    const float t = static_cast<float>(best.s / dlen);
    if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;
    return Hit{t, detail::from_ray_frame(rcc, best.normal, ray), static_cast<float>(best.u)};
}

}  // namespace rtc

#include "intersectors/phantom_bounds.h"
