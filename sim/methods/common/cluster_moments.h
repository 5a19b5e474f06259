// Internal to the cluster grouping and frames (cluster_groups.cpp,
// cluster_frame.cpp): the moments of a set of primitives (their orientation
// tensor and the scatter of their points), the eigenvectors of those, and a
// primitive's box in a rotated frame, all in double. The grouping sums the
// moments of millions of primitives in one order fixed by its splits, so
// every sum here is written once, in one order: the groups depend on it.
#pragma once

#include "sim/methods/common/cluster_groups.h"

#include <array>
#include <limits>

#ifdef __AVX__
#include <immintrin.h>
#endif

namespace rtc::cluster_detail {

using Sym3 = std::array<std::array<double, 3>, 3>;

struct Axes {
    DVec3 x, y, z;
};

// Eigenvectors of a symmetric 3x3 matrix (cyclic Jacobi rotations), ordered
// by eigenvalue, largest first; equal eigenvalues keep the axis order.
[[nodiscard]] std::array<DVec3, 3> eigenvectors(Sym3 a);

// Four double lanes (GCC and Clang vector extensions: AVX under x86-64-v3,
// pairs of SSE2 operations otherwise). Every lane of every operation below is
// the scalar operation it stands for, so the sums are bit for bit the same.
// (Without AVX, GCC warns wherever such a vector is passed by value that its
// ABI differs from AVX code's: no such call crosses from one build to the
// other, so the warning is off for the files that include this one.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
using D4 = double __attribute__((vector_size(32)));

[[nodiscard]] inline D4 lanes(const Vec3& v) { return D4{double(v.x), double(v.y), double(v.z), 0.0}; }
[[nodiscard]] inline D4 lanes(const DVec3& v) { return D4{v.x, v.y, v.z, 0.0}; }
[[nodiscard]] inline DVec3 dvec3(const D4& v) { return {v[0], v[1], v[2]}; }

// Orientation tensor and point scatter of a set of primitives, summed in the
// order they are added. Only the upper triangles are summed (the lower ones
// would be the same sums of the same products: c[r] c[q] = c[q] c[r]), in
// lanes: xx xy xz yy, then yz zz.
struct Moments {
    std::array<D4, 2> orientation_lanes{};  // sum over primitives of length * d d^T (d: unit chord)
    std::array<D4, 2> outer_lanes{};        // sum of (c - ref)(c - ref)^T over sphere centres c
    D4 sum{};                               // of c - ref
    DVec3 ref{0.0};
    double points = 0.0;

    [[gnu::always_inline]] void add(const Spheres& s) {
        if (points == 0.0) ref = DVec3(s.center[0]);
        const D4 r = lanes(ref);
        for (int i = 0; i < s.count; ++i) {
            const D4 c = lanes(s.center[i]) - r;
            sum += c;
            points += 1.0;
            add_products(outer_lanes, c);
        }
        const D4 d = lanes(s.center[s.count - 1]) - lanes(s.center[0]);
        const double len = glm::length(dvec3(d));
        if (len > 0.0) add_products(orientation_lanes, d, len);
    }
    [[nodiscard]] DVec3 mean() const { return points > 0.0 ? ref + dvec3(sum) / points : ref; }
    [[nodiscard]] Sym3 orientation() const { return full(orientation_lanes); }
    [[nodiscard]] Sym3 covariance() const {
        Sym3 c{};
        if (points == 0.0) return c;
        const Sym3 outer = full(outer_lanes);
        const DVec3 m = dvec3(sum) / points;
        for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) c[r][q] = outer[r][q] / points - m[r] * m[q];
        return c;
    }

private:
    // to += v v^T (upper triangle), each product divided by `by` if given.
    static void add_products(std::array<D4, 2>& to, const D4& v) {
        to[0] += __builtin_shufflevector(v, v, 0, 0, 0, 1) * __builtin_shufflevector(v, v, 0, 1, 2, 1);
        to[1] += __builtin_shufflevector(v, v, 1, 2, 3, 3) * __builtin_shufflevector(v, v, 2, 2, 3, 3);
    }
    static void add_products(std::array<D4, 2>& to, const D4& v, double by) {
        to[0] += __builtin_shufflevector(v, v, 0, 0, 0, 1) * __builtin_shufflevector(v, v, 0, 1, 2, 1) / by;
        to[1] += __builtin_shufflevector(v, v, 1, 2, 3, 3) * __builtin_shufflevector(v, v, 2, 2, 3, 3) / by;
    }
    static Sym3 full(const std::array<D4, 2>& u) {
        return {{{u[0][0], u[0][1], u[0][2]}, {u[0][1], u[0][3], u[1][0]}, {u[0][2], u[1][0], u[1][1]}}};
    }
};

