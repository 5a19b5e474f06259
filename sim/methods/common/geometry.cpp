#include "sim/methods/common/geometry.h"

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

namespace {

BoundProxy proxy(const Vec3& p0, const Vec3& p1, float r) { return {{p0, p1, p1, p1}, std::max(r, 0.0f)}; }
BoundProxy proxy(const Cylinder& c) { return proxy(c.p0, c.p1, c.radius); }
BoundProxy proxy(const Capsule& c) { return proxy(c.p0, c.p1, c.radius); }
BoundProxy proxy(const Link& k) { return proxy(k.p0, k.p1, std::max(k.r0, k.r1)); }
BoundProxy proxy(const PhantomCurve& c) { return {c.cp, max_radius(c)}; }

}  // namespace

std::vector<BoundProxy> bound_proxies(const Geometry& g) {
    std::vector<BoundProxy> out;
    std::visit([&](const auto& v) { for (const auto& p : v) out.push_back(proxy(p)); }, g.prims);
    return out;
}

std::vector<BoundProxy> triangle_proxies(const Geometry& g) {
    std::vector<BoundProxy> out;
    out.reserve(g.triangles.size());
    for (const Triangle& t : g.triangles) {
        const Vec3 v[3] = {t.v0, t.v1, t.v2};
        // The longest edge runs from v[k] to v[(k + 1) % 3]; the third vertex sits between.
        int k = 0;
        float longest = -1.0f;
        for (int e = 0; e < 3; ++e) {
            const Vec3 d = v[(e + 1) % 3] - v[e];
            if (const float l = glm::dot(d, d); l > longest) longest = l, k = e;
        }
        const Vec3& third = v[(k + 2) % 3];
        out.push_back({{v[k], third, third, v[(k + 1) % 3]}, 0.0f});
    }
    return out;
}

float primitive_radius(const Geometry& g, std::uint32_t index) {
    return std::visit([&](const auto& v) { return proxy(v[index]).radius; }, g.prims);
}

Aabb geometry_bounds(const Geometry& g) {
    Aabb b;
    std::visit([&](const auto& v) { for (const auto& p : v) b.extend(bounds(p)); }, g.prims);
    for (const Triangle& t : g.triangles) b.extend(bounds(t));
    return b;
}

}  // namespace rtc
