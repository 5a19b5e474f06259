// Shared helpers for core tests: seeded random scenes and a tiny reference
// triangle test (the intersectors layer has the production one; core tests
// must not depend on it).
#pragma once

#include "core/affine.h"

#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace rtc::test {

struct Rng {
    std::mt19937 gen;
    explicit Rng(std::uint32_t seed) : gen(seed) {}
    // Implementation-defined distributions are avoided: a plain 24-bit mantissa.
    float uniform() { return static_cast<float>(gen() >> 8) * (1.0f / 16777216.0f); }
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    Vec3 point(float lo, float hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
    Vec3 direction() {
        for (;;) {
            const Vec3 v = point(-1.0f, 1.0f);
            const float l = glm::length(v);
            if (l > 0.1f && l <= 1.0f) return v / l;
        }
    }
};

struct Tri {
    Vec3 a, b, c;
    [[nodiscard]] Aabb box() const {
        Aabb bb = Aabb::from_point(a);
        bb.extend(b);
        bb.extend(c);
        return bb;
    }
};

// Moller-Trumbore; good enough for tests that compare two traversals of the
// same triangles (both sides call this same function).
[[nodiscard]] inline std::optional<float> hit_triangle(const Tri& tri, const Ray& r) {
    const Vec3 e1 = tri.b - tri.a, e2 = tri.c - tri.a;
    const Vec3 p = glm::cross(r.direction, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) return std::nullopt;
    const float inv = 1.0f / det;
    const Vec3 s = r.origin - tri.a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return std::nullopt;
    const Vec3 q = glm::cross(s, e1);
    const float v = glm::dot(r.direction, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return std::nullopt;
    const float t = glm::dot(e2, q) * inv;
    if (t < r.tmin || t > r.tmax) return std::nullopt;
    return t;
}

[[nodiscard]] inline std::vector<Tri> random_triangles(Rng& rng, int n, float size = 0.1f) {
    std::vector<Tri> tris;
    for (int i = 0; i < n; ++i) {
        const Vec3 c = rng.point(-1.0f, 1.0f);
        tris.push_back({c + rng.point(-size, size), c + rng.point(-size, size),
                        c + rng.point(-size, size)});
    }
    return tris;
}

[[nodiscard]] inline std::vector<Aabb> random_boxes(Rng& rng, int n, float size = 0.1f) {
    std::vector<Aabb> boxes;
    for (int i = 0; i < n; ++i) {
        const Vec3 c = rng.point(-1.0f, 1.0f);
        const Vec3 h = rng.point(0.0f, size);
        boxes.push_back({c - h, c + h});
    }
    return boxes;
}

// A ray from outside the unit cube aimed at a random point inside it.
[[nodiscard]] inline Ray random_ray(Rng& rng) {
    const Vec3 target = rng.point(-1.0f, 1.0f);
    const Vec3 origin = 3.0f * rng.direction();
    return {origin, 0.0f, (target - origin) * rng.uniform(0.5f, 2.0f), kInfinity};
}

}  // namespace rtc::test
