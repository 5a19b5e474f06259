// obb-nodes: a custom-primitive BLAS whose nodes may be oriented, in the
// spirit of Woop et al. 2014 ("Exploiting Local Orientation Similarity for
// Efficient Ray Traversal of Hair and Fur", HPG 2014) and Embree's hair BVH
// (kernels/builders/bvh_builder_hair.h, kernels/bvh/bvh_node_obb.h): the
// builder picks, per split, the lowest SAH among a world-space object split,
// an object split in the frame of the primitives' direction and a strand
// split (core/obb_build.h); a node with an oriented split gives each child its
// own frame and box, tested by the RT unit with that child's transform
// (obb_box_test per child, in place of blas_box_test). Leaf boxes of oriented
// nodes are the primitives' own OBBs, so many rays are culled before a context
// switch, as in the masquerade, without one instance per primitive.
// Hardware: no shipping GPU tests per-child oriented boxes (NVIDIA's patent
// US 11,282,261 describes alternative world spaces inside the unit); the
// method needs the feature "obb_nodes". Closest hits are identical to ref's:
// the same programs run with the world ray and every box is conservative.
// Memory: obb_child bytes extra per oriented child (Embree: a 3x4 affine
// instead of an AABB).
// With bvh.oriented_triangles the triangle BLAS is built the same way over the
// triangles (framed by their longest edges, Geometry's triangle_proxies), one
// triangle per leaf as the builder makes them (ref's mesh BLAS puts up to
// bvh.triangle_leaf_size in a leaf), with a triangle test in place of the
// hand-over in its SAH.
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

// A triangle test in units of one aligned box test, for the triangle BLAS's
// SAH (ObbBuildOptions::intersection): 8 cycles against 4 in
// turing-per-ray-guess (Vulkan-Sim's RTX 2060 range), as the custom
// primitives' 50 is an estimate of the same kind.
constexpr double kTriangleTestInBoxTests = 2.0;

ObbTreeStructures build_obb_nodes(const Geometry& g, const MethodOptions& o) {
    std::vector<Aabb> boxes(g.primitive_count());
    std::visit([&](const auto& prims) {
        parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(prims[i]); });
    }, g.prims);
    ObbBuildOptions b;  // SAH costs: core/obb_build.h
    b.width = o.custom_blas.width;
    b.bins = o.custom_blas.bins;
    std::optional<ObbBvh> mesh;
    if (o.oriented_triangles && !g.triangles.empty()) {
        std::vector<Aabb> triangle_boxes(g.triangles.size());
        parallel_for(g.triangles.size(), o.triangle_blas.threads,
                     [&](std::size_t i, unsigned) { triangle_boxes[i] = bounds(g.triangles[i]); });
        ObbBuildOptions t;
        t.width = o.triangle_blas.width;
        t.bins = o.triangle_blas.bins;
        t.intersection = kTriangleTestInBoxTests;
        mesh = build_obb_bvh(triangle_boxes, triangle_proxies(g), t);
    }
    return make_obb_tree_structures(build_obb_bvh(boxes, bound_proxies(g), b), std::move(mesh), g, o);
}

}  // namespace

MethodEntry obb_nodes_method() {
    return {{"obb-nodes",
             "BLAS with oriented nodes chosen by SAH (Woop et al. 2014, Embree hair BVH); per-child OBB tests in hardware",
             {"custom_primitives", "obb_nodes"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<ObbTreeMethod>>(build_obb_nodes(g, o));
            }};
}

}  // namespace rtc
