#include "sim/methods/common/two_level_method.h"

#include "core/bvh.h"
#include "core/parallel.h"
#include "sim/methods/common/geometry.h"

#include <variant>

namespace rtc {

UninitializedVector<Instance> instance_slots(std::size_t n) {
    UninitializedVector<Instance> instances;
    instances.reserve(n + 1);
    instances.resize(n);
    return instances;
}

std::optional<Bvh> mesh_blas(const Geometry& g, const MethodOptions& o) {
    if (g.triangles.empty()) return std::nullopt;
    std::vector<Aabb> boxes;
    boxes.reserve(g.triangles.size());
    for (const Triangle& t : g.triangles) boxes.push_back(bounds(t));
    return build_bvh(boxes, o.triangle_blas);
}

std::optional<Instance> add_mesh_blas(const Geometry& g, const MethodOptions& o, std::vector<Bvh>& blases,
                                      std::vector<BlasKind>& kinds) {
    std::optional<Bvh> mesh = mesh_blas(g, o);
    if (!mesh) return std::nullopt;
    blases.push_back(std::move(*mesh));
    kinds.push_back(BlasKind::Triangles);
    return make_instance(static_cast<std::uint32_t>(blases.size() - 1), 0, Affine{});
}

ObbTreeStructures make_obb_tree_structures(ObbBvh tree, std::optional<ObbBvh> mesh, const Geometry& g,
                                           const MethodOptions& o) {
    std::vector<Bvh> blases;
    blases.push_back(std::move(tree.bvh));
    std::vector<BlasKind> kinds{BlasKind::Custom};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    ObbFrames mesh_frames;
    const bool mesh_oriented = mesh.has_value() && !g.triangles.empty();
    if (mesh_oriented) {
        blases.push_back(std::move(mesh->bvh));
        kinds.push_back(BlasKind::Triangles);
        instances.push_back(make_instance(1, 0, Affine{}));
        mesh_frames = std::move(mesh->frames);
    } else {
        add_mesh_blas(g, o, blases, kinds, instances);
    }
    return {{build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)},
            std::move(tree.frames), std::move(mesh_frames), mesh_oriented};
}

StructureCounts count_two_level(const TwoLevelStructures& s) {
    StructureCounts c;
    c.width = s.accel.tlas.width;
    c.tlas_nodes = s.accel.tlas.node_count();
    c.instances = s.accel.instances.size();
    c.blases = s.accel.blases.size();
    for (std::size_t b = 0; b < s.accel.blases.size(); ++b) {
        const Bvh& blas = s.accel.blases[b];
        c.blas_nodes += blas.node_count();
        const BlasKind k = s.blas_kind[b];
        const bool triangles = k == BlasKind::Triangles || k == BlasKind::StandInTriangles;
        (triangles ? c.triangles : k == BlasKind::Lss ? c.lss_prims : c.custom_prims) += blas.primitive_count();
    }
    return c;
}

ObbTreeStructures build_quantized_tree(const Geometry& g, const MethodOptions& o, const QuantizeOptions& q) {
    std::vector<Aabb> boxes(g.primitive_count());
    std::visit([&](const auto& prims) {
        parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(prims[i]); });
    }, g.prims);
    std::optional<ObbBvh> mesh;
    if (o.oriented_triangles)
        if (std::optional<Bvh> tree = mesh_blas(g, o)) mesh = quantize_obb_bvh(std::move(*tree), triangle_proxies(g), q);
    return make_obb_tree_structures(quantize_obb_bvh(build_bvh(boxes, o.custom_blas), bound_proxies(g), q),
                                    std::move(mesh), g, o);
}

}  // namespace rtc
