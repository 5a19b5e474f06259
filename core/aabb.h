// Axis-aligned bounding box and the ray/box slab test the hardware performs.
#pragma once

#include "core/float_step.h"
#include "core/ray.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtc {

struct Aabb {
    // An empty box (lo > hi) so that extending it by anything yields that thing.
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    [[nodiscard]] static Aabb from_point(const Vec3& p) { return {p, p}; }

    void extend(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    [[nodiscard]] bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    [[nodiscard]] Vec3 extent() const { return hi - lo; }
    [[nodiscard]] Vec3 center() const { return 0.5f * (lo + hi); }
    [[nodiscard]] float surface_area() const {
        if (empty()) return 0.0f;
        const Vec3 e = extent();
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
    [[nodiscard]] bool contains(const Vec3& p) const {
        return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y &&
               p.z <= hi.z;
    }
    [[nodiscard]] bool contains(const Aabb& b) const { return contains(b.lo) && contains(b.hi); }
    [[nodiscard]] bool finite() const {
        return std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(lo.z) &&
               std::isfinite(hi.x) && std::isfinite(hi.y) && std::isfinite(hi.z);
    }
};

// Bounds of the exact box [lo, hi] (computed in double from float inputs,
// a few double roundings at most) as the smallest float box around it: both
// ends widened by 2^-48 of the larger magnitude (far more than those
// roundings, far less than a float ulp) and rounded outward.
[[nodiscard]] inline Aabb outward_bounds(const DVec3& lo, const DVec3& hi) {
    Aabb b;
    for (int i = 0; i < 3; ++i) {
        if (!(lo[i] <= hi[i])) return {};  // NaN or empty
        const double m = std::max(std::abs(lo[i]), std::abs(hi[i])) * 0x1p-48;
        const double l = lo[i] - m, h = hi[i] + m;
        b.lo[i] = static_cast<float>(l);
        b.hi[i] = static_cast<float>(h);
        if (double(b.lo[i]) > l) b.lo[i] = float_step_down(b.lo[i]);
        if (double(b.hi[i]) < h) b.hi[i] = float_step_up(b.hi[i]);
    }
    return b;
}

[[nodiscard]] inline Aabb merge(Aabb a, const Aabb& b) {
    a.extend(b);
    return a;
}

// Slab test with a precomputed safe reciprocal direction. Returns the entry
// distance, or +inf when the ray misses the box within [tmin, tmax]. The
// interval is closed at both ends so that a hit exactly at tmax is still found
// (closest-hit ties are broken by primitive index, see core/hit_record.h).
inline constexpr float kSlabPad = 1.0f + 4.0f * std::numeric_limits<float>::epsilon();

[[nodiscard]] inline float intersect_box(const Aabb& box, const Vec3& origin, const Vec3& inv_dir,
                                         float tmin, float tmax) {
    const float tx0 = (box.lo.x - origin.x) * inv_dir.x, tx1 = (box.hi.x - origin.x) * inv_dir.x;
    const float ty0 = (box.lo.y - origin.y) * inv_dir.y, ty1 = (box.hi.y - origin.y) * inv_dir.y;
    const float tz0 = (box.lo.z - origin.z) * inv_dir.z, tz1 = (box.hi.z - origin.z) * inv_dir.z;
    const float tnear = std::max(std::max(std::min(tx0, tx1), std::min(ty0, ty1)),
                                 std::max(std::min(tz0, tz1), tmin));
    const float tfar = std::min(std::min(std::max(tx0, tx1), std::max(ty0, ty1)),
                                std::min(std::max(tz0, tz1), tmax));
    // Scaling tfar up by a few ulps makes the test conservative against the
    // rounding of the six products (Ize 2013, "Robust BVH Ray Traversal").
    return tnear <= tfar * kSlabPad ? tnear : kInfinity;
}

}  // namespace rtc
