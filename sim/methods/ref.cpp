// ref: the reference method of Wald et al. 2020. One custom-primitive BLAS
// over the primitives' AABBs (+ the optional triangle BLAS) under a tiny TLAS;
// every leaf box the ray reaches is a context switch into the intersection
// program, which gets the object-space ray (bit-identical to the world ray:
// the instance is the identity) and the primitive index.
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

struct RefLeaf {
    template <class Programs>
    static float custom_leaf(const PrimitiveQuery& q, Programs& programs) {
        return programs.custom(q.prim, q.object_ray, q.tmax);
    }
};

template <class Prim>
TwoLevelStructures build_ref(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<Aabb> boxes(prims.size());
    parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(prims[i]); });
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.custom_blas));
    std::vector<BlasKind> kinds{BlasKind::Custom};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh_blas(g, o, blases, kinds, instances);
    return {build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)};
}

}  // namespace

MethodEntry ref_method() {
    return {{"ref", "custom-primitive AABBs in one BLAS; a context switch per leaf box reached",
             {"custom_primitives"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<TwoLevelMethod<RefLeaf>>>(
                    std::visit([&](const auto& prims) { return build_ref(prims, g, o); }, g.prims));
            }};
}

}  // namespace rtc
