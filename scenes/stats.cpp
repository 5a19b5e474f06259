// Scene statistics (see stats.h). Sums in double: millions of small terms.
#include "scenes/stats.h"

#include "scenes/convert.h"

#include <algorithm>
#include <cmath>

namespace rtc {

SceneStats compute_stats(const Scene& scene) {
    const Strands& s = scene.strands;
    SceneStats st;
    st.strands = s.strand_count();
    st.segments = s.segment_count();
    st.points = s.points.size();
    st.triangles = scene.mesh.triangles.size();
    st.curve_basis = s.basis;
    for (std::size_t i = 0; i < s.strand_count(); ++i) st.curves += curve_count(s.offsets[i + 1] - s.offsets[i], s.basis);
    for (std::size_t k = 0; k < s.points.size(); ++k) {
        st.bounds.extend(s.points[k] - Vec3(s.radii[k]));
        st.bounds.extend(s.points[k] + Vec3(s.radii[k]));
    }
    for (const Vec3& v : scene.mesh.vertices) st.bounds.extend(v);

    double length = 0.0, radius = 0.0, ratio = 0.0;
    std::size_t with_radius = 0;
    for (std::size_t i = 0; i < s.strand_count(); ++i)
        for (std::uint32_t k = s.offsets[i]; k + 1 < s.offsets[i + 1]; ++k) {
            const double len = glm::length(DVec3(s.points[k + 1]) - DVec3(s.points[k]));
            const double r = 0.5 * (double{s.radii[k]} + double{s.radii[k + 1]});
            length += len;
            radius += r;
            const auto magnitude = [](const Vec3& p) {
                return std::max({std::abs(double{p.x}), std::abs(double{p.y}), std::abs(double{p.z})});
            };
            const double m = std::max(magnitude(s.points[k]), magnitude(s.points[k + 1]));
            st.thin_segments += too_thin_for_float(std::max(double{s.radii[k]}, double{s.radii[k + 1]}), m);
            if (r > 0.0) {
                ratio += len / r;
                ++with_radius;
            }
        }
    if (st.segments > 0) {
        st.mean_segment_length = length / static_cast<double>(st.segments);
        st.mean_radius = radius / static_cast<double>(st.segments);
    }
    if (with_radius > 0) st.mean_length_over_radius = ratio / static_cast<double>(with_radius);
    return st;
}

}  // namespace rtc
