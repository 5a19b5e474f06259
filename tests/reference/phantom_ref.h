// Reference for the phantom curve (tests only): the sweep of spheres along the
// Bezier approximated by a chain of links (each the exact sweep of a sphere
// along a chord with linear radius) in long double. Two levels keep it cheap
// and fine: 64 coarse links, grown by a bound on the chord's sag (|B''| h^2/8
// for the centre and the radius), cull; a coarse link the ray meets is
// replaced by 64 fine links (4096 over the curve: sag ~ 1e-8 of the curvature
// radius, below the 1e-3 r tolerance for length/radius up to 10^4).
#pragma once

#include "intersectors/phantom.h"
#include "straight_ref.h"

namespace rtc::ref {

inline V3 bez(const PhantomCurve& c, Real t) {
    const Real s = 1 - t;
    V3 p{0, 0, 0};
    const Real w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
    for (int i = 0; i < 4; ++i) p = p + w[i] * v3(c.cp[i]);
    return p;
}
inline Real bez_r(const PhantomCurve& c, Real t, Real scale) {
    const Real s = 1 - t;
    return scale * (s * s * s * c.radius[0] + 3 * s * s * t * c.radius[1] +
                    3 * s * t * t * c.radius[2] + t * t * t * c.radius[3]);
}

// Nearest hit distance (ray units) at or after tmin of the chain, radii scaled.
inline std::optional<Real> phantom_chain(const PhantomCurve& c, const Ray& ray, Real scale = 1) {
    const V3 o = v3(ray.origin), d = v3(ray.direction);
    constexpr int kCoarse = 64, kFine = 64;
    Real m2 = 0, mr2 = 0;
    for (int i = 0; i < 2; ++i) {
        const V3 dd = v3(c.cp[i + 2]) - 2 * v3(c.cp[i + 1]) + v3(c.cp[i]);
        m2 = std::max(m2, std::sqrt(dot(dd, dd)));
        mr2 = std::max(mr2, std::abs(Real(c.radius[i + 2]) - 2 * c.radius[i + 1] + c.radius[i]));
    }
    const Real h = Real(1) / kCoarse;
    const Real grow = 1.5L * 6 * (m2 + scale * mr2) * h * h / 8 + 1e-12L;
    std::optional<Real> best;
    auto consider = [&](const Interval& iv) {
        const auto t = nearest(iv, ray.tmin);
        if (t && (!best || *t < *best)) best = t;
    };
    for (int i = 0; i < kCoarse; ++i) {
        const Real t0 = i * h, t1 = (i + 1) * h;
        const Interval coarse = link(o, d, bez(c, t0), bez_r(c, t0, scale) + grow, bez(c, t1),
                                     bez_r(c, t1, scale) + grow);
        if (coarse.empty() || (best && coarse.lo > *best)) continue;
        for (int j = 0; j < kFine; ++j) {
            const Real a = t0 + j * h / kFine, b = t0 + (j + 1) * h / kFine;
            consider(link(o, d, bez(c, a), bez_r(c, a, scale), bez(c, b), bez_r(c, b, scale)));
        }
    }
    return best;
}

}  // namespace rtc::ref
