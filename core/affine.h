// Affine 3x4 transform (a linear 3x3 part and a translation), the transform
// an RT core applies to a ray at an instance. Named by what it maps:
// `world_from_object` takes object-space points to world space, its inverse is
// `object_from_world` (pbrt-v4 naming).
#pragma once

#include "core/aabb.h"

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <algorithm>
#include <cmath>
#include <optional>

namespace rtc {

struct Affine {
    glm::mat3 linear{1.0f};  // column-major: linear[c] is the image of axis c
    Vec3 translation{0.0f};

    [[nodiscard]] static Affine identity() { return {}; }
    [[nodiscard]] static Affine translate(const Vec3& t) { return {glm::mat3(1.0f), t}; }
    [[nodiscard]] static Affine scale(const Vec3& s) {
        glm::mat3 m(1.0f);
        m[0][0] = s.x, m[1][1] = s.y, m[2][2] = s.z;
        return {m, Vec3(0.0f)};
    }
    // Columns are the images of the object axes; `origin` the image of 0.
    [[nodiscard]] static Affine from_columns(const Vec3& x, const Vec3& y, const Vec3& z,
                                             const Vec3& origin) {
        return {glm::mat3(x, y, z), origin};
    }

    [[nodiscard]] Vec3 point(const Vec3& p) const { return linear * p + translation; }
    [[nodiscard]] Vec3 vector(const Vec3& v) const { return linear * v; }
    [[nodiscard, gnu::always_inline]] Ray ray(const Ray& r) const {
        return {point(r.origin), r.tmin, vector(r.direction), r.tmax};
    }

    // The inverse, or nothing when the linear part is singular or not finite.
    [[nodiscard]] std::optional<Affine> inverse() const {
        const float det = glm::determinant(linear);
        if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) return std::nullopt;
        const glm::mat3 inv = glm::inverse(linear);
        return Affine{inv, -(inv * translation)};
    }
    // The float box around the exact image of `b` (a TLAS box must hold all
    // of its instance's box): the corners in double, widened by 2^-48 of
    // their magnitude for the double roundings and rounded outward, so at
    // most an ulp of the position wider than the image.
    [[nodiscard]] Aabb box(const Aabb& b) const {
        if (b.empty()) return {};
        // The lowest and highest corner per axis without visiting the eight:
        // a corner's coordinate is ((m0 p0 + m1 p1) + m2 p2) + t, each sum
        // rounded, and a rounded sum never falls when a term rises, so the
        // corner of each term's smaller product is the lowest (and the
        // larger, the highest), bit for bit. A zero or non-finite result
        // (where the corners' signed zeros or NaNs could order differently)
        // takes the corners (box_by_corners, tested equal on both paths).
        const glm::dmat3 m(linear);
        const DVec3 t(translation), p0(b.lo), p1(b.hi);
        DVec3 lo, hi;
        for (int i = 0; i < 3; ++i) {
            double l[3], h[3];
            for (int j = 0; j < 3; ++j) {
                const double a = m[j][i] * p0[j], c = m[j][i] * p1[j];
                l[j] = std::min(a, c);
                h[j] = std::max(a, c);
            }
            lo[i] = l[0] + l[1] + l[2] + t[i];
            hi[i] = h[0] + h[1] + h[2] + t[i];
            if (!(std::isfinite(lo[i]) && std::isfinite(hi[i]) && lo[i] != 0.0 && hi[i] != 0.0))
                return box_by_corners(b);
        }
        return outward_bounds(lo, hi);
    }
    // The same from all eight corners, as box() was first written.
    [[nodiscard]] Aabb box_by_corners(const Aabb& b) const {
        if (b.empty()) return {};
        const glm::dmat3 m(linear);
        const DVec3 t(translation);
        DVec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
        for (int corner = 0; corner < 8; ++corner) {
            const DVec3 p{(corner & 1) ? b.hi.x : b.lo.x, (corner & 2) ? b.hi.y : b.lo.y,
                          (corner & 4) ? b.hi.z : b.lo.z};
            const DVec3 q = m * p + t;
            lo = glm::min(lo, q), hi = glm::max(hi, q);
        }
        return outward_bounds(lo, hi);
    }
};

// An affine map evaluated about a point: linear * (p - origin). This is how
// the modelled hardware applies an instance's object_from_world: the ray
// origin is taken relative to the instance's own origin (`origin`, the world
// image of object-space 0) before the rotation and scale, so the rounding of
// the transform scales with the ray's distance from the instance, not with
// the instance's distance from the world origin (a translation applied after
// the 3x3 product, linear * p + translation, rounds at the magnitude of
// linear * p: for a radius-0.01 box 1e3 from the origin that is ~0.4 % of
// the box per operation). Mathematically the same map as
// Affine{linear, -(linear * origin)}.
struct CentredAffine {
    glm::mat3 linear{1.0f};
    Vec3 origin{0.0f};

    [[nodiscard]] Vec3 point(const Vec3& p) const { return linear * (p - origin); }
    [[nodiscard]] Vec3 vector(const Vec3& v) const { return linear * v; }
    [[nodiscard, gnu::always_inline]] Ray ray(const Ray& r) const {
        return {point(r.origin), r.tmin, vector(r.direction), r.tmax};
    }
};

// The inverse of `a` about a's translation (the world image of 0), or nothing
// when a's linear part is singular or not finite.
[[nodiscard]] inline std::optional<CentredAffine> centred_inverse(const Affine& a) {
    const float det = glm::determinant(a.linear);
    if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) return std::nullopt;
    return CentredAffine{glm::inverse(a.linear), a.translation};
}

[[nodiscard]] inline Affine operator*(const Affine& a, const Affine& b) {
    return {a.linear * b.linear, a.linear * b.translation + a.translation};
}

}  // namespace rtc
