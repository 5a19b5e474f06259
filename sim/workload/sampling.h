// Warping of uniform random numbers into the distributions the workloads
// need: stratified offsets inside a pixel, and cosine-weighted directions on
// the hemisphere around a normal (the ideal importance sampling of a diffuse
// surface: with pdf cos(theta)/pi the estimator weight of a Lambertian BRDF is
// just its albedo).
#pragma once

#include "core/ray.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>

namespace rtc {

// Offset in [0,1)^2 of sample `sample` of `spp` inside a pixel. One sample
// sits at the centre; otherwise the first k*k samples (k = floor(sqrt(spp)))
// are jittered in a k x k grid of strata and any rest are uniform in the
// pixel. (u, v) are the two uniforms of that sample.
[[nodiscard]] inline glm::vec2 pixel_offset(std::uint32_t sample, std::uint32_t spp, float u,
                                            float v) {
    if (spp <= 1) return {0.5f, 0.5f};
    auto k = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(spp)));
    while ((k + 1) * (k + 1) <= spp) ++k;  // guard the sqrt rounding
    while (k * k > spp) --k;
    if (sample >= k * k) return {u, v};
    const float inv = 1.0f / static_cast<float>(k);
    const glm::vec2 o{(static_cast<float>(sample % k) + u) * inv,
                      (static_cast<float>(sample / k) + v) * inv};
    // Rounding can push (k-1 + u)/k to 1.0f: keep the offset inside the pixel.
    constexpr float kBelowOne = 0x1.fffffep-1f;  // largest float below 1
    return {std::fmin(o.x, kBelowOne), std::fmin(o.y, kBelowOne)};
}

// Right-handed orthonormal basis (t, b, n) around a unit vector n, without
// branches on the near-pole case (Duff et al. 2017, "Building an Orthonormal
// Basis, Revisited", JCGT 6(1)).
struct Frame {
    Vec3 t, b, n;
    [[nodiscard]] Vec3 to_world(const Vec3& local) const {
        return local.x * t + local.y * b + local.z * n;
    }
};

[[nodiscard]] inline Frame frame_around(const Vec3& n) {
    const float s = std::copysign(1.0f, n.z);
    const float a = -1.0f / (s + n.z);
    const float c = n.x * n.y * a;
    return {Vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x), Vec3(c, s + n.y * n.y * a, -n.y), n};
}

// Cosine-weighted direction in the local frame (z up), from the concentric
// mapping of the unit square to the disk followed by projection up onto the
// hemisphere (Malley's method). pdf = cos(theta) / pi.
[[nodiscard]] inline Vec3 cosine_hemisphere(float u, float v) {
    const float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
    float r = 0.0f, phi = 0.0f;
    constexpr float kQuarterPi = std::numbers::pi_v<float> / 4.0f;
    if (a != 0.0f || b != 0.0f) {
        if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = kQuarterPi * (b / a);
        } else {
            r = b;
            phi = 2.0f * kQuarterPi - kQuarterPi * (a / b);
        }
    }
    const float x = r * std::cos(phi), y = r * std::sin(phi);
    const float z = std::sqrt(std::fmax(0.0f, 1.0f - x * x - y * y));
    return {x, y, z};
}

// Cosine-weighted unit direction around the unit normal n (world space).
[[nodiscard]] inline Vec3 cosine_direction(const Vec3& n, float u, float v) {
    return glm::normalize(frame_around(n).to_world(cosine_hemisphere(u, v)));
}

}  // namespace rtc