// Right-handed orthonormal axes: x along `x`, y along the part of `hint`
// across x (any perpendicular when that vanishes).
[[nodiscard]] Axes complete(DVec3 x, const DVec3& hint);
// The principal axis of the points across the unit axis x.
[[nodiscard]] DVec3 across(const Moments& m, const DVec3& x);
// x: the dominant direction; y: the points' principal axis across it.
[[nodiscard]] Axes principal_axes(const Moments& m);

struct DBox {
    DVec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    void extend(const DBox& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    [[nodiscard]] double area() const {
        const DVec3 e = hi - lo;
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

// The box of a primitive's spheres in the frame `a` placed at `origin`.
template <class Prim>
[[nodiscard]] DBox box_in(const Prim& prim, const Axes& a, const DVec3& origin) {
    const Spheres s = spheres(prim);
    DBox b;
    for (int i = 0; i < s.count; ++i) {
        const DVec3 v = DVec3(s.center[i]) - origin;
        const DVec3 q(glm::dot(v, a.x), glm::dot(v, a.y), glm::dot(v, a.z));
        b.lo = glm::min(b.lo, q - double(s.radius[i]));
        b.hi = glm::max(b.hi, q + double(s.radius[i]));
    }
    return b;
}

// glm::min(x, y) and glm::max(x, y) in every lane: (y < x) ? y : x and
// (x < y) ? y : x, the same choice on ties and NaN.
[[nodiscard]] inline D4 min_lanes(const D4& x, const D4& y) {
#ifdef __AVX__
    return _mm256_min_pd(y, x);
#else
    D4 m = x;
    for (int k = 0; k < 4; ++k) m[k] = y[k] < x[k] ? y[k] : x[k];
    return m;
#endif
}
[[nodiscard]] inline D4 max_lanes(const D4& x, const D4& y) {
#ifdef __AVX__
    return _mm256_max_pd(y, x);
#else
    D4 m = x;
    for (int k = 0; k < 4; ++k) m[k] = x[k] < y[k] ? y[k] : x[k];
    return m;
#endif
}

// A frame's axes as the columns box_in multiplies by: lane k of `x` is the
// x component of axis k.
struct AxesLanes {
    D4 x, y, z;
    explicit AxesLanes(const Axes& a)
        : x{a.x.x, a.y.x, a.z.x, 0.0}, y{a.x.y, a.y.y, a.z.y, 0.0}, z{a.x.z, a.y.z, a.z.z, 0.0} {}
};

// DBox in lanes: `extend_in` is box.extend(box_in(prim, a, origin)), with
// the same operations (each coordinate glm::dot's (x + y) + z).
struct DBoxLanes {
    D4 lo = D4{} + std::numeric_limits<double>::infinity(), hi = -lo;
    template <class Prim>
    void extend_in(const Prim& prim, const AxesLanes& a, const D4& origin) {
        const Spheres s = spheres(prim);
        D4 plo = D4{} + std::numeric_limits<double>::infinity(), phi = -plo;
        for (int i = 0; i < s.count; ++i) {
            const D4 v = lanes(s.center[i]) - origin;
            const D4 q = (v[0] * a.x + v[1] * a.y) + v[2] * a.z;
            const double r = s.radius[i];
            plo = min_lanes(plo, q - r);
            phi = max_lanes(phi, q + r);
        }
        lo = min_lanes(lo, plo);
        hi = max_lanes(hi, phi);
    }
    [[nodiscard]] DBox box() const { return {dvec3(lo), dvec3(hi)}; }
};

// glm::dot(v, w) of lanes 0-2: (x + y) + z.
[[nodiscard]] inline double dot(const D4& v, const DVec3& w) { return v[0] * w.x + v[1] * w.y + v[2] * w.z; }

// centroid(s) and unit_chord(s) below, in lanes; `len` is the chord's length.
[[nodiscard]] inline D4 centroid_lanes(const Spheres& s) {
    D4 c{};
    for (int i = 0; i < s.count; ++i) c += lanes(s.center[i]);
    return c / double(s.count);
}
[[nodiscard]] inline D4 unit_chord_lanes(const Spheres& s, double& len) {
    const D4 d = lanes(s.center[s.count - 1]) - lanes(s.center[0]);
    len = glm::length(dvec3(d));
    return len > 0.0 ? d / len : D4{};
}

[[nodiscard]] inline DVec3 centroid(const Spheres& s) {
    DVec3 c(0.0);
    for (int i = 0; i < s.count; ++i) c += DVec3(s.center[i]);
    return c / double(s.count);
}

// The chord from the first sphere to the last, unit length (zero if none).
[[nodiscard]] inline DVec3 unit_chord(const Spheres& s) {
    const DVec3 d = DVec3(s.center[s.count - 1]) - DVec3(s.center[0]);
    const double len = glm::length(d);
    return len > 0.0 ? d / len : DVec3(0.0);
}

}  // namespace rtc::cluster_detail
