// cluster: the clustered masquerade, the future work Wald et al. 2020 name
// (apply the ray transform to whole subtrees; ../shared/docs/method.md).
// Primitives are grouped into clusters of k (cluster_groups.h: strand runs or
// orientation-similarity splitting); each cluster's BLAS is built over its
// members' boxes expressed in the cluster's own rotated frame, and one TLAS
// instance per cluster maps that frame to world. The hardware transforms the
// ray once per cluster and then tests oriented boxes all the way down; a BLAS
// leaf is a context switch into the same intersection program as obb's, with
// the world-space ray and the primitive's global index.
//
// A cluster of one primitive is exactly the masquerade: the shared unit-box
// BLAS under the primitive's OBB, so size 1 reproduces obb count for count.
//
// The program's index: the instance id is the cluster's first slot in the
// members table, the BLAS primitive index the offset in it. A real renderer
// would reorder its primitive buffer by cluster at build time and index it
// with instance id + primitive index (OptiX's instanceId has 32 bits), so the
// memory model charges no table. (DXR's InstanceID has 24 bits: above 2^24
// primitives it would need 4 B per instance, or, for the orientation
// strategy whose clusters all hold k but the last, instance index * k.)
#include "core/parallel.h"
#include "sim/methods/common/cluster_groups.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rtc {

namespace {

struct ClusterStructures {
    TwoLevelStructures two;
    std::vector<std::uint32_t> members;  // global primitive of each cluster slot
};

struct ClusterMethod {
    using Structures = ClusterStructures;

    static StructureCounts count(const Structures& s) { return count_two_level(s.two); }
    static std::size_t bytes(const Structures& s) {
        return s.two.accel.memory_bytes() + s.members.capacity() * sizeof(std::uint32_t);
    }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        trace_two_level<Mode>(s.two.accel, ray, programs.sink(), [&](const PrimitiveQuery& q) -> float {
            if (s.two.blas_kind[q.instance.blas] == BlasKind::Triangles)
                return programs.triangle(q.prim, q.object_ray, q.tmax);
            return programs.custom(s.members[q.instance.id + q.prim], q.world_ray, q.tmax);
        });
        return programs.template finish<Mode>(ray);
    }
};

// The simulator's bytes per cluster of k >= 2 primitives beyond the shared
// per-primitive figure: the cluster's own small BLAS, built one after another
// on every core, leaves the C library's heap fragmented, far beyond the
// structures' own ~550 B (report.json: simulator.structure_bytes). Measured
// peaks (GNU time, max RSS, --threads 2, procedural fur, ref then cluster,
// orientation and strand strategies alike), minus ref's 218 B per primitive:
//   size 2: 0.25 M capsules 1.45 GB, 0.5 M 3.49 GB, 1 M 6.89 GB: 11-13.5 KB per cluster;
//   size 4: 1 M 1.17 GB: 3.8 KB;  size 8: 1 M 0.27 GB and size 16: 0.27 GB: under 1 KB.
// (The 20 M fur at size 2, 10 M clusters, needs ~135 GB: it was killed at
// 24.3 GB while the estimate, without this term, said 7.82 GiB.) With margin:
double bytes_per_cluster(int k) {
    if (k < 4) return 16384.0;
    if (k < 8) return 5120.0;
    return 1536.0;
}

std::uint64_t cluster_count(const Geometry& g, const ClusterOptions& o) {
    if (o.strategy == ClusterStrategy::Strand) return strand_cluster_count(g.primitive_count(), g.strand_first, o.size);
    const std::uint64_t k = static_cast<std::uint64_t>(std::max(o.size, 1));
    return (g.primitive_count() + k - 1) / k;
}

template <class Prim>
ClusterStructures build_cluster(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    const std::span<const Prim> p(prims);
    for (std::size_t i = 0; i < prims.size(); ++i)  // before any geometry is formed from them
        if (!bounds(prims[i]).finite())
            throw std::invalid_argument("cluster: primitive " + std::to_string(i) +
                                        " has a NaN or infinite bounding box");
    Clusters c = o.cluster.strategy == ClusterStrategy::Strand
                     ? group_strand(prims.size(), g.strand_first, o.cluster.size)
                     : group_orientation(p, o.cluster.size, o.custom_blas.threads);
    const std::size_t n = c.count();
    // Clusters of one share the unit-box BLAS (index 0); the others get their own.
    bool singles = false;
    for (std::size_t i = 0; i < n; ++i) singles = singles || c.first[i + 1] - c.first[i] == 1;
    std::vector<std::uint32_t> blas_of(n, 0);
    std::uint32_t blas_count = singles ? 1 : 0;
    for (std::size_t i = 0; i < n; ++i)
        if (c.first[i + 1] - c.first[i] > 1) blas_of[i] = blas_count++;
    std::vector<Bvh> blases(blas_count);
    if (singles) blases[0] = build_bvh(std::vector<Aabb>{kUnitBox}, o.custom_blas);
    BuildOptions one = o.custom_blas;
    one.threads = 1;
    UninitializedVector<Instance> instances = instance_slots(n);
    parallel_for(n, o.custom_blas.threads, [&](std::size_t i, unsigned) {
        const std::span<const std::uint32_t> members =
            std::span<const std::uint32_t>(c.members).subspan(c.first[i], c.first[i + 1] - c.first[i]);
        if (members.size() == 1) {
            instances[i] = make_instance(0, c.first[i], oriented_bounds(prims[members[0]], o.obb).world_from_unit);
            return;
        }
        const FramedCluster f = frame_cluster(p, members, o.cluster.frame);
        blases[blas_of[i]] = build_bvh(f.boxes, one);
        instances[i] = make_instance(blas_of[i], c.first[i], f.world_from_frame);
    });
    std::vector<BlasKind> kinds(blases.size(), BlasKind::Custom);
    add_mesh_blas(g, o, blases, kinds, instances);
    return {{build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)},
            std::move(c.members)};
}

}  // namespace

MethodEntry cluster_method() {
    return {{"cluster",
             "one instance per cluster of primitives, its BLAS built in the cluster's rotated frame "
             "(the paper's future work; config block \"cluster\")",
             {"custom_primitives", "instance_transforms"}},
            [](const Geometry& g, const MethodOptions& o) -> std::uint64_t {
                return cluster_count(g, o.cluster) + (g.triangles.empty() ? 0 : 1);
            },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<ClusterMethod>>(
                    std::visit([&](const auto& prims) { return build_cluster(prims, g, o); }, g.prims));
            },
            nullptr,
            [](double primitives, double strands, const MethodOptions& o) {
                const double k = std::max(o.cluster.size, 1);
                // Strand clusters do not cross strands: one part-filled per strand at most.
                const double clusters = std::ceil(primitives / k) +
                                        (o.cluster.strategy == ClusterStrategy::Strand && k > 1 ? strands : 0.0);
                if (k == 1) return MethodFootprint{clusters, 200.0 * clusters};  // obb's (obb.cpp)
                return MethodFootprint{clusters, clusters * (200.0 + bytes_per_cluster(o.cluster.size))};
            }};
}

}  // namespace rtc
