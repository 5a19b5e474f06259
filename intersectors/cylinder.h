// Cylinder with flat caps (the synthetic experiment of Wald et al. 2020).
//
// Derivation. The solid cylinder is the intersection of two convex sets: the
// infinite cylinder of radius r around the axis, and the slab 0 <= axial <= L.
// The ray meets each in an interval (span.h); the cylinder's interval is their
// overlap, and whichever of the two bounds an end says whether the hit is on
// the side (radial normal) or a cap (normal +-axis). Solved in double around
// the ray point closest to the centre (span.h). A zero-length cylinder is a
// disc without thickness and is never hit; so is a zero-radius one.
//
// Bounds: the AABB of the two cap discs (each disc spans r * sqrt(1 - w_i^2)
// along axis i); OBB: axis p0-p1 with the exact length (flat caps need no
// extension by r), half-width r across; Tight == Paper.
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

struct Cylinder {
    Vec3 p0{0.0f};
    Vec3 p1{0.0f};
    float radius = 0.0f;
};

[[nodiscard]] inline bool is_finite(const Cylinder& c) {
    return is_finite(c.p0) && is_finite(c.p1) && std::isfinite(c.radius);
}

[[nodiscard]] inline Aabb bounds(const Cylinder& c) {
    const double r = std::max(c.radius, 0.0f);
    const DVec3 p0(c.p0), p1(c.p1), axis = p1 - p0;
    const double len2 = glm::dot(axis, axis);
    DVec3 e(r);
    if (len2 > 0.0) {
        // The end disks' extents r sqrt(1 - w_i^2) = r sqrt(w_j^2 + w_k^2)
        // (no cancellation), widened by 2^-40 for their few roundings.
        const DVec3 a2 = axis * axis;
        e = r * (glm::sqrt(DVec3(a2.y + a2.z, a2.z + a2.x, a2.x + a2.y) / len2) + 0x1p-40);
    }
    return outward_bounds(glm::min(p0, p1) - e, glm::max(p0, p1) + e);
}

[[nodiscard]] inline Obb oriented_bounds(const Cylinder& c, ObbVariant = ObbVariant::Paper) {
    return segment_obb(c.p0, c.p1, std::max(c.radius, 0.0f), 0.0f);
}

// The cylinder program's operations per path (conventions: core/ops.h).
// Entry: the cylinder's 28 B (2 loads), the radius test, ba (3), len2 (3)
// and its test.
inline constexpr Ops kCylinderEntry{.fma = 6, .branch = 2, .load = 2};
// The bounding-sphere reject: c (6), the local ray (oc 3, d.d 3, oc.d 3, t0
// a division and a branch, o 3), len a sqrt, reach (1), d.d > 0, o.o (3),
// reach^2 (1), the compare.
inline constexpr Ops kCylinderSphereReject = kCylinderEntry + Ops{.fma = 23, .div = 1, .sqrt = 1, .branch = 3};
// The solve: w (a reciprocal and 3), a (3), the infinite cylinder's span (31
// with 2 divisions, a sqrt and 2 branches), the slab's (11 with 2 divisions
// and 2 branches), their overlap (2), the pick (1, 3 branches).
inline constexpr Ops kCylinderSolved = kCylinderSphereReject + Ops{.fma = 51, .div = 5, .sqrt = 1, .branch = 7};
// A hit adds: the point (3), z (6), the side normal (6, n.n 3, a branch, a
// sqrt and a reciprocal, 3) or a cap's (a branch), u = z / len (a division,
// clamp 2).
inline constexpr Ops kCylinderHit = kCylinderSolved + Ops{.fma = 23, .div = 2, .sqrt = 1, .branch = 2};

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const Cylinder& cyl, const Ray& ray, Sink& sink) {
    sink.on(Event::IsCylinder);
    const double r = cyl.radius;
    if (!(r > 0.0)) {
        count_ops(sink, kCylinderEntry);
        return std::nullopt;
    }
    const DVec3 p0(cyl.p0), p1(cyl.p1);
    const DVec3 ba = p1 - p0;
    const double len2 = glm::dot(ba, ba);
    if (!(len2 > 0.0)) {
        count_ops(sink, kCylinderEntry);
        return std::nullopt;
    }
    const DVec3 c = 0.5 * (p0 + p1);
    const LocalRay lr = local_ray(ray, c);
    const double len = std::sqrt(len2);
    const double reach = 0.5 * len + r;  // bounding sphere reject
    if (!(lr.dd > 0.0) || !(glm::dot(lr.o, lr.o) <= reach * reach)) {
        count_ops(sink, kCylinderSphereReject);
        return std::nullopt;
    }

    const DVec3 w = ba / len;
    const DVec3 a = p0 - c;
    enum Part { kSide = 0, kCap0 = 1, kCap1 = 2 };
    const Span span =
        overlap(cylinder_span(lr, a, w, r, kSide),
                slab_span(glm::dot(lr.o - a, w), glm::dot(lr.d, w), 0.0, len, kCap0, kCap1));
    SpanPick hit;
    if (!pick(span, lr, ray, hit)) {
        count_ops(sink, kCylinderSolved);
        return std::nullopt;
    }
    count_ops(sink, kCylinderHit);

    const DVec3 p = lr.o + hit.s * lr.d;
    const double z = glm::dot(p - a, w);
    Vec3 normal;
    if (hit.part == kSide) {
        const DVec3 n = p - (a + z * w);
        const double nn = glm::dot(n, n);
        normal = nn > 0.0 ? Vec3(n / std::sqrt(nn)) : Vec3(w);
    } else {
        normal = Vec3(hit.part == kCap0 ? -w : w);
    }
    return Hit{hit.t, normal, static_cast<float>(std::clamp(z / len, 0.0, 1.0))};
}

}  // namespace rtc
