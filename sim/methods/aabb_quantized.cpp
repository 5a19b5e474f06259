// aabb-quantized: obb-quantized without its rotations. ref's BLASes with
// every node's child boxes rounded outwards to 12 bits of the node's extent
// (RDNA4's quantised children; core/obb_bvh_quantize.cpp), no node rotated:
// the axis-aligned baseline an oriented-box tree is compared with on AMD
// hardware, whose AABB nodes are quantised the same way (Kern et al. 2025,
// "DOBB-BVH", measure their oriented trees against such a BVH8). Against it,
// obb-quantized's speedup is the rotations' alone; against ref, it also
// carries the cost of the quantisation, which ref (float boxes) does not pay.
// The custom-primitive BLAS is always quantised; the triangle BLAS when
// obb-quantized would orient it (bvh.oriented_triangles). Closest hits are
// identical to ref's; no extra bytes; ordinary box tests only.
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

ObbTreeStructures build_aabb_quantized(const Geometry& g, const MethodOptions& o) {
    QuantizeOptions q;
    q.accept = 0.0;  // no rotation is ever accepted: 12-bit axis-aligned children
    return build_quantized_tree(g, o, q);
}

}  // namespace

MethodEntry aabb_quantized_method() {
    return {{"aabb-quantized",
             "ref's BLAS with RDNA4's 12-bit child boxes and no rotation: obb-quantized's axis-aligned baseline",
             {"custom_primitives"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<ObbTreeMethod>>(build_aabb_quantized(g, o));
            }};
}

}  // namespace rtc
