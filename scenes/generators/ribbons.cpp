#include "scenes/generators/ribbons.h"

#include "scenes/generators/random.h"

#include <cmath>

namespace rtc {

namespace {

// A unit vector perpendicular to `axis` at a random angle around it.
Vec3 random_side(const Vec3& axis, SceneRng& rng) {
    const float len = glm::length(axis);
    const Vec3 n = len > 0.0f ? axis / len : Vec3(0.0f, 1.0f, 0.0f);
    const Vec3 helper = std::abs(n.x) < 0.9f ? Vec3(1.0f, 0.0f, 0.0f) : Vec3(0.0f, 1.0f, 0.0f);
    const Vec3 u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
    const double phi = 2.0 * 3.14159265358979323846 * rng.uniform();
    return u * static_cast<float>(std::cos(phi)) + v * static_cast<float>(std::sin(phi));
}

}  // namespace

void append_ribbons(const Strands& s, std::uint64_t seed, TriangleMesh& mesh) {
    SceneRng rng(seed);
    for (std::size_t k = 0; k + 1 < s.offsets.size(); ++k) {
        const std::uint32_t first = s.offsets[k], last = s.offsets[k + 1];
        if (last - first < 2) continue;
        const Vec3 side = random_side(s.points[last - 1] - s.points[first], rng);
        // Two vertices per point: left (2i) and right (2i + 1) of the centreline.
        const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
        for (std::uint32_t i = first; i < last; ++i) {
            mesh.vertices.push_back(s.points[i] - side * s.radii[i]);
            mesh.vertices.push_back(s.points[i] + side * s.radii[i]);
        }
        for (std::uint32_t i = 0; i + 1 < last - first; ++i) {
            const std::uint32_t l0 = base + 2 * i, r0 = l0 + 1, l1 = l0 + 2, r1 = l0 + 3;
            const bool wide0 = s.radii[first + i] > 0.0f, wide1 = s.radii[first + i + 1] > 0.0f;
            if (wide0) mesh.triangles.push_back({l0, r0, wide1 ? r1 : l1});
            if (wide1) mesh.triangles.push_back({l0, r1, l1});
        }
    }
}

}  // namespace rtc
