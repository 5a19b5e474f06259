#include "sim/methods/methods.h"

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "core/parallel.h"

#include <stdexcept>

namespace rtc {

std::optional<Method> method_from_name(std::string_view s) {
    return enum_from_name<Method>(kMethodNames, s);
}

std::size_t Geometry::primitive_count() const {
    return std::visit([](const auto& v) { return v.size(); }, prims);
}

Geometry make_geometry(const Scene& scene, PrimitiveKind kind, int subdivision) {
    Geometry g;
    g.kind = kind;
    g.prims = to_primitives(scene.strands, kind, subdivision);
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

std::uint64_t instance_count(Method method, const Geometry& g) {
    const std::uint64_t mesh = g.triangles.empty() ? 0 : 1;
    return method == Method::Ref ? 1 + mesh : g.primitive_count() + mesh;
}

namespace {

// Adds the triangle BLAS (if any) and its identity instance.
void add_mesh(const Geometry& g, const MethodOptions& o, std::vector<Bvh>& blases,
              std::vector<BlasKind>& kinds, std::vector<Instance>& instances) {
    if (g.triangles.empty()) return;
    std::vector<Aabb> boxes;
    boxes.reserve(g.triangles.size());
    for (const Triangle& t : g.triangles) boxes.push_back(bounds(t));
    blases.push_back(build_bvh(boxes, o.triangle_blas));
    kinds.push_back(BlasKind::Triangles);
    instances.push_back(make_instance(static_cast<std::uint32_t>(blases.size() - 1), 0, Affine{}));
}

template <class Prim>
MethodAccel build_ref(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<Aabb> boxes(prims.size());
    parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(prims[i]); });
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.custom_blas));
    std::vector<BlasKind> kinds{BlasKind::Custom};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh(g, o, blases, kinds, instances);
    return {Method::Ref, build_two_level(std::move(blases), std::move(instances), o.tlas),
            std::move(kinds)};
}

template <class Prim>
MethodAccel build_obb(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(std::vector<Aabb>{kUnitBox}, o.custom_blas));
    std::vector<BlasKind> kinds{BlasKind::Custom};
    // One instance per primitive (each slot written by one task: deterministic).
    std::vector<Instance> instances(prims.size());
    parallel_for(prims.size(), o.tlas.threads, [&](std::size_t i, unsigned) {
        instances[i] = make_instance(0, static_cast<std::uint32_t>(i), oriented_bounds(prims[i], o.obb).world_from_unit);
    });
    add_mesh(g, o, blases, kinds, instances);
    return {Method::Obb, build_two_level(std::move(blases), std::move(instances), o.tlas),
            std::move(kinds)};
}

}  // namespace

MethodAccel build_method(Method method, const Geometry& g, const MethodOptions& o) {
    return std::visit(
        [&](const auto& prims) {
            return method == Method::Ref ? build_ref(prims, g, o) : build_obb(prims, g, o);
        },
        g.prims);
}

}  // namespace rtc
