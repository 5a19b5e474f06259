// Cubic Bezier evaluation (Bernstein form) for the phantom curve, in double.
//
// B(t) = (1-t)^3 P0 + 3(1-t)^2 t P1 + 3(1-t) t^2 P2 + t^3 P3, and
// B'(t) = 3[(1-t)^2 (P1-P0) + 2(1-t) t (P2-P1) + t^2 (P3-P2)], and
// B''(t) = 6[(1-t)(P2 - 2P1 + P0) + t(P3 - 2P2 + P1)], linear in t. The same
// formulas serve positions (DVec3) and radii (double). The curve lies in the
// convex hull of its control points, which every bound of the phantom uses.
#pragma once

#include "core/ray.h"

#include <array>

namespace rtc {

template <class T>
[[nodiscard]] inline T bezier(const std::array<T, 4>& p, double t) {
    const double s = 1.0 - t;
    return (s * s * s) * p[0] + (3.0 * s * s * t) * p[1] + (3.0 * s * t * t) * p[2] +
           (t * t * t) * p[3];
}

template <class T>
[[nodiscard]] inline T bezier_derivative(const std::array<T, 4>& p, double t) {
    const double s = 1.0 - t;
    return (3.0 * s * s) * (p[1] - p[0]) + (6.0 * s * t) * (p[2] - p[1]) +
           (3.0 * t * t) * (p[3] - p[2]);
}

template <class T>
[[nodiscard]] inline T bezier_second_derivative(const std::array<T, 4>& p, double t) {
    return (6.0 * (1.0 - t)) * (p[2] - 2.0 * p[1] + p[0]) + (6.0 * t) * (p[3] - 2.0 * p[2] + p[1]);
}

}  // namespace rtc
