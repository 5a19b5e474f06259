#include "sim/methods/geometry.h"

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"

namespace rtc {

std::size_t Geometry::primitive_count() const {
    return std::visit([](const auto& v) { return v.size(); }, prims);
}

Geometry make_geometry(const Scene& scene, PrimitiveKind kind, int subdivision) {
    Geometry g;
    g.kind = kind;
    g.prims = to_primitives(scene.strands, kind, subdivision);
    const std::vector<std::uint32_t> strand = primitive_strands(scene.strands, kind, subdivision);
    for (std::size_t i = 0; i < strand.size(); ++i)
        if (i == 0 || strand[i] != strand[i - 1]) g.strand_first.push_back(static_cast<std::uint32_t>(i));
    g.triangles.reserve(scene.mesh.triangles.size());
    for (const auto& t : scene.mesh.triangles)
        g.triangles.push_back({scene.mesh.vertices[t[0]], scene.mesh.vertices[t[1]],
                               scene.mesh.vertices[t[2]]});
    return g;
}

Aabb geometry_bounds(const Geometry& g) {
    Aabb b;
    std::visit([&](const auto& v) { for (const auto& p : v) b.extend(bounds(p)); }, g.prims);
    for (const Triangle& t : g.triangles) b.extend(bounds(t));
    return b;
}

}  // namespace rtc
