// Ray: origin, unnormalized direction and the parametric interval [tmin, tmax].
//
// The direction is deliberately not normalized: instancing transforms the ray
// into object space without renormalizing, so a parameter t names the same
// point at every level of the hierarchy (pbrt-v4 primitive.cpp does the same).
#pragma once

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <cmath>
#include <limits>

namespace rtc {

using Vec3 = glm::vec3;
using DVec3 = glm::dvec3;

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Ray {
    Vec3 origin{0.0f};
    float tmin = 0.0f;
    Vec3 direction{0.0f, 0.0f, 1.0f};
    float tmax = kInfinity;

    [[nodiscard]] Vec3 at(float t) const { return origin + t * direction; }
};

// Reciprocal of the direction with zero components mapped to a huge finite
// value of the same sign, so slab tests never compute 0 * inf = NaN.
[[nodiscard, gnu::always_inline]] inline Vec3 safe_inverse(const Vec3& d) {
    auto inv = [](float x) {
        constexpr float kBig = 1e30f;
        if (x == 0.0f) return std::signbit(x) ? -kBig : kBig;
        return 1.0f / x;
    };
    return {inv(d.x), inv(d.y), inv(d.z)};
}

}  // namespace rtc
