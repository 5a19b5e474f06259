// What the simulated hardware does when traversal reaches a primitive, shared
// by every method: a triangle is tested in the RT unit; a custom primitive is
// a context switch into its user intersection program on the SM, run at once
// or deferred to the end of traversal. A method decides which leaves reach
// which of these, with which ray and index; this file decides what happens
// there and keeps the closest hit.
#pragma once

#include "core/affine.h"
#include "core/obb.h"
#include "core/ops.h"
#include "core/sinks.h"
#include "core/traverse.h"
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "intersectors/triangle.h"
#include "sim/hardware/call_profiles.h"
#include "sim/hardware/trace_hit.h"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace rtc {

// When intersection programs run (a traversal policy, not a cost):
// Immediate: as OptiX on Turing, when the leaf is reached; an accepted hit
//            shrinks tmax at once.
// Deferred:  as Vulkan-Sim models it, candidates are collected during
//            traversal and the programs run afterwards (with the world-space
//            ray), so custom hits do not shrink tmax during traversal.
enum class IsSchedule : std::uint8_t { Immediate, Deferred };

struct TraceOptions {
    IsSchedule schedule = IsSchedule::Immediate;
    PhantomOptions phantom;
};

// Per-thread scratch reused across rays (no allocation per ray).
struct TraceScratch {
    std::vector<std::uint32_t> deferred;
    // The SIMT model needs each program call's own events: a LeafPrograms
    // that records calls (kRecordCalls) counts each call into a slot of its
    // own here (cleared per ray). The frame looks their profile ids up after
    // the ray (WarpFrame::add_lane), not after each call, where the lookup's
    // 16-byte loads read counts the program had just written in 2-byte adds,
    // which the store buffer cannot forward (inferred: this VM has no
    // hardware counters; the warp model's wall time fell 7-11 %,
    // docs/benchmark.md).
    CallCounts calls;
};

template <class Prim, class Sink>
std::optional<Hit> run_intersection_program(const Prim& prim, const Ray& ray, Sink& sink,
                                            const TraceOptions& options) {
    if constexpr (std::is_same_v<Prim, PhantomCurve>)
        return intersect(prim, ray, sink, options.phantom);
    else
        return intersect(prim, ray, sink);
}

// The software OBB test's operations (conventions: core/ops.h): the
// primitive's 3 x 4 map (48 B, 3 loads), the ray's origin (12) and direction
// (9) mapped, the direction's reciprocals (3), the slab test (12 and 8 min
// and max) and its two branches.
inline constexpr Ops kLeafObbTest{.fma = 41, .div = 3, .branch = 2, .load = 3};

// The leaf handling of one ray. A method's trace function calls begin(),
// then triangle() / custom() for each primitive its traversal reaches (each
// returns the distance of an accepted hit, or +inf), then finish().
// kRecordCalls: each program call's own counts are recorded for the SIMT
// model (scratch.calls). A compile-time flag, not a runtime test,
// so that the per-ray model's traversal is compiled without any recording
// (a runtime branch here changed how GCC inlined the per-ray path).
template <class Prim, class Sink, bool kRecordCalls = false>
class LeafPrograms {
public:
    LeafPrograms(std::span<const Prim> prims, std::span<const Triangle> triangles,
                 const TraceOptions& options, TraceScratch& scratch, Sink& sink)
        : prims_(prims), triangles_(triangles), options_(options), scratch_(scratch), sink_(sink),
          deferred_(options.schedule == IsSchedule::Deferred) {
        scratch_.deferred.clear();  // emptied by every finish() after this
    }

    [[nodiscard]] Sink& sink() { return sink_; }

    void begin() {
        sink_.on(Event::Ray);
        best_ = {};
        if constexpr (kRecordCalls) scratch_.calls.clear();
    }

    // A hardware ray/triangle test (object-space ray of the triangle's instance).
    float triangle(std::uint32_t index, Ray object_ray, float tmax) {
        object_ray.tmax = tmax;
        const auto h = intersect(triangles_[index], object_ray, sink_);
        return h ? offer({h->t, h->normal, h->u, index, GeometryId::Triangles}) : kInfinity;
    }

