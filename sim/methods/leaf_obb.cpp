// leaf-obb: Embree's per-curve OBB test (kernels/geometry/curveNi.h and
// curveNi_intersector.h: each leaf stores a quantised OBB per curve and tests
// them before the curve intersector) moved to the start of the intersection
// program on RT hardware. The structures are ref's (one custom-primitive BLAS
// over the AABBs), so every leaf box reached is still a context switch; the
// program first tests the ray against the primitive's OBB (the same box the
// masquerade builds, obb.cpp) and returns at once on a miss or when the box
// starts beyond the current hit. The software test is its own event
// (leaf_obb_test); a program body runs (is_call) only for rays that pass.
// Closest hits are identical to ref's: the OBB contains the primitive and is
// tested with the same float operations as the masquerade's unit-box test.
// Memory: one OBB per primitive beside the BLAS (leaf_obb bytes).
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

struct LeafObbStructures {
    TwoLevelStructures two_level;
    std::vector<CentredAffine> unit_from_world;  // per primitive: world -> its OBB's unit box
};

struct WorldRayLeaf {
    template <class Programs>
    static float custom_leaf(const PrimitiveQuery& q, Programs& programs) {
        return programs.custom(q.prim, q.world_ray, q.tmax);
    }
};

struct LeafObbMethod {
    using Structures = LeafObbStructures;

    static StructureCounts count(const Structures& s) {
        StructureCounts c = count_two_level(s.two_level);
        c.leaf_obbs = s.unit_from_world.size();
        return c;
    }
    static std::size_t bytes(const Structures& s) {
        return s.two_level.accel.memory_bytes() + s.unit_from_world.capacity() * sizeof(CentredAffine);
    }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        programs.set_leaf_obbs(s.unit_from_world);
        trace_two_level<Mode>(s.two_level.accel, ray, programs.sink(),
                              two_level_leaf<WorldRayLeaf>(s.two_level, programs));
        return programs.template finish<Mode>(ray);
    }
};

template <class Prim>
LeafObbStructures build_leaf_obb(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<Aabb> boxes(prims.size());
    std::vector<CentredAffine> unit_from_world(prims.size());
    parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) {
        boxes[i] = bounds(prims[i]);
        // make_instance inverts exactly as the masquerade's instances do.
        unit_from_world[i] = make_instance(0, 0, oriented_bounds(prims[i], o.obb).world_from_unit).object_from_world;
    });
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.custom_blas));
    std::vector<BlasKind> kinds{BlasKind::Custom};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh_blas(g, o, blases, kinds, instances);
    return {{build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)},
            std::move(unit_from_world)};
}

}  // namespace

MethodEntry leaf_obb_method() {
    return {{"leaf-obb",
             "ref's BLAS; each intersection program starts with a software OBB test (Embree curveNi)",
             {"custom_primitives"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<LeafObbMethod>>(
                    std::visit([&](const auto& prims) { return build_leaf_obb(prims, g, o); }, g.prims));
            }};
}

}  // namespace rtc
