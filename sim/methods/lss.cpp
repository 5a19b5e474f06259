// lss: NVIDIA Blackwell's linear swept spheres (NVIDIA developer blog "Render
// Path-Traced Hair in Real Time with NVIDIA GeForce RTX 50 Series GPUs", 2025;
// VK_NV_ray_tracing_linear_swept_spheres; US 2026/0148476 A1). A capsule (one
// radius, round caps) and a link (Han et al. 2019: the hull of two spheres,
// i.e. a sphere swept with linearly varying radius) are LSS primitives, so
// the RT unit tests them itself, as it tests triangles: no context switch, no
// intersection program, one lss_test event per primitive reached. The BLAS is
// ref's (one box per primitive; NVIDIA's LSS bounding is not public) and the
// test is the same shape math as ref's program, so closest hits are identical.
// Cylinders (flat caps) and phantom curves (cubic Beziers) are not LSS: the
// method reports n/a for them (an LSS polyline of a curve would give
// different hits; not modelled). Memory: lss_prim bytes per primitive.
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

#include <stdexcept>

namespace rtc {

namespace {

struct LssLeaf {
    template <class Programs>
    static float custom_leaf(const PrimitiveQuery& q, Programs& programs) {
        return programs.lss(q.prim, q.object_ray, q.tmax);
    }
};

std::string lss_not_applicable(const Geometry& g) {
    if (g.kind == PrimitiveKind::Capsule || g.kind == PrimitiveKind::Link) return {};
    return std::string(kind_name(g.kind)) +
           " primitives are not linear swept spheres (LSS hardware takes capsules and links)";
}

template <class Prim>
TwoLevelStructures build_lss(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<Aabb> boxes(prims.size());
    parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(prims[i]); });
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.custom_blas));
    std::vector<BlasKind> kinds{BlasKind::Lss};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh_blas(g, o, blases, kinds, instances);
    return {build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)};
}

}  // namespace

MethodEntry lss_method() {
    return {{"lss", "capsules and links as linear swept spheres tested in the RT unit (Blackwell): no context switch",
             {"lss"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                if (const std::string why = lss_not_applicable(g); !why.empty())
                    throw std::invalid_argument("lss: " + why);
                return std::make_unique<BuiltMethodOf<TwoLevelMethod<LssLeaf>>>(
                    std::visit([&](const auto& prims) { return build_lss(prims, g, o); }, g.prims));
            },
            lss_not_applicable};
}

}  // namespace rtc
