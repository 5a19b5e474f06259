// Oriented bounds of a phantom curve (included by phantom.h).
//
// Every box here bounds the control points grown by the largest radius, which
// bounds the swept curve by the convex hull property (the radius Bezier never
// exceeds its largest control value either). Paper (Wald et al. 2020): axis
// from the first to the last control point, box symmetric about that axis and
// widened until every control point fits. Tight: the smallest-area box among
// a few candidate axes (the chord, the inner leg P2-P1, the end tangents and
// the paper box itself, so Tight is never worse than Paper); across the axis
// each candidate is turned towards the control polygon's largest deviation
// (hair segments are nearly planar) and fitted asymmetrically.
#pragma once

#include "intersectors/phantom.h"

namespace rtc {

namespace detail {

struct CurveBox {
    Vec3 center, x, y, z, half;
    [[nodiscard]] float area() const { return half.x * half.y + half.y * half.z + half.z * half.x; }
};

// Fits the control points (grown by r) in the frame (x, y, z) around p0;
// symmetric about the axis through p0 when `symmetric`.
[[nodiscard]] inline CurveBox fit_curve_box(const PhantomCurve& c, const Vec3& x, const Vec3& y,
                                            const Vec3& z, float r, bool symmetric) {
    Vec3 lo(kInfinity), hi(-kInfinity);
    for (const Vec3& p : c.cp) {
        const Vec3 v = p - c.cp[0];
        const Vec3 l(glm::dot(v, x), glm::dot(v, y), glm::dot(v, z));
        lo = glm::min(lo, l);
        hi = glm::max(hi, l);
    }
    if (symmetric) {
        const float mx = std::max(-lo.x, hi.x), my = std::max(-lo.y, hi.y);
        lo.x = -mx, hi.x = mx, lo.y = -my, hi.y = my;
    }
    const Vec3 mid = 0.5f * (lo + hi);
    return {c.cp[0] + mid.x * x + mid.y * y + mid.z * z, x, y, z, 0.5f * (hi - lo) + r};
}

[[nodiscard]] inline Vec3 curve_axis(const PhantomCurve& c, const Vec3& v) {
    const float l = glm::length(v);
    if (l > 0.0f) return v / l;
    // Coincident ends: the farthest control point from P0, else any axis.
    Vec3 far(0.0f);
    for (const Vec3& p : c.cp)
        if (glm::length(p - c.cp[0]) > glm::length(far)) far = p - c.cp[0];
    const float fl = glm::length(far);
    return fl > 0.0f ? far / fl : Vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace detail

[[nodiscard]] inline Obb oriented_bounds(const PhantomCurve& c, ObbVariant v = ObbVariant::Paper) {
    const float r = max_radius(c);
    const Vec3 chord = detail::curve_axis(c, c.cp[3] - c.cp[0]);
    const Basis b = orthonormal_basis(chord);
    detail::CurveBox best = detail::fit_curve_box(c, b.x, b.y, chord, r, true);
    if (v == ObbVariant::Tight) {
        const Vec3 axes[] = {chord, c.cp[2] - c.cp[1], c.cp[1] - c.cp[0], c.cp[3] - c.cp[2],
                             (c.cp[2] + c.cp[3]) - (c.cp[0] + c.cp[1])};
        for (const Vec3& raw : axes) {
            if (!(glm::length(raw) > 0.0f)) continue;
            const Vec3 z = glm::normalize(raw);
            // Across the axis, align x with the largest deviation of the polygon.
            Vec3 dev(0.0f);
            for (const Vec3& p : c.cp) {
                const Vec3 q = p - c.cp[0];
                const Vec3 perp = q - glm::dot(q, z) * z;
                if (glm::dot(perp, perp) > glm::dot(dev, dev)) dev = perp;
            }
            // A deviation that is only rounding noise (a nearly straight
            // curve) can vanish once projected across z: keep the default
            // basis then, so the frame never turns NaN.
            Vec3 x = orthonormal_basis(z).x;
            const Vec3 across = dev - glm::dot(dev, z) * z;
            const float across_len = glm::length(across);
            if (across_len > 0.0f && std::isfinite(across_len)) x = across / across_len;
            const Vec3 y = glm::normalize(glm::cross(z, x));
            if (!std::isfinite(y.x) || !std::isfinite(y.y) || !std::isfinite(y.z)) continue;
            const detail::CurveBox box = detail::fit_curve_box(c, x, y, z, r, false);
            if (box.area() < best.area()) best = box;
        }
    }
    // The chosen frame's half-extents again, exactly (double) against its
    // float centre and axes: the float fit above only chose the frame. Then
    // the hardware's error bound (finish_obb, frame.h).
    const DVec3 center(best.center);
    const DVec3 axes[3] = {DVec3(best.x), DVec3(best.y), DVec3(best.z)};
    DVec3 ext(0.0);
    double reach = 0.0;
    for (const Vec3& p : c.cp) {
        const DVec3 q = DVec3(p) - center;
        for (int i = 0; i < 3; ++i) ext[i] = std::max(ext[i], std::abs(glm::dot(axes[i], q)));
        reach = std::max(reach, glm::length(q));
    }
    for (int i = 0; i < 3; ++i) ext[i] += double(r) * glm::length(axes[i]);
    return finish_obb(best.center, best.x, best.y, best.z, ext, reach + double(r));
}

}  // namespace rtc
