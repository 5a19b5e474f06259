// UV sphere mesh (see sphere_mesh.h).
#include "scenes/generators/sphere_mesh.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rtc {

TriangleMesh make_sphere_mesh(const Vec3& center, float radius, int rings, int sectors) {
    if (rings < 2 || sectors < 3) throw std::invalid_argument("sphere mesh: too few rings or sectors");
    TriangleMesh m;
    // Poles are single vertices so no degenerate triangles appear there.
    m.vertices.push_back(center + Vec3(0, radius, 0));
    for (int i = 1; i < rings; ++i) {
        const double theta = std::numbers::pi * i / rings;
        for (int j = 0; j < sectors; ++j) {
            const double phi = 2.0 * std::numbers::pi * j / sectors;
            m.vertices.push_back(center + radius * Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
                                                        static_cast<float>(std::cos(theta)),
                                                        static_cast<float>(-std::sin(theta) * std::sin(phi))));
        }
    }
    const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
    m.vertices.push_back(center - Vec3(0, radius, 0));
    auto ring = [&](int i, int j) {  // vertex j of interior ring i (1-based)
        return static_cast<std::uint32_t>(1 + (i - 1) * sectors + (j % sectors));
    };
    for (int j = 0; j < sectors; ++j) m.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            m.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
            m.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
        }
    for (int j = 0; j < sectors; ++j)
        m.triangles.push_back({bottom, ring(rings - 1, j + 1), ring(rings - 1, j)});
    return m;
}

}  // namespace rtc
