// Strands -> primitives (see convert.h for the rules and why).
#include "scenes/convert.h"

#include "core/input_error.h"

#include <algorithm>
#include <string>

namespace rtc {

namespace bspline {

PhantomCurve to_bezier(const std::array<Vec3, 4>& p, const std::array<float, 4>& r) {
    // Uniform cubic B-spline basis change: the Bezier control points are
    // (p0 + 4 p1 + p2)/6, (2 p1 + p2)/3, (p1 + 2 p2)/3, (p1 + 4 p2 + p3)/6.
    PhantomCurve c;
    c.cp = {(p[0] + 4.0f * p[1] + p[2]) / 6.0f, (2.0f * p[1] + p[2]) / 3.0f,
            (p[1] + 2.0f * p[2]) / 3.0f, (p[1] + 4.0f * p[2] + p[3]) / 6.0f};
    c.radius = {(r[0] + 4.0f * r[1] + r[2]) / 6.0f, (2.0f * r[1] + r[2]) / 3.0f,
                (r[1] + 2.0f * r[2]) / 3.0f, (r[1] + 4.0f * r[2] + r[3]) / 6.0f};
    return c;
}

Vec3 eval(const std::array<Vec3, 4>& p, float t) {
    const float s = 1.0f - t;
    const float b0 = s * s * s / 6.0f;
    const float b1 = (3.0f * t * t * t - 6.0f * t * t + 4.0f) / 6.0f;
    const float b2 = (-3.0f * t * t * t + 3.0f * t * t + 3.0f * t + 1.0f) / 6.0f;
    const float b3 = t * t * t / 6.0f;
    return b0 * p[0] + b1 * p[1] + b2 * p[2] + b3 * p[3];
}

Vec3 bezier_point(const PhantomCurve& c, float t) {
    const float s = 1.0f - t;
    return s * s * s * c.cp[0] + 3.0f * s * s * t * c.cp[1] + 3.0f * s * t * t * c.cp[2] +
           t * t * t * c.cp[3];
}

float bezier_radius(const PhantomCurve& c, float t) {
    const float s = 1.0f - t;
    return s * s * s * c.radius[0] + 3.0f * s * s * t * c.radius[1] + 3.0f * s * t * t * c.radius[2] +
           t * t * t * c.radius[3];
}

std::pair<PhantomCurve, PhantomCurve> split_half(const PhantomCurve& c) {
    auto split = [](const auto& a, auto& left, auto& right) {
        const auto ab = 0.5f * (a[0] + a[1]), bc = 0.5f * (a[1] + a[2]), cd = 0.5f * (a[2] + a[3]);
        const auto abc = 0.5f * (ab + bc), bcd = 0.5f * (bc + cd);
        const auto mid = 0.5f * (abc + bcd);
        left = {a[0], ab, abc, mid};
        right = {mid, bcd, cd, a[3]};
    };
    std::pair<PhantomCurve, PhantomCurve> out;
    split(c.cp, out.first.cp, out.second.cp);
    split(c.radius, out.first.radius, out.second.radius);
    return out;
}

}  // namespace bspline

namespace {

void check_subdivision(PrimitiveKind kind, int subdivision) {
    if (subdivision != 1 && subdivision != 2 && subdivision != 4 && subdivision != 8)
        throw InputError("curve subdivision must be 1, 2, 4 or 8, got " + std::to_string(subdivision));
    if (subdivision != 1 && kind != PrimitiveKind::Phantom)
        throw InputError("curve subdivision " + std::to_string(subdivision) +
                         " applies only to phantom curves, not to " + std::string(kind_name(kind)));
}

void append_subdivided(std::vector<PhantomCurve>& out, const PhantomCurve& c, int pieces) {
    if (pieces == 1) {
        out.push_back(c);
        return;
    }
    const auto [left, right] = bspline::split_half(c);
    append_subdivided(out, left, pieces / 2);
    append_subdivided(out, right, pieces / 2);
}

// Calls f(strand, first point index, point count) for each strand.
template <class F>
void for_each_strand(const Strands& s, F&& f) {
    for (std::uint32_t i = 0; i + 1 < s.offsets.size(); ++i)
        f(i, s.offsets[i], s.offsets[i + 1] - s.offsets[i]);
}

template <class Prim, class Make>
std::vector<Prim> per_segment(const Strands& s, Make&& make) {
    std::vector<Prim> out;
    out.reserve(s.segment_count());
    for_each_strand(s, [&](std::uint32_t, std::uint32_t first, std::uint32_t n) {
        for (std::uint32_t j = first; j + 1 < first + n; ++j) out.push_back(make(j, j + 1));
    });
    return out;
}

std::vector<PhantomCurve> phantom_curves(const Strands& s, int subdivision) {
    std::vector<PhantomCurve> out;
    out.reserve(s.segment_count() * static_cast<std::size_t>(subdivision));
    for_each_strand(s, [&](std::uint32_t, std::uint32_t first, std::uint32_t n) {
        if (n < 2) return;  // no segment to cover (loaders never produce these)
        const Vec3* p = &s.points[first];
        const float* r = &s.radii[first];
        // Point k of the strand extended by one phantom point at each end.
        auto point = [&](std::int64_t k) {
            if (k < 0) return 2.0f * p[0] - p[1];
            if (k >= n) return 2.0f * p[n - 1] - p[n - 2];
            return p[k];
        };
        auto radius = [&](std::int64_t k) {
            if (k < 0) return 2.0f * r[0] - r[1];
            if (k >= n) return 2.0f * r[n - 1] - r[n - 2];
            return r[k];
        };
        for (std::int64_t j = 0; j + 1 < n; ++j) {
            const PhantomCurve c = bspline::to_bezier(
                {point(j - 1), point(j), point(j + 1), point(j + 2)},
                {radius(j - 1), radius(j), radius(j + 1), radius(j + 2)});
            append_subdivided(out, c, subdivision);
        }
    });
    return out;
}

// The Bezier basis: strand points 3i..3i+3 are curve i's control points
// (radii likewise); a trailing one or two links are a line or a quadratic
// Bezier, degree-elevated to the cubic that traces exactly that.
PhantomCurve bezier_piece(const Vec3* p, const float* r, std::uint32_t links) {
    PhantomCurve c;
    if (links == 3) {
        c.cp = {p[0], p[1], p[2], p[3]};
        c.radius = {r[0], r[1], r[2], r[3]};
    } else if (links == 2) {
        c.cp = {p[0], (p[0] + 2.0f * p[1]) / 3.0f, (2.0f * p[1] + p[2]) / 3.0f, p[2]};
        c.radius = {r[0], (r[0] + 2.0f * r[1]) / 3.0f, (2.0f * r[1] + r[2]) / 3.0f, r[2]};
    } else {
        c.cp = {p[0], (2.0f * p[0] + p[1]) / 3.0f, (p[0] + 2.0f * p[1]) / 3.0f, p[1]};
        c.radius = {r[0], (2.0f * r[0] + r[1]) / 3.0f, (r[0] + 2.0f * r[1]) / 3.0f, r[1]};
    }
    return c;
}

std::vector<PhantomCurve> bezier_curves(const Strands& s, int subdivision) {
    std::vector<PhantomCurve> out;
    out.reserve(primitive_count(s, PrimitiveKind::Phantom, subdivision));
    for_each_strand(s, [&](std::uint32_t, std::uint32_t first, std::uint32_t n) {
        for (std::uint32_t j = 0; j + 1 < n; j += 3)
            append_subdivided(out, bezier_piece(&s.points[first + j], &s.radii[first + j], std::min(3u, n - 1 - j)),
                              subdivision);
    });
    return out;
}

}  // namespace

std::size_t curve_count(std::size_t points, CurveBasis basis) {
    if (points < 2) return 0;
    return basis == CurveBasis::Bezier ? (points - 1 + 2) / 3 : points - 1;
}

std::size_t primitive_count(const Strands& s, PrimitiveKind kind, int subdivision) {
    if (kind != PrimitiveKind::Phantom) return s.segment_count();
    if (s.basis == CurveBasis::BSpline) return s.segment_count() * static_cast<std::size_t>(subdivision);
    std::size_t n = 0;
    for_each_strand(s, [&](std::uint32_t, std::uint32_t, std::uint32_t points) { n += curve_count(points, s.basis); });
    return n * static_cast<std::size_t>(subdivision);
}

PrimitiveArray to_primitives(const Strands& s, PrimitiveKind kind, int subdivision) {
    check_subdivision(kind, subdivision);
    const auto& P = s.points;
    const auto& R = s.radii;
    switch (kind) {
        case PrimitiveKind::Cylinder:
            return per_segment<Cylinder>(s, [&](std::uint32_t a, std::uint32_t b) {
                return Cylinder{P[a], P[b], 0.5f * (R[a] + R[b])};
            });
        case PrimitiveKind::Capsule:
            return per_segment<Capsule>(s, [&](std::uint32_t a, std::uint32_t b) {
                return Capsule{P[a], P[b], 0.5f * (R[a] + R[b])};
            });
        case PrimitiveKind::Link:
            return per_segment<Link>(
                s, [&](std::uint32_t a, std::uint32_t b) { return Link{P[a], R[a], P[b], R[b]}; });
        case PrimitiveKind::Phantom:
            return s.basis == CurveBasis::Bezier ? bezier_curves(s, subdivision) : phantom_curves(s, subdivision);
    }
    throw InputError("unknown primitive kind");
}

std::vector<std::uint32_t> primitive_strands(const Strands& s, PrimitiveKind kind, int subdivision) {
    check_subdivision(kind, subdivision);
    std::vector<std::uint32_t> out;
    out.reserve(primitive_count(s, kind, subdivision));
    const CurveBasis basis = kind == PrimitiveKind::Phantom ? s.basis : CurveBasis::BSpline;  // one per link
    for_each_strand(s, [&](std::uint32_t strand, std::uint32_t, std::uint32_t n) {
        out.insert(out.end(), curve_count(n, basis) * static_cast<std::size_t>(subdivision), strand);
    });
    return out;
}

std::size_t primitive_count(const PrimitiveArray& prims) {
    return std::visit([](const auto& v) { return v.size(); }, prims);
}

}  // namespace rtc
