// A scene as plain data: strands (polylines with a radius per point) and an
// optional triangle mesh. Loaders and generators produce it; conversion
// (scenes/convert.h) turns strands into primitives of one kind.
#pragma once

#include "core/enum_names.h"
#include "core/ray.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rtc {

// How a strand's points define its phantom curves (scenes/convert.h); the
// straight kinds (cylinder, capsule, link) connect consecutive points in
// both, one primitive per link.
//   BSpline: the points are a uniform cubic B-spline's control points, one
//            curve per link (this project's first conversion, the default).
//   Bezier:  the points are a cubic Bezier control polygon, one curve per
//            three links (points 3i..3i+3, consecutive curves sharing an end
//            point), as Wald et al. 2020 built theirs.
enum class CurveBasis : std::uint8_t { BSpline, Bezier };
inline constexpr std::array<std::string_view, 2> kCurveBasisNames = {"bspline", "bezier"};

[[nodiscard]] constexpr std::string_view curve_basis_name(CurveBasis b) {
    return kCurveBasisNames[static_cast<std::size_t>(b)];
}
[[nodiscard]] constexpr std::optional<CurveBasis> curve_basis_from_name(std::string_view s) {
    return enum_from_name<CurveBasis>(kCurveBasisNames, s);
}

struct Strands {
    std::vector<Vec3> points;
    std::vector<float> radii;              // one per point
    std::vector<std::uint32_t> offsets{0}; // strand i is points[offsets[i], offsets[i+1])
    CurveBasis basis = CurveBasis::BSpline;

    [[nodiscard]] std::size_t strand_count() const { return offsets.size() - 1; }
    [[nodiscard]] std::size_t segment_count() const {
        std::size_t n = 0;
        for (std::size_t i = 0; i + 1 < offsets.size(); ++i)
            n += offsets[i + 1] - offsets[i] > 0 ? offsets[i + 1] - offsets[i] - 1 : 0;
        return n;
    }
};

struct TriangleMesh {
    std::vector<Vec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct Scene {
    std::string name;
    Strands strands;
    TriangleMesh mesh;
    // What the files held and the scene drops, one line each (e.g. a pbrt
    // file's spheres and camera): warnings, and report.json's scene.notes.
    std::vector<std::string> notes;
};

}  // namespace rtc
