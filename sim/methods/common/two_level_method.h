// What ref and obb share (and what later two-level methods can reuse): a TLAS
// over instances of BLASes, the optional triangle BLAS for the mesh under an
// identity instance, its structure counts, and the ray path through the two
// levels. A method differs only in its `Leaf` policy: which program a custom
// leaf calls, with which ray and index:
//   template <class Programs>
//   static float custom_leaf(const PrimitiveQuery&, Programs&);
#pragma once

#include "core/obb_build.h"
#include "core/obb_nodes.h"
#include "core/two_level.h"
#include "sim/methods/method.h"

#include <optional>
#include <vector>

namespace rtc {

// Custom: leaves are custom primitives (a hand-over each); Triangles: the
// mesh; Lss: leaves are linear swept spheres tested in the RT unit;
// StandInTriangles: triangles tested in the RT unit that stand in for the
// curve primitives (dots), hits reported as the primitives'.
enum class BlasKind : std::uint8_t { Custom, Triangles, Lss, StandInTriangles };

struct TwoLevelStructures {
    TwoLevel accel;
    std::vector<BlasKind> blas_kind;  // per BLAS
};

// `n` unconstructed instances (the caller writes every one, in parallel)
// with room for add_mesh_blas's one more, for methods that keep an array of
// them (cluster; obb makes its instances on demand, see build_two_level).
// Growing a vector of a million instances by one element moves them all into
// a buffer twice as large (104 MB copied and 208 MB of fresh pages: a quarter
// of the obb build's page faults on configs/runs/head_1m.json when obb still
// kept the array), and constructing them first is a serial pass over fresh
// pages.
[[nodiscard]] UninitializedVector<Instance> instance_slots(std::size_t n);

// The triangle BLAS over the mesh, if the geometry has one.
[[nodiscard]] std::optional<Bvh> mesh_blas(const Geometry& g, const MethodOptions& o);

// Appends the triangle BLAS (if the geometry has a mesh) and returns its
// identity instance (none without a mesh).
[[nodiscard]] std::optional<Instance> add_mesh_blas(const Geometry& g, const MethodOptions& o,
                                                    std::vector<Bvh>& blases, std::vector<BlasKind>& kinds);

// Appends the triangle BLAS (if the geometry has a mesh) and its identity instance.
template <class Instances>
void add_mesh_blas(const Geometry& g, const MethodOptions& o, std::vector<Bvh>& blases,
                   std::vector<BlasKind>& kinds, Instances& instances) {
    if (std::optional<Instance> mesh = add_mesh_blas(g, o, blases, kinds)) instances.push_back(*mesh);
}

[[nodiscard]] StructureCounts count_two_level(const TwoLevelStructures& s);

// The leaf dispatch every two-level method shares: triangles to the RT unit's
// test, every other BLAS's primitives to Leaf::custom_leaf.
template <class Leaf, class Programs>
auto two_level_leaf(const TwoLevelStructures& s, Programs& programs) {
    // The kinds' array by value: one load fewer per primitive than through s.
    return [kinds = s.blas_kind.data(), &programs](const PrimitiveQuery& q) __attribute__((always_inline)) -> float {
        if (kinds[q.instance.blas] == BlasKind::Triangles)
            return programs.triangle(q.prim, q.object_ray, q.tmax);
        return Leaf::custom_leaf(q, programs);
    };
}

template <class Leaf>
struct TwoLevelMethod {
    using Structures = TwoLevelStructures;

    static StructureCounts count(const Structures& s) { return count_two_level(s); }
    static std::size_t bytes(const Structures& s) { return s.accel.memory_bytes(); }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        trace_two_level<Mode>(s.accel, ray, programs.sink(), two_level_leaf<Leaf>(s, programs));
        return programs.template finish<Mode>(ray);
    }
};

// The leaf of methods whose program takes the world-space ray and the
// primitive index straight from the BLAS leaf.
struct WorldRayLeaf {
    template <class Programs>
    static float custom_leaf(const PrimitiveQuery& q, Programs& programs) {
        return programs.custom(q.prim, q.world_ray, q.tmax);
    }
};

// Two-level methods whose custom-primitive BLAS (BLAS 0) has oriented child
// boxes (core/obb_frames.h): obb-nodes (one transform per oriented child, priced
// as extra bytes per child) and obb-quantized (one table rotation per node,
// no extra bytes). The TLAS is ref's; the mesh BLAS (BLAS 1) is ref's, or,
// with MethodOptions::oriented_triangles, oriented the method's own way.
struct ObbTreeStructures {
    TwoLevelStructures two_level;
    ObbFrames frames;       // of BLAS 0's entries
    ObbFrames mesh_frames;  // of the mesh BLAS's entries, when mesh_oriented
    bool mesh_oriented = false;
};

// Wraps an oriented-box tree over the geometry's primitives (ids = primitive
// indices) as BLAS 0 under an identity instance, plus the mesh BLAS: `mesh`
// (an oriented tree over the triangles) if given, else ref's.
[[nodiscard]] ObbTreeStructures make_obb_tree_structures(ObbBvh tree, std::optional<ObbBvh> mesh,
                                                         const Geometry& g, const MethodOptions& o);

// GPURT's pass (quantize_obb_bvh under `q`) on ref's BLAS over the
// primitives and, with bvh.oriented_triangles, on ref's triangle BLAS (a
// triangle's candidate rotation from its longest edge), wrapped as above:
// obb-quantized, and with no rotation accepted its baseline aabb-quantized.
[[nodiscard]] ObbTreeStructures build_quantized_tree(const Geometry& g, const MethodOptions& o,
                                                     const QuantizeOptions& q);

struct ObbTreeMethod {
    using Structures = ObbTreeStructures;

    static StructureCounts count(const Structures& s) {
        StructureCounts c = count_two_level(s.two_level);
        if (s.frames.style == ObbStyle::PerChild) c.oriented_children = s.frames.rotated_entries();
        if (s.mesh_oriented && s.mesh_frames.style == ObbStyle::PerChild)
            c.oriented_children += s.mesh_frames.rotated_entries();
        return c;
    }
    static std::size_t bytes(const Structures& s) {
        return s.two_level.accel.memory_bytes() + s.frames.memory_bytes() + s.mesh_frames.memory_bytes();
    }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        auto& sink = programs.sink();
        const TwoLevel& accel = s.two_level.accel;
        trace_two_level_with<Mode>(
            accel, ray, sink, two_level_leaf<WorldRayLeaf>(s.two_level, programs),
            [&](std::uint32_t blas, const Ray& object_ray, float tmax, auto&& on_leaf) {
                if (blas == 0) return traverse_obb<Mode>(accel.blases[0], s.frames, object_ray, tmax, sink, on_leaf);
                if (s.mesh_oriented)  // the only other BLAS is the mesh's
                    return traverse_obb<Mode>(accel.blases[blas], s.mesh_frames, object_ray, tmax, sink, on_leaf);
                return traverse<Mode, kBlasEvents>(accel.blases[blas], object_ray.origin,
                                                   safe_inverse(object_ray.direction), object_ray.tmin,
                                                   tmax, sink, on_leaf);
            });
        return programs.template finish<Mode>(ray);
    }
};

}  // namespace rtc
