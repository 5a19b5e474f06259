// Shared geometry of the bounding programs: a deterministic orthonormal basis,
// bounds rounded outward from exact (double) values, and the OBB of a segment
// swept by a radius.
//
// The basis follows Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited" (JCGT 6(1)): branch-free except for the sign, continuous away
// from n.z = 0 and deterministic, so the same primitive always yields the same
// OBB.
//
// Padding is the rounding error the float computation can make, not a share
// of the position (which made results move with the scene: issue 38, item 4).
// AABBs are computed in double from the float inputs and rounded outward to
// float: at most one ulp of each coordinate, the least any float box can pay.
// An OBB's centre and axes are rounded to float first; its half-extents are
// then computed exactly (double) against that float centre and those float
// axes, and grown by the error bound of what the hardware does with the box
// (obb_slack below). The hardware applies an instance transform about the
// instance's centre (CentredAffine, core/affine.h), so that bound scales with
// the primitive's size and the ray's distance from it, never with the
// distance from the world origin.
#pragma once

#include "core/float_step.h"
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

// The error bound of an OBB (u = 2^-24, a float's unit roundoff). A surface
// point x at distance |x - c| from the box centre c, reached by a ray at
// parameter t with direction d, lands in the unit box as the hardware
// computes it (core/instance_box.h: L (o - c) and L d in float, then the
// slab test) off its exact unit-box coordinate, per axis i with half-extent
// h_i, by at most
//   (42 u |x - c| + 12 u t |d|) / h_i:
// 8 sqrt(3) u |x - c| for the float axes' departure from orthonormal (the
// extents are exact against the float axes, not against their inverse),
// 12 sqrt(3) u |x - c| for the float inverse L (glm::inverse: cofactors, the
// determinant, its reciprocal), 4 sqrt(3) u (|x - c| + t |d|) for o - c and
// the 3x3 product, 3 sqrt(3) u t |d| for the direction's; the slab test's
// own rounding is covered by kSlabPad (core/aabb.h, Ize 2013). So:
// - kObbSlack = 2^-18 = 64 u of the primitive's reach from the centre is
//   added to every half-extent (absolute, in world units);
// - kObbPad = 2^-10 of each half-extent (Obb::padded; Wald et al. 2020 pad
//   likewise) covers the term in t |d|, i.e. rays that reach the box within
//   about 1,300 half-extents of their origin (13 units for a radius of 0.01).
//   It is the one part of the bound that is not proven for every ray:
//   a ray from farther away is covered by the error's typical size, not
//   its worst case (the padding before this bound had the same limit).
inline constexpr double kObbSlack = 0x1p-18;
inline constexpr float kObbPad = 0x1p-10f;

// A float box around exact half-extents `ext` of a primitive whose points
// lie within `reach` of `center`, on the float axes x, y, z: grown by
// kObbSlack * reach, kept invertible (half-extents of at least 2^-20 of the
// reach and 1e-12, so the determinant stays a normal float), rounded up and
// padded by kObbPad.
[[nodiscard]] inline Obb finish_obb(const Vec3& center, const Vec3& x, const Vec3& y, const Vec3& z,
                                    const DVec3& ext, double reach) {
    const double floor = std::max(reach * 0x1p-20, 1e-12);
    Vec3 half;
    for (int i = 0; i < 3; ++i) {
        const double h = std::max(ext[i] + kObbSlack * reach, floor);
        half[i] = static_cast<float>(h);
        if (double(half[i]) < h) half[i] = float_step_up(half[i]);
    }
    return Obb::from_frame(center, x, y, z, half).padded(kObbPad);
}

// OBB of everything within `radius` of the segment p0-p1, extended by `cap`
// beyond both ends along the axis (radius for round ends, 0 for flat caps).
// The shape lies in the segment extended by cap at both ends, swept by a disk
// of the radius perpendicular to the exact axis n; along a float axis e that
// spans max over both ends |e.(q - c)| + radius |e x n|, computed in double.
[[nodiscard]] inline Obb segment_obb(const Vec3& p0, const Vec3& p1, float radius, float cap) {
    const Vec3 axis = p1 - p0;
    const float len = glm::length(axis);
    const Vec3 w = len > 0.0f ? axis / len : Vec3(0.0f, 0.0f, 1.0f);
    const Basis uv = orthonormal_basis(w);
    const Vec3 center = 0.5f * (p0 + p1);
    const DVec3 c(center), ab = DVec3(p1) - DVec3(p0);
    const double l = glm::length(ab);
    const DVec3 n = l > 0.0 ? ab / l : DVec3(w);
    const DVec3 q0 = DVec3(p0) - c - double(cap) * n, q1 = DVec3(p1) - c + double(cap) * n;
    const double r = radius;
    const Vec3 axes[3] = {uv.x, uv.y, w};
    DVec3 ext;
    for (int i = 0; i < 3; ++i) {
        const DVec3 e(axes[i]);
        ext[i] = std::max(std::abs(glm::dot(e, q0)), std::abs(glm::dot(e, q1))) + r * glm::length(glm::cross(e, n));
    }
    const double reach = std::max(glm::length(q0), glm::length(q1)) + r;
    return finish_obb(center, uv.x, uv.y, w, ext, reach);
}

[[nodiscard]] inline bool is_finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

[[nodiscard]] inline DVec3 to_double(const Vec3& v) { return DVec3(v); }

}  // namespace rtc
