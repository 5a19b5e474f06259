// Tracing one ray through a method's structures: the leaf programs of the
// simulated hardware (triangle test in hardware; context switch + user
// intersection program for custom primitives) and the closest-hit record.
#pragma once

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "intersectors/triangle.h"
#include "sim/methods/methods.h"
#include "sim/methods/trace_hit.h"

#include <algorithm>
#include <span>
#include <type_traits>
#include <vector>

namespace rtc {

// When intersection programs run (a traversal policy, not a cost):
// Immediate: as OptiX on Turing, when the leaf is reached; an accepted hit
//            shrinks tmax at once.
// Deferred:  as Vulkan-Sim models it, candidates are collected during
//            traversal and the programs run afterwards, so custom hits do not
//            shrink tmax during traversal.
enum class IsSchedule : std::uint8_t { Immediate, Deferred };

struct TraceOptions {
    IsSchedule schedule = IsSchedule::Immediate;
    PhantomOptions phantom;
};

// Per-thread scratch reused across rays (no allocation per ray).
struct TraceScratch {
    std::vector<std::uint32_t> deferred;
};

template <class Prim, class Sink>
std::optional<Hit> run_intersection_program(const Prim& prim, const Ray& ray, Sink& sink,
                                            const TraceOptions& options) {
    if constexpr (std::is_same_v<Prim, PhantomCurve>)
        return intersect(prim, ray, sink, options.phantom);
    else
        return intersect(prim, ray, sink);
}

template <TraversalMode Mode = TraversalMode::Closest, class Prim, class Sink>
TraceHit trace_ray(const MethodAccel& m, std::span<const Prim> prims,
                   std::span<const Triangle> triangles, const Ray& ray, Sink& sink,
                   const TraceOptions& options, TraceScratch& scratch) {
    sink.on(Event::Ray);
    TraceHit best;
    const auto offer = [&](const TraceHit& candidate) {
        if (candidate.closer_than(best)) best = candidate;
        return candidate.t;
    };
    // Both methods call exactly this with the same world-space ray (for ref the
    // object-space ray of its identity instance is bit-identical to it).
    const auto run_program = [&](std::uint32_t index, Ray r, float tmax) {
        sink.on(Event::IsCall);
        r.tmax = tmax;
        const auto h = run_intersection_program(prims[index], r, sink, options);
        if (!h) return kInfinity;
        sink.on(Event::ReportedHit);
        return offer({h->t, h->normal, h->u, index, GeometryId::Curves});
    };
    const bool deferred = options.schedule == IsSchedule::Deferred;
    scratch.deferred.clear();
    const auto on_prim = [&](const PrimitiveQuery& q) -> float {
        if (m.blas_kind[q.instance.blas] == BlasKind::Triangles) {
            Ray r = q.object_ray;
            r.tmax = q.tmax;
            const auto h = intersect(triangles[q.prim], r, sink);
            return h ? offer({h->t, h->normal, h->u, q.prim, GeometryId::Triangles}) : kInfinity;
        }
        sink.on(Event::ContextSwitch);
        const bool ref = m.method == Method::Ref;
        const std::uint32_t index = ref ? q.prim : q.instance.id;
        if (deferred) {
            scratch.deferred.push_back(index);
            return kInfinity;
        }
        return run_program(index, ref ? q.object_ray : q.world_ray, q.tmax);
    };
    trace_two_level<Mode>(m.accel, ray, sink, on_prim);
    for (const std::uint32_t index : scratch.deferred)
        run_program(index, ray,
                    Mode == TraversalMode::Closest ? std::min(best.t, ray.tmax) : ray.tmax);
    return best;
}

}  // namespace rtc