    // A hardware ray/triangle test of a triangle that stands in for curve
    // primitive `prim` (dots: crossed quads per segment). The RT unit does
    // exactly what it does for a mesh triangle; the hit is reported as the
    // primitive's, so it competes with (and is compared with) curve hits.
    float proxy_triangle(const Triangle& tri, std::uint32_t prim, Ray object_ray, float tmax) {
        object_ray.tmax = tmax;
        const auto h = intersect(tri, object_ray, sink_);
        return h ? offer({h->t, h->normal, h->u, prim, GeometryId::Curves}) : kInfinity;
    }

    // A custom-primitive leaf: the hand-over to the SM, then primitive
    // `index`'s program with `ray` (now, or after traversal when deferred).
    float custom(std::uint32_t index, const Ray& ray, float tmax) {
        sink_.on(Event::ContextSwitch);
        if (deferred_) {
            scratch_.deferred.push_back(index);
            return kInfinity;
        }
        return run_program(index, ray, tmax);
    }

    // Programs start with an Embree-style OBB test (curveNi_intersector.h):
    // per primitive the map of its OBB onto the unit box; a ray that misses
    // it (or enters it beyond the current hit) skips the program's body.
    void set_leaf_obbs(std::span<const CentredAffine> unit_from_world) { leaf_obbs_ = unit_from_world; }

    // A hardware ray/LSS test in the RT unit (capsules and links are linear
    // swept spheres: both end spheres and the tangent cone between them): no
    // hand-over and no program; the closest hit is kept as for triangles.
    float lss(std::uint32_t index, Ray ray, float tmax) {
        sink_.on(Event::LssTest);
        if constexpr (std::is_same_v<Prim, Capsule> || std::is_same_v<Prim, Link>) {
            ray.tmax = tmax;
            NullSink math;  // the shape's math; its cost is the LssTest event
            const auto h = intersect(prims_[index], ray, math);
            return h ? offer({h->t, h->normal, h->u, index, GeometryId::Curves}) : kInfinity;
        } else {
            throw std::logic_error("lss: only capsules and links are linear swept spheres");
        }
    }

    // Runs the deferred programs (world-space ray) and returns the closest
    // hit. The list is emptied here, not in begin(), and only read under the
    // deferred schedule: an immediate ray tests one flag.
    template <TraversalMode Mode>
    TraceHit finish(const Ray& ray) {
        if (deferred_ && !scratch_.deferred.empty()) {
            for (const std::uint32_t index : scratch_.deferred)
                run_program(index, ray,
                            Mode == TraversalMode::Closest ? std::min(best_.t, ray.tmax) : ray.tmax);
            scratch_.deferred.clear();
        }
        return best_;
    }

private:
    float offer(const TraceHit& candidate) {
        if (candidate.closer_than(best_)) best_ = candidate;
        return candidate.t;
    }

    [[gnu::always_inline]] float run_program(std::uint32_t index, Ray ray, float tmax) {
        ray.tmax = tmax;
        if constexpr (kRecordCalls) {  // the call's events into the ray's and apart
            static_assert(std::is_same_v<Sink, CountingSink>, "recorded calls count into a CountingSink");
            CallSink call{sink_, scratch_.calls.add()};  // a zeroed slot
            return program(index, ray, call);
        } else {
            return program(index, ray, sink_);
        }
    }

    template <class ProgramSink>
    [[gnu::always_inline]] float program(std::uint32_t index, const Ray& ray, ProgramSink& sink) {
        if (!leaf_obbs_.empty()) {
            // The same float operations as the hardware's instance transform +
            // unit-box test of the masquerade (obb), so the same rays pass.
            sink.on(Event::LeafObbTest);
            count_ops(sink, kLeafObbTest);
            const Ray u = leaf_obbs_[index].ray(ray);
            if (intersect_box(kUnitBox, u.origin, safe_inverse(u.direction), u.tmin, u.tmax) == kInfinity)
                return kInfinity;
        }
        sink.on(Event::IsCall);
        const auto h = run_intersection_program(prims_[index], ray, sink, options_);
        if (!h) return kInfinity;
        sink.on(Event::ReportedHit);
        return offer({h->t, h->normal, h->u, index, GeometryId::Curves});
    }

    std::span<const Prim> prims_;
    std::span<const Triangle> triangles_;
    const TraceOptions& options_;
    TraceScratch& scratch_;
    Sink& sink_;
    // options_.schedule == Deferred, read per program call without going
    // through the options' reference.
    bool deferred_;
    TraceHit best_;
    std::span<const CentredAffine> leaf_obbs_;
};

}  // namespace rtc
