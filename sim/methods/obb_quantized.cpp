// obb-quantized: AMD RDNA4's oriented nodes (RADV src/amd/vulkan/bvh: a BVH8
// box node holds one `obb_matrix_index` into a fixed table of rotations,
// shared by its 8 children; GPURT builds them, see rt-hardware.md section 5).
// The BLAS is ref's AABB tree; then, bottom up, each node takes the table
// rotation of its child with the largest AABB area, bounds its children in
// that frame and keeps it when their areas sum to less than 1.12 x their
// AABBs' (GPURT RefitOrientedBounds3_1.hlsl, OBB_SA_FACTOR_THRESHOLD); every
// node's child boxes are then rounded outwards to 12 bits of the node's extent
// (RDNA4's quantised children), so boxes stay conservative after both
// quantisations. The table is a stand-in with GPURT's size, 104 rotations
// (core/obb_bvh_quantize.cpp says how it compares with AMD's). A rotated node
// costs one node_rotate (the ray's 3x3 transform) and ordinary box tests; no
// extra bytes (the index lives in the 128-B node). Needs the feature
// "quantized_obb_nodes". Closest hits are identical to ref's.
// Note: RDNA4 nodes are 8 wide; the method follows the config's BVH width.
// With bvh.oriented_triangles the same pass runs on ref's triangle BLAS (what
// GPURT does on RDNA4: it orients triangle geometry only; Kern et al. 2025,
// "DOBB-BVH", measure it), a triangle's candidate rotation taken from its
// longest edge (Geometry's triangle_proxies).
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

ObbTreeStructures build_obb_quantized(const Geometry& g, const MethodOptions& o) {
    return build_quantized_tree(g, o, QuantizeOptions{});  // 104 rotations, accept below 1.12, 12-bit children
}

}  // namespace

MethodEntry obb_quantized_method() {
    return {{"obb-quantized",
             "ref's BLAS with one rotation per node from a table of 104 (AMD RDNA4 / GPURT), 12-bit child boxes",
             {"custom_primitives", "quantized_obb_nodes"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<ObbTreeMethod>>(build_obb_quantized(g, o));
            }};
}

}  // namespace rtc
