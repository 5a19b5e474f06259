#include "sim/methods/two_level_method.h"

namespace rtc {

void add_mesh_blas(const Geometry& g, const MethodOptions& o, std::vector<Bvh>& blases,
                   std::vector<BlasKind>& kinds, std::vector<Instance>& instances) {
    if (g.triangles.empty()) return;
    std::vector<Aabb> boxes;
    boxes.reserve(g.triangles.size());
    for (const Triangle& t : g.triangles) boxes.push_back(bounds(t));
    blases.push_back(build_bvh(boxes, o.triangle_blas));
    kinds.push_back(BlasKind::Triangles);
    instances.push_back(make_instance(static_cast<std::uint32_t>(blases.size() - 1), 0, Affine{}));
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
        (s.blas_kind[b] == BlasKind::Triangles ? c.triangles : c.custom_prims) += blas.primitive_count();
    }
    return c;
}

}  // namespace rtc
