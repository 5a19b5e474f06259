// The phantom curve primitive (Reshetov & Luebke 2018, "Phantom Ray-Hair
// Intersector", Proc. ACM CGIT 1(2), HPG 2018): a cubic Bezier with a radius
// that is the cubic Bezier of four radius values. What both intersection
// programs share: the curve, the options that pick a program, its AABB and
// the double-precision ray-centric frame.
//
// Two programs intersect it (PhantomOptions::program):
//   Bracketed (phantom.h): this project's root search bracketed by sub-curve
//     capsules, nearest first, which finds the nearest crossing of the sphere
//     sweep (about 4-5 iterations per call).
//   Paper (phantom_reshetov.h): Reshetov & Luebke's iteration as published,
//     with the capped bounding cylinder early out Wald et al. 2020 used.
#pragma once

#include "core/enum_names.h"
#include "core/ops.h"
#include "intersectors/frame.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>

namespace rtc {

struct PhantomCurve {
    std::array<Vec3, 4> cp{};        // Bezier control points
    std::array<float, 4> radius{};   // radius as a cubic Bezier in the same parameter
};

enum class PhantomProgram : std::uint8_t { Bracketed, Paper };
inline constexpr std::array<std::string_view, 2> kPhantomProgramNames = {"bracketed", "paper"};

[[nodiscard]] constexpr std::string_view phantom_program_name(PhantomProgram p) {
    return kPhantomProgramNames[static_cast<std::size_t>(p)];
}
[[nodiscard]] constexpr std::optional<PhantomProgram> phantom_program_from_name(std::string_view s) {
    return enum_from_name<PhantomProgram>(kPhantomProgramNames, s);
}

struct PhantomOptions {
    bool early_out = true;    // the program's bounding-cylinder test before iterating
    int max_iterations = 24;  // bracketed: per search start
    PhantomProgram program = PhantomProgram::Bracketed;
    int paper_max_iterations = 40;  // paper: per curve end (Reshetov & Luebke's cap)
};

[[nodiscard]] inline bool is_finite(const PhantomCurve& c) {
    for (int i = 0; i < 4; ++i)
        if (!is_finite(c.cp[i]) || !std::isfinite(c.radius[i])) return false;
    return true;
}

[[nodiscard]] inline float max_radius(const PhantomCurve& c) {
    return std::max({c.radius[0], c.radius[1], c.radius[2], c.radius[3], 0.0f});
}

// Control-polygon hull grown by the largest radius (convex hull property).
[[nodiscard]] inline Aabb bounds(const PhantomCurve& c) {
    Aabb b;
    for (const Vec3& p : c.cp) b.extend(p);
    const double r = max_radius(c);
    return outward_bounds(DVec3(b.lo) - r, DVec3(b.hi) + r);
}

namespace detail {

struct DBasis {
    DVec3 x, y;
};
[[nodiscard]] inline DBasis dbasis(const DVec3& n) {  // Duff et al. 2017, in double
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    return {DVec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
            DVec3(b, sign + n.y * n.y * a, -n.y)};
}

// The curve in the ray-centric frame (RCC): origin at the ray origin, z along
// the unit ray direction, so the ray is the z axis and distances along it are
// t |d|. Radii clamped at 0.
struct RccCurve {
    std::array<DVec3, 4> q;
    std::array<double, 4> r;
    DBasis xy;     // world x, y axes of the frame
    DVec3 e;       // world z axis (unit ray direction)
    double dlen;   // |d|
};

[[nodiscard]] inline RccCurve to_ray_frame(const PhantomCurve& pc, const Ray& ray) {
    RccCurve c;
    const DVec3 d(ray.direction);
    c.dlen = glm::length(d);
    c.e = d / c.dlen;
    c.xy = dbasis(c.e);
    const DVec3 o(ray.origin);
    for (int i = 0; i < 4; ++i) {
        const DVec3 v = DVec3(pc.cp[i]) - o;
        c.q[i] = DVec3(glm::dot(v, c.xy.x), glm::dot(v, c.xy.y), glm::dot(v, c.e));
        c.r[i] = std::max(double(pc.radius[i]), 0.0);
    }
    return c;
}

// A normal given in the frame, back in world space (unit; -d when degenerate).
[[nodiscard]] inline Vec3 from_ray_frame(const RccCurve& c, const DVec3& n_rcc, const Ray& ray) {
    const DVec3 n = n_rcc.x * c.xy.x + n_rcc.y * c.xy.y + n_rcc.z * c.e;
    const double nl = glm::length(n);
    return nl > 0.0 ? Vec3(n / nl) : Vec3(-ray.direction / float(c.dlen));
}

// Operations both phantom programs share (conventions: core/ops.h).
// Entry: the curve's 4 control points and 4 radii (64 B, 4 loads), the
// finiteness tests (3), the largest radius (3), |d| (3 and a sqrt) and the
// two tests on it.
inline constexpr Ops kPhantomEntry{.fma = 6, .sqrt = 1, .branch = 5, .load = 4};
// to_ray_frame: |d| (3 and a sqrt), e = d / |d| (a reciprocal, 3), the basis
// (12 and a reciprocal), each control point moved and projected (4 x 12),
// the radii's clamps (4).
inline constexpr Ops kPhantomSetup{.fma = 70, .div = 2, .sqrt = 1};
// from_ray_frame: the normal back in world space (9), its length (3 and a
// sqrt) and normalisation (a reciprocal, 3); t = s / |d| (a division) and
// its two range tests.
inline constexpr Ops kPhantomReport{.fma = 15, .div = 2, .sqrt = 1, .branch = 2};

}  // namespace detail

}  // namespace rtc
