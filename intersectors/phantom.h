// Phantom curve (Reshetov & Luebke 2018, "Phantom Ray-Hair Intersector",
// Proc. ACM CGIT 1(2), HPG 2018): a cubic Bezier swept by a sphere whose
// radius is the cubic Bezier of the four radius values.
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
// (when the ray misses the cone, t moves towards the ray's closest approach to
// the axis instead). Converged when |zeta_c| <= 1e-6 r. Like Reshetov, two
// searches start at t = 0 and t = 1; we add a third from the control-polygon
// sample nearest the ray (curly curves) and the two end spheres, which make
// the sweep closed and let consecutive segments join. The nearest candidate
// not before tmin wins. Reshetov's early out tests the ray against a cylinder
// around the chord P0-P3 bounding the curve (convex hull property).
// Done in double for the same reason as span.h.
#pragma once

#include "core/events.h"
#include "core/obb.h"
#include "intersectors/bezier.h"
#include "intersectors/span.h"
#include "intersectors/frame.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace rtc {

struct PhantomCurve {
    std::array<Vec3, 4> cp{};        // Bezier control points
    std::array<float, 4> radius{};   // radius as a cubic Bezier in the same parameter
};

struct PhantomOptions {
    bool early_out = true;   // Reshetov's bounding-cylinder test before iterating
    int max_iterations = 24; // per search start (the HPG 2018 listings cap a few tens)
};

[[nodiscard]] inline bool is_finite(const PhantomCurve& c) {
    for (int i = 0; i < 4; ++i)
        if (!is_finite(c.cp[i]) || !std::isfinite(c.radius[i])) return false;
    return true;
}

[[nodiscard]] inline float max_radius(const PhantomCurve& c) {
    return std::max({c.radius[0], c.radius[1], c.radius[2], c.radius[3], 0.0f});
}

// Control-polygon hull grown by the largest radius (convex hull property).
[[nodiscard]] inline Aabb bounds(const PhantomCurve& c) {
    Aabb b;
    for (const Vec3& p : c.cp) b.extend(p);
    const float r = max_radius(c);
    return padded_bounds({b.lo - r, b.hi + r});
}

namespace detail {

struct DBasis {
    DVec3 x, y;
};
[[nodiscard]] inline DBasis dbasis(const DVec3& n) {  // Duff et al. 2017, in double
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    return {DVec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            DVec3(b, sign + n.y * n.y * a, -n.y)};
}

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

// One root search from parameter t; returns the number of iterations run.
inline int phantom_search(const std::array<DVec3, 4>& q, const std::array<double, 4>& rr,
                          double t, double smin, int max_iterations, PhantomCandidate& best) {
    int it = 0;
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
        if (!on_cone) {  // aim at the ray's closest approach to the tangent line
            const double sin2 = a.x * a.x + a.y * a.y;
            s = sin2 > 1e-12 ? cp.z / sin2 : c.z;
        }
        const double zeta = s * a.z - ca;
        const double zeta_c = on_cone ? (zeta + k * r) / (1.0 - k * k) : zeta;
        const double t_raw = t + zeta_c / dcl;
        if (on_cone && std::abs(zeta_c) <= 1e-6 * r) {
            if (t_raw >= 0.0 && t_raw <= 1.0 && s < best.s) {
                const DVec3 radial = DVec3(0.0, 0.0, s) - c - zeta * a;
                const double rl = glm::length(radial);
                const DVec3 n = (rl > 0.0 ? nk * radial / rl : DVec3(0.0)) - k * a;
                best = {s, t_raw, n};
            }
            return it;
        }
        const double t_new = std::clamp(t_raw, 0.0, 1.0);
        if (t_new == t) return it;  // pushed off an end: the end sphere decides there
        t = t_new;
    }
    return it;
}

}  // namespace detail

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const PhantomCurve& pc, const Ray& ray, Sink& sink,
                                           const PhantomOptions& opt = {}) {
    sink.on(Event::IsPhantom);
    if (!is_finite(pc) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
    const DVec3 d(ray.direction);
    const double dlen = glm::length(d);
    const double rmax = max_radius(pc);
    if (!(dlen > 0.0) || !(rmax > 0.0)) return std::nullopt;

    // Ray-centric frame.
    const DVec3 e = d / dlen;
    const detail::DBasis xy = detail::dbasis(e);
    const DVec3 o(ray.origin);
    std::array<DVec3, 4> q;
    std::array<double, 4> rr;
    for (int i = 0; i < 4; ++i) {
        const DVec3 v = DVec3(pc.cp[i]) - o;
        q[i] = DVec3(glm::dot(v, xy.x), glm::dot(v, xy.y), glm::dot(v, e));
        rr[i] = std::max(double(pc.radius[i]), 0.0);
    }
    const double smin = double(ray.tmin) * dlen;

    if (opt.early_out) {
        sink.on(Event::PhantomEarlyOut);
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

    detail::PhantomCandidate best;
    detail::sphere_candidate(q[0], rr[0], 0.0, smin, best);
    detail::sphere_candidate(q[3], rr[3], 1.0, smin, best);
    int iterations = detail::phantom_search(q, rr, 0.0, smin, opt.max_iterations, best);
    iterations += detail::phantom_search(q, rr, 1.0, smin, opt.max_iterations, best);
    // Third start: the control-polygon sample nearest the ray (curly curves
    // can hold a hit far from both ends that neither end search reaches).
    double t_near = 0.5, d_near = kDInf;
    for (int i = 1; i < 8; ++i) {
        const DVec3 p = bezier(q, i / 8.0);
        const double dist2 = p.x * p.x + p.y * p.y;
        if (dist2 < d_near) d_near = dist2, t_near = i / 8.0;
    }
    iterations += detail::phantom_search(q, rr, t_near, smin, opt.max_iterations, best);
    sink.add(Event::PhantomIteration, static_cast<std::uint32_t>(iterations));

    if (!(best.s < kDInf)) return std::nullopt;
    const float t = static_cast<float>(best.s / dlen);
    if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;
    const DVec3 n = best.normal.x * xy.x + best.normal.y * xy.y + best.normal.z * e;
    const double nl = glm::length(n);
    const Vec3 normal = nl > 0.0 ? Vec3(n / nl) : Vec3(-ray.direction / float(dlen));
    return Hit{t, normal, static_cast<float>(best.u)};
}

}  // namespace rtc

#include "intersectors/phantom_bounds.h"
