// Accuracy harness shared by the intersector property tests: random rays aimed
// near a primitive, compared with an extended-precision reference.
//
// A ray is "grazing" when the reference disagrees with itself between the
// primitive shrunk and grown by 1e-3 r (radii scaled by 1 -+ 1e-3, cylinder
// ends moved likewise): the float answer may go either way there. Outside that
// band hit/miss must agree; on agreeing hits |t - t_ref| |d| is compared with
// 1e-3 r. A float t cannot be closer than half an ulp of itself, so the check
// allows 1e-3 r + ulp(t) |d| and the strict figure is reported separately.
#pragma once

#include "core/ray.h"
#include "straight_ref.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>

namespace rtc::test {

inline Vec3 random_unit(std::mt19937& rng) {
    std::normal_distribution<float> n;
    for (;;) {
        const Vec3 v(n(rng), n(rng), n(rng));
        const float l = glm::length(v);
        if (l > 1e-3f) return v / l;
    }
}

inline float uniform(std::mt19937& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}
inline float log_uniform(std::mt19937& rng, float lo, float hi) {
    return std::exp(uniform(rng, std::log(lo), std::log(hi)));
}

// A ray from distance `dist` (times the primitive length) aimed at `target`,
// with a random unnormalized direction length in [0.1, 10].
inline Ray aim(std::mt19937& rng, const Vec3& target, float dist) {
    const Vec3 dir = random_unit(rng);
    const float scale = log_uniform(rng, 0.1f, 10.0f);
    return {target - dist * dir, 0.0f, dir * scale, kInfinity};
}

struct AccuracyStats {
    long rays = 0, grazing = 0, disagree = 0, both_hit = 0, over_strict = 0, over_allowed = 0;
    double max_err_r = 0.0;  // max |t - t_ref| |d| / r over agreeing hits

    void add(const std::optional<float>& t, const std::optional<ref::Real>& t_ref,
             bool grazing_ray, const Ray& ray, double r) {
        ++rays;
        if (grazing_ray) {
            ++grazing;
            return;
        }
        if (t.has_value() != t_ref.has_value()) {
            ++disagree;
            return;
        }
        if (!t) return;
        ++both_hit;
        const double len = glm::length(DVec3(ray.direction));
        const double err = std::abs(double(*t) - double(*t_ref)) * len;
        const double ulp = std::nextafter(std::abs(*t), kInfinity) - std::abs(*t);
        max_err_r = std::max(max_err_r, err / r);
        if (err > 1e-3 * r) ++over_strict;
        if (err > 1e-3 * r + ulp * len) ++over_allowed;
    }
    [[nodiscard]] double agreement() const {
        const long n = rays - grazing;
        return n > 0 ? 1.0 - double(disagree) / double(n) : 1.0;
    }
    [[nodiscard]] std::string summary(const char* kind) const {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "%s: %ld rays, %ld grazing, agreement %.6f%% (%ld disagree), %ld hits, "
                      "max |dt||d| = %.3g r, %ld over 1e-3 r strictly, %ld over 1e-3 r + ulp(t)",
                      kind, rays, grazing, 100.0 * agreement(), disagree, both_hit, max_err_r,
                      over_strict, over_allowed);
        return buf;
    }
};

}  // namespace rtc::test
