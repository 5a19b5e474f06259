// pbrt-v4 curve and mesh shapes (see shapes.h for the mapping).
#include "scenes/loaders/pbrt/shapes.h"

#include "scenes/limits.h"

#include <array>
#include <cmath>

namespace rtc::pbrt {

namespace {

Vec3 point(const std::vector<double>& xyz, std::size_t i) {
    return {static_cast<float>(xyz[3 * i]), static_cast<float>(xyz[3 * i + 1]), static_cast<float>(xyz[3 * i + 2])};
}

Vec3 bezier(const std::array<Vec3, 4>& c, float t) {
    const float s = 1.0f - t;
    return s * s * s * c[0] + 3.0f * s * s * t * c[1] + 3.0f * s * t * t * c[2] + t * t * t * c[3];
}

// Segment `i`'s cubic Bezier control points (pbrt-v4 curves: quadratic
// segments are degree-elevated, B-spline segments change basis).
std::array<Vec3, 4> segment(const std::vector<double>& P, bool bspline, int degree, std::size_t i) {
    if (!bspline) {
        const std::size_t k = i * static_cast<std::size_t>(degree);
        if (degree == 3) return {point(P, k), point(P, k + 1), point(P, k + 2), point(P, k + 3)};
        const Vec3 a = point(P, k), b = point(P, k + 1), c = point(P, k + 2);
        return {a, (a + 2.0f * b) / 3.0f, (2.0f * b + c) / 3.0f, c};
    }
    if (degree == 3) {
        const Vec3 p0 = point(P, i), p1 = point(P, i + 1), p2 = point(P, i + 2), p3 = point(P, i + 3);
        return {(p0 + 4.0f * p1 + p2) / 6.0f, (2.0f * p1 + p2) / 3.0f, (p1 + 2.0f * p2) / 3.0f,
                (p1 + 4.0f * p2 + p3) / 6.0f};
    }
    // Quadratic B-spline: runs from the midpoint of p0 p1 to that of p1 p2 with p1 as its middle control point.
    const Vec3 p0 = point(P, i), p1 = point(P, i + 1), p2 = point(P, i + 2);
    const Vec3 a = 0.5f * (p0 + p1), c = 0.5f * (p1 + p2);
    return {a, (a + 2.0f * p1) / 3.0f, (2.0f * p1 + c) / 3.0f, c};
}

void check_finite(const ParamList& params, const Param& p) {
    for (const double x : p.numbers)
        if (std::abs(x) > kMaxCoordinate) params.fail(p, std::string("value beyond +-") + kMaxCoordinateText);
}

std::vector<std::array<std::uint32_t, 3>> triangles_of(const ParamList& params, const Param& P,
                                                       const Param* indices, std::size_t corners) {
    const std::size_t vertices = P.numbers.size() / 3;
    std::vector<double> idx;
    if (indices) {
        idx = indices->numbers;
    } else if (vertices == corners) {
        for (std::size_t i = 0; i < corners; ++i) idx.push_back(static_cast<double>(i));
    } else {
        params.fail(P, "\"integer indices\" are needed when there are " + std::to_string(vertices) +
                           " points (not " + std::to_string(corners) + ")");
    }
    const Param& where = indices ? *indices : P;
    if (idx.size() % corners != 0)
        params.fail(where, std::to_string(idx.size()) + " indices, need a multiple of " + std::to_string(corners));
    for (const double v : idx)
        if (v < 0 || v >= static_cast<double>(vertices))
            params.fail(where, "index " + std::to_string(static_cast<long long>(v)) + " out of range (" +
                                   std::to_string(vertices) + " points)");
    std::vector<std::array<std::uint32_t, 3>> out;
    for (std::size_t f = 0; f < idx.size(); f += corners) {
        auto at = [&](std::size_t k) { return static_cast<std::uint32_t>(idx[f + k]); };
        if (corners == 3) {
            out.push_back({at(0), at(1), at(2)});
        } else {  // bilinear patch p00 p10 p01 p11
            out.push_back({at(0), at(1), at(3)});
            out.push_back({at(0), at(3), at(2)});
        }
    }
    return out;
}

void add_mesh(const ParamList& params, TriangleMesh& out, std::size_t corners) {
    const Param* P = params.find("P", "point3");
    if (!P) params.fail("missing parameter \"point3 P\"");
    check_finite(params, *P);
    const auto tris = triangles_of(params, *P, params.find("indices", "integer"), corners);
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (std::size_t i = 0; i < P->numbers.size() / 3; ++i) out.vertices.push_back(point(P->numbers, i));
    for (const auto& t : tris) out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
}

}  // namespace

void add_triangle_mesh(const ParamList& params, TriangleMesh& out) { add_mesh(params, out, 3); }
void add_bilinear_mesh(const ParamList& params, TriangleMesh& out) { add_mesh(params, out, 4); }

void add_curve(const ParamList& params, Strands& out, CurveBasis out_basis) {
    const Param* P = params.find("P", "point3");
    if (!P) params.fail("missing parameter \"point3 P\"");
    check_finite(params, *P);
    const std::string basis = params.string("basis", "bezier");
    const std::string type = params.string("type", "flat");
    const double degree_value = params.number("degree", "integer", 3);
    if (basis != "bezier" && basis != "bspline")
        params.fail(*params.find("basis", "string"), "must be \"bezier\" or \"bspline\", got \"" + basis + "\"");
    if (type != "flat" && type != "cylinder" && type != "ribbon")
        params.fail(*params.find("type", "string"), "must be \"flat\", \"cylinder\" or \"ribbon\", got \"" + type + "\"");
    if (degree_value != 2 && degree_value != 3) params.fail(*params.find("degree", "integer"), "must be 2 or 3");
    const int degree = static_cast<int>(degree_value);
    const bool bspline = basis == "bspline";
    const std::size_t n = P->numbers.size() / 3;
    const auto d = static_cast<std::size_t>(degree);
    if (n < d + 1)
        params.fail(*P, std::to_string(n) + " points, a degree " + std::to_string(degree) + " curve needs at least " +
                            std::to_string(d + 1));
    if (!bspline && (n - 1) % d != 0)
        params.fail(*P, std::to_string(n) + " points, a degree " + std::to_string(degree) +
                            " Bezier curve needs " + std::to_string(d) + "n + 1");
    const std::size_t segments = bspline ? n - d : (n - 1) / d;

    const double width = params.number("width", "float", 1.0);
    const double w0 = params.number("width0", "float", width), w1 = params.number("width1", "float", width);
    for (const char* key : {"width", "width0", "width1"})
        if (const Param* w = params.find(key, "float"); w && !(w->numbers[0] >= 0.0 && w->numbers[0] <= kMaxCoordinate))
            params.fail(*w, std::string("a width must lie in [0, ") + kMaxCoordinateText + "]");
    const Param* N = params.find("N", "normal");
    if (type == "ribbon" && !N) params.fail("a \"ribbon\" curve needs normals \"normal N\"");
    // pbrt-v4 discards N on other types (with a warning) and checks it on ribbons only.
    if (type == "ribbon" && N->numbers.size() / 3 != segments + 1)
        params.fail(*N, std::to_string(N->numbers.size() / 3) + " normals, need one per segment end (" +
                            std::to_string(segments + 1) + ")");
    const double split = params.number("splitdepth", "integer", 3);
    if (split < 0 || split > 30) params.fail(*params.find("splitdepth", "integer"), "must lie in [0, 30]");

    // Bezier: the cubic control points themselves (consecutive segments share
    // an end point, computed alike), radius = width / 2 at each control
    // point's parameter (a linear radius has those control values).
    // BSpline: `degree` samples on the curve per segment.
    const bool control_points = out_basis == CurveBasis::Bezier;
    const std::size_t steps = control_points ? 3 : d;
    for (std::size_t s = 0; s < segments; ++s) {
        const std::array<Vec3, 4> c = segment(P->numbers, bspline, degree, s);
        for (std::size_t k = (s == 0 ? 0 : 1); k <= steps; ++k) {
            const float t = static_cast<float>(k) / static_cast<float>(steps);
            const double u = (static_cast<double>(s) + t) / static_cast<double>(segments);
            out.points.push_back(control_points ? c[k] : k == 0 ? c[0] : k == d ? c[3] : bezier(c, t));
            out.radii.push_back(static_cast<float>(0.5 * ((1.0 - u) * w0 + u * w1)));
        }
    }
    out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
}

}  // namespace rtc::pbrt
