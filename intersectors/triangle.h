// Triangle, tested "in hardware" with the watertight test of Woop, Benthin and
// Wald 2013 ("Watertight Ray/Triangle Intersection", JCGT 2(1)).
//
// Derivation. Permute the axes so the ray direction's largest component is z,
// then shear so the ray becomes the +z axis through the origin. In that space
// the edge functions U, V, W of the three edges are 2D cross products of the
// sheared vertices; the ray hits iff they all have the same sign (an edge
// shared by two triangles gets opposite signs in the two, so no ray slips
// between them). A zero edge function is recomputed in double, which is exact
// for products of floats, so the sign test is exact as in the paper. The
// distance is T / (U + V + W) with T the U,V,W-weighted sheared z. Done in
// float, as the hardware does.
#pragma once

#include "core/aabb.h"
#include "core/events.h"
#include "intersectors/frame.h"
#include "intersectors/hit.h"

#include <optional>
#include <utility>

namespace rtc {

struct Triangle {
    Vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
};

[[nodiscard]] inline bool is_finite(const Triangle& t) {
    return is_finite(t.v0) && is_finite(t.v1) && is_finite(t.v2);
}

[[nodiscard]] inline Aabb bounds(const Triangle& t) {
    Aabb b = Aabb::from_point(t.v0);
    b.extend(t.v1);
    b.extend(t.v2);
    return b;  // exact: min/max of the vertices need no rounding
}

template <class Sink>
[[nodiscard]] std::optional<Hit> intersect(const Triangle& tri, const Ray& ray, Sink& sink) {
    sink.on(Event::TriangleTest);
    const Vec3& d = ray.direction;
    const Vec3 ad = glm::abs(d);
    int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
    if (!(ad[kz] > 0.0f)) return std::nullopt;  // zero or NaN direction
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0f) std::swap(kx, ky);  // keep the winding of the sheared space
    const float sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1.0f / d[kz];

    const Vec3 a = tri.v0 - ray.origin, b = tri.v1 - ray.origin, c = tri.v2 - ray.origin;
    const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
    float u = cx * by - cy * bx;
    float v = ax * cy - ay * cx;
    float w = bx * ay - by * ax;
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        u = static_cast<float>(double(cx) * by - double(cy) * bx);
        v = static_cast<float>(double(ax) * cy - double(ay) * cx);
        w = static_cast<float>(double(bx) * ay - double(by) * ax);
    }
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f))
        return std::nullopt;
    const float det = u + v + w;
    if (!(det != 0.0f)) return std::nullopt;
    const float az = sz * a[kz], bz = sz * b[kz], cz = sz * c[kz];
    const float t = (u * az + v * bz + w * cz) / det;
    if (!(t >= ray.tmin && t <= ray.tmax)) return std::nullopt;

    const Vec3 n = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
    const float nn = glm::dot(n, n);
    const Vec3 normal = nn > 0.0f ? n / std::sqrt(nn) : Vec3(0.0f, 0.0f, 1.0f);
    return Hit{t, normal, v / det};  // u: barycentric weight of v1
}

}  // namespace rtc
