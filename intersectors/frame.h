// Shared geometry of the bounding programs: a deterministic orthonormal basis,
// conservative padding of boxes, and the OBB of a segment swept by a radius.
//
// The basis follows Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited" (JCGT 6(1)): branch-free except for the sign, continuous away
// from n.z = 0 and deterministic, so the same primitive always yields the same
// OBB. Boxes are padded relative to the magnitude of their coordinates (a few
// ulps) so that rounding in the box computation never excludes a surface point;
// OBBs are additionally grown by 2^-10 of each half-extent (Obb::padded) so the
// hardware's world->unit-box ray transform, done in float, never culls a ray
// the intersector reports as a hit (Wald et al. 2020 pad their OBBs likewise).
#pragma once

#include "core/obb.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtc {

struct Basis {
    Vec3 x, y;  // unit vectors perpendicular to n and to each other
};

// Duff et al. 2017, Listing 3 (restated): for unit n, returns x, y with
// (x, y, n) a right-handed orthonormal frame.
[[nodiscard]] inline Basis orthonormal_basis(const Vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
            Vec3(b, sign + n.y * n.y * a, -n.y)};
}

// Relative padding of bounds: 16 ulps of the largest magnitude involved covers
// the handful of roundings in min/max, +/- radius and the OBB corner products.
inline constexpr float kBoundsUlps = 16.0f * std::numeric_limits<float>::epsilon();
inline constexpr float kObbPad = 0x1p-10f;

[[nodiscard]] inline Aabb padded_bounds(Aabb b) {
    if (b.empty()) return b;
    for (int i = 0; i < 3; ++i) {
        const float m = std::max({std::abs(b.lo[i]), std::abs(b.hi[i]), b.hi[i] - b.lo[i]});
        const float pad = m * kBoundsUlps + std::numeric_limits<float>::min();
        b.lo[i] -= pad;
        b.hi[i] += pad;
    }
    return b;
}

// OBB of everything within `radius` of the segment p0-p1, extended by `cap`
// beyond both ends along the axis (radius for round ends, 0 for flat caps).
// Half-extents get a floor so the box stays invertible even for a zero-length,
// zero-radius primitive: 2^-20 of the primitive's size and of its distance
// from the origin (below float resolution there anyway), and 1e-12 absolute so
// the determinant (product of three half-extents) stays a normal float.
[[nodiscard]] inline Obb segment_obb(const Vec3& p0, const Vec3& p1, float radius, float cap) {
    const Vec3 axis = p1 - p0;
    const float len = glm::length(axis);
    const Vec3 w = len > 0.0f ? axis / len : Vec3(0.0f, 0.0f, 1.0f);
    const Basis uv = orthonormal_basis(w);
    const Vec3 center = 0.5f * (p0 + p1);
    const float scale = std::max({len, radius, std::abs(center.x), std::abs(center.y),
                                  std::abs(center.z)});
    const float floor = std::max(scale * 0x1p-20f, 1e-12f);
    // The rounding of p0, p1, the axis and the basis moves surface points by a
    // few ulps of `scale`; cover that absolutely before the relative padding.
    const float slack = scale * kBoundsUlps;
    const float side = std::max(radius + slack, floor);
    const float along = std::max(0.5f * len + cap + slack, floor);
    return Obb::from_frame(center, uv.x, uv.y, w, Vec3(side, side, along)).padded(kObbPad);
}

[[nodiscard]] inline bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

[[nodiscard]] inline DVec3 to_double(const Vec3& v) { return DVec3(v); }

}  // namespace rtc
