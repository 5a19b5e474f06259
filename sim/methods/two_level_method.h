// What ref and obb share (and what later two-level methods can reuse): a TLAS
// over instances of BLASes, the optional triangle BLAS for the mesh under an
// identity instance, its structure counts, and the ray path through the two
// levels. A method differs only in its `Leaf` policy: which program a custom
// leaf calls, with which ray and index:
//   template <class Programs>
//   static float custom_leaf(const PrimitiveQuery&, Programs&);
#pragma once

#include "core/two_level.h"
#include "sim/methods/method.h"

#include <vector>

namespace rtc {

enum class BlasKind : std::uint8_t { Custom, Triangles };

struct TwoLevelStructures {
    TwoLevel accel;
    std::vector<BlasKind> blas_kind;  // per BLAS
};

// Appends the triangle BLAS (if the geometry has a mesh) and its identity instance.
void add_mesh_blas(const Geometry& g, const MethodOptions& o, std::vector<Bvh>& blases,
                   std::vector<BlasKind>& kinds, std::vector<Instance>& instances);

[[nodiscard]] StructureCounts count_two_level(const TwoLevelStructures& s);

template <class Leaf>
struct TwoLevelMethod {
    using Structures = TwoLevelStructures;

    static StructureCounts count(const Structures& s) { return count_two_level(s); }
    static std::size_t bytes(const Structures& s) { return s.accel.memory_bytes(); }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        trace_two_level<Mode>(s.accel, ray, programs.sink(), [&](const PrimitiveQuery& q) -> float {
            if (s.blas_kind[q.instance.blas] == BlasKind::Triangles)
                return programs.triangle(q.prim, q.object_ray, q.tmax);
            return Leaf::custom_leaf(q, programs);
        });
        return programs.template finish<Mode>(ray);
    }
};

}  // namespace rtc
