// Two-level acceleration structure: a TLAS over instances, each instance a
// BLAS placed in the world by an affine transform.
//
// At an instance the ray is transformed into object space (one
// InstanceTransform event) with its direction left unnormalized, so the t of a
// hit in a BLAS is directly comparable with hits from other instances.
#pragma once

#include "core/affine.h"
#include "core/bvh.h"
#include "core/instance_box.h"
#include "core/sinks.h"
#include "core/traverse.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace rtc {

// An instance as a method describes it (build_two_level's input).
struct Instance {
    std::uint32_t blas = 0;  // index into TwoLevel::blases
    std::uint32_t id = 0;    // user instance id, handed to the leaf program
    Affine world_from_object;
    CentredAffine object_from_world;  // about world_from_object.translation
};

// An instance as the traversal reads it: what the instance step needs, in one
// 64-byte line. (world_from_object only places the instance's TLAS box.) The
// whole Instance, 104 bytes at a 104-byte stride, spread the same fields over
// two or three lines.
struct alignas(64) TlasInstance {
    CentredAffine object_from_world;
    std::uint32_t blas = 0;
    std::uint32_t id = 0;
};
static_assert(sizeof(TlasInstance) == 64);

struct TwoLevel {
    std::vector<Bvh> blases;
    // In the TLAS's leaf order: leaf slot k holds instance k, and
    // tlas.prim_ids is the identity (build_two_level); the traversal relies
    // on it and indexes instances by leaf slot.
    UninitializedVector<TlasInstance> instances;
    Bvh tlas;  // over the world-space boxes of the instances' BLAS roots
    // Set by build_two_level: the TLAS root is one leaf over one instance
    // whose object_from_world is the identity (ones on the diagonal, zeros
    // of either sign elsewhere, origin 0) and whose BLAS has inner nodes, the shape of
    // the reference method's scene. trace_two_level then skips the instance
    // transform for rays it maps to themselves bit for bit (see
    // passes_identity), counting the same events.
    bool lone_identity = false;

    [[nodiscard]] std::size_t memory_bytes() const;
};

// Makes an instance; throws std::invalid_argument when the transform is
// singular or not finite (it could not be inverted by the hardware either).
[[nodiscard]] Instance make_instance(std::uint32_t blas, std::uint32_t id,
                                     const Affine& world_from_object);

// Builds the TLAS over `instances` (whose BLASes must already be in `blases`).
[[nodiscard]] TwoLevel build_two_level(std::vector<Bvh> blases, std::span<const Instance> instances,
                                       const BuildOptions& tlas_options);
[[nodiscard]] inline TwoLevel build_two_level(std::vector<Bvh> blases, const std::vector<Instance>& instances,
                                              const BuildOptions& tlas_options) {
    return build_two_level(std::move(blases), std::span<const Instance>(instances), tlas_options);
}

// The same TLAS over `count` instances that `instance(i)` makes, called twice
// per instance from the build's threads (for its TLAS box, then in the TLAS's
// leaf order), so that no array of every Instance is made: for the
// masquerade's million instances that array was 104 MB of memory new to the
// process (docs/benchmark.md, issue 19 round 11). `instance` must return the
// same instance for the same i; it may throw (the build then rethrows).
[[nodiscard]] TwoLevel build_two_level(std::vector<Bvh> blases, std::size_t count,
                                       const std::function<Instance(std::size_t)>& instance,
                                       const BuildOptions& tlas_options);

// What a primitive program sees: which instance and primitive, the ray in both
// spaces and the current closest distance.
struct PrimitiveQuery {
    const TlasInstance& instance;
    std::uint32_t instance_index;
    std::uint32_t prim;  // primitive index inside the instance's BLAS
    const Ray& world_ray;
    const Ray& object_ray;
    float tmax;
};

// True when the identity transform (object_from_world of an instance that
// TwoLevel::lone_identity names) maps `ray` to itself bit for bit. Per
// component it computes x - 0, then (1 * x + z1 * y) + z2 * z with signed
// zeros zi (core/instance_box.h's order): exact for finite components, except
// that -0 plus a +0 is +0. So: every origin and direction component finite and none
// -0 (camera and bounce rays nearly always are).
[[nodiscard]] inline bool passes_identity_reference(const Ray& ray) {
    const auto ok = [](float x) { return std::isfinite(x) && !(x == 0.0f && std::signbit(x)); };
    return ok(ray.origin.x) && ok(ray.origin.y) && ok(ray.origin.z) && ok(ray.direction.x) &&
           ok(ray.direction.y) && ok(ray.direction.z);
}

#if defined(__SSE2__)
// passes_identity_reference() on the ray's lanes (core/box_lanes.h's
// RayLanes), for lanes 0-2 of both vectors: lane 3 holds tmin and tmax.
[[nodiscard, gnu::always_inline]] inline bool passes_identity(const RayLanes& r) {
    const __m128 o = r.origin_tmin, d = r.direction_tmax;
    const __m128 zero = _mm_setzero_ps();
    // x - x is 0 for finite x and NaN for an infinity or NaN.
    const __m128 finite = _mm_and_ps(_mm_cmpeq_ps(_mm_sub_ps(o, o), zero), _mm_cmpeq_ps(_mm_sub_ps(d, d), zero));
    // -0.0f's bits in each lane, one load (as a known constant GCC built it
    // from an immediate: three instructions).
    const __m128i minus_zero = _mm_castps_si128(_mm_load_ps(kLaneConstants.minus_zero));
    const __m128i neg0 = _mm_or_si128(_mm_cmpeq_epi32(_mm_castps_si128(o), minus_zero),
                                      _mm_cmpeq_epi32(_mm_castps_si128(d), minus_zero));
    return (_mm_movemask_ps(_mm_andnot_ps(_mm_castsi128_ps(neg0), finite)) & 0x7) == 0x7;
}
#endif

[[nodiscard, gnu::always_inline]] inline bool passes_identity(const Ray& ray) {
#if defined(__SSE2__)
    return passes_identity(RayLanes(ray));
#else
    return passes_identity_reference(ray);
#endif
}

namespace detail {

// The root's one child when it is a leaf (the masquerade's unit-box BLAS).
[[nodiscard]] inline const BvhEntry* one_leaf(const Bvh& b) {
    const bool one = b.root.count == (BvhEntry::kInnerBit | 1u) && !b.entries[b.root.first].is_inner();
    return one ? &b.entries[b.root.first] : nullptr;
}

// A BLAS leaf's primitives handed to `on_prim` one by one, nearest accepted t
// first. Inlined into every caller (the BLAS traversal and the one-leaf path):
// as a call it cost case 1 ref 4 % more instructions.
template <TraversalMode Mode, class PrimFn>
[[gnu::always_inline]] inline auto blas_leaf(const TlasInstance& inst, const std::uint32_t& index, const Bvh& blas,
                                             const Ray& ray, const Ray& object_ray, PrimFn& on_prim) {
    // The leaf ids' array by value: one load fewer per primitive than through blas.
    return [&inst, index, ids = blas.prim_ids.data(), &ray, &object_ray, &on_prim](
               std::uint32_t first, std::uint32_t count, float tmax) __attribute__((always_inline)) {
        float best = kInfinity;
        for (std::uint32_t j = 0; j < count; ++j) {
            const PrimitiveQuery q{inst, index, ids[first + j], ray, object_ray, tmax};
            const float t = on_prim(q);
            if (t < best) best = t;
            if (Mode == TraversalMode::Closest && t < tmax) tmax = t;
            if (Mode == TraversalMode::AnyHit && t < kInfinity) break;
        }
        return best;
    };
}

// trace_instances() for a TwoLevel::lone_identity scene and a ray that
// passes_identity(): the same events, tests and floats, in the same order
// (traverse()'s one-leaf root, the instance step, the BLAS traversal), with
// the world ray as the object ray. One traversal call instead of two, no
// transform, one reciprocal of the direction. Inlined into the tracer: GCC
// stopped inlining it once each method compiled a second tracer (the warp
// model's), and the call cost case 2 ref per-ray 15 instructions per ray.
// With SSE it takes the ray's lanes that passes_identity() loaded: the
// reciprocal and the root's box test use them as they are (case 2 ref: 15
// fewer instructions per ray than three-instruction loads of each Vec3).
template <TraversalMode Mode, class Sink, class PrimFn>
[[gnu::always_inline]] inline float trace_lone_identity(const TwoLevel& scene, const Ray& ray,
#if defined(__SSE2__)
                                                        const RayLanes& lanes,
#endif
                                                        Sink& sink, PrimFn& on_prim) {
    if (Mode == TraversalMode::Closest && ray.tmin > ray.tmax) return kInfinity;
    sink.on(kTlasEvents.node_visit);
    sink.add(kTlasEvents.box_test, 1);
    const BvhEntry& leaf = scene.tlas.entries[scene.tlas.root.first];
#if defined(__SSE2__)
    // Lanes 0-2 are safe_inverse_fast(ray.direction)'s; lane 3 (of tmax) is unused.
    const __m128 inv = safe_inverse_lanes(lanes.direction_tmax);
    const float entry = intersect_box_lanes(leaf.box, lanes.origin_tmin, inv, ray.tmin, ray.tmax);
#else
    const Vec3 inv_dir = safe_inverse_fast(ray.direction);
    const float entry = intersect_lone_box(leaf.box, ray.origin, inv_dir, ray.tmin, ray.tmax);
#endif
    if (entry == kInfinity || (Mode == TraversalMode::Closest && entry > ray.tmax)) return kInfinity;
#if defined(__SSE2__)
    Vec3 inv_dir;
    store3(inv, inv_dir);
#endif
    const std::uint32_t index = leaf.first;  // the leaf ids are the identity (TwoLevel::instances)
    const TlasInstance& inst = scene.instances[index];
    sink.on(Event::InstanceTransform);
    const Bvh& blas = scene.blases[inst.blas];
    const auto on_blas_leaf = blas_leaf<Mode>(inst, index, blas, ray, ray, on_prim);
    // lone_identity's BLAS is not a root over one leaf: traverse() skips that test.
    const float t =
        traverse<Mode, kBlasEvents, false>(blas, ray.origin, inv_dir, ray.tmin, ray.tmax, sink, on_blas_leaf);
    return t < kInfinity ? t : kInfinity;
}

// kLaneInstances: BLASes are traversed by traverse(), so an instance over a
// one-leaf BLAS can take traverse()'s one-leaf path with the transform and
// box test on SIMD lanes (core/instance_box.h), building the object-space ray
// only for the instances whose box the ray enters.
template <TraversalMode Mode, bool kLaneInstances, class Sink, class PrimFn, class BlasFn>
float trace_instances(const TwoLevel& scene, const Ray& ray, Sink& sink, PrimFn&& on_prim,
                      BlasFn&& traverse_blas) {
    const Vec3 inv_dir = safe_inverse_fast(ray.direction);
    const LaneRay lanes(ray);
    // Inlined into the TLAS traversal: as a call, every instance leaf cost a
    // spill and reload of the traversal's broadcast ray registers.
    const auto on_tlas_leaf = [&](std::uint32_t first, std::uint32_t count,
                                  float tmax) __attribute__((always_inline)) {
        float nearest = kInfinity;
        for (std::uint32_t k = 0; k < count; ++k) {
            // The TLAS's leaf ids are the identity (TwoLevel::instances): slot
            // first + k is the instance, without a dependent load of prim_ids.
            const std::uint32_t index = first + k;
            const TlasInstance& inst = scene.instances[index];
            sink.on(Event::InstanceTransform);
            const Bvh& blas = scene.blases[inst.blas];
            const BvhEntry* leaf = kLaneInstances ? one_leaf(blas) : nullptr;
            ObjectRayParts entered;
            if (leaf) {  // traverse()'s events and tests, in its order
                if (Mode == TraversalMode::Closest && ray.tmin > tmax) continue;
                sink.on(kBlasEvents.node_visit);
                sink.add(kBlasEvents.box_test, 1);
                const float entry =
                    intersect_instance_box(inst.object_from_world, leaf->box, lanes, tmax, entered);
                if (entry == kInfinity || (Mode == TraversalMode::Closest && entry > tmax)) continue;
            }
            // The object ray on the lanes (the scalar transform's floats, see
            // object_ray); for a one-leaf BLAS the box test's own transform.
            const Ray object_ray = leaf ? Ray{entered.origin, ray.tmin, entered.direction, tmax}
                                        : rtc::object_ray(inst.object_from_world, lanes, tmax);
            const auto on_blas_leaf = blas_leaf<Mode>(inst, index, blas, ray, object_ray, on_prim);
            float t = kInfinity;
            if (leaf) {
                const float hit = on_blas_leaf(leaf->first, leaf->count, tmax);
                t = hit < kInfinity ? hit : kInfinity;
            } else {
                t = traverse_blas(inst.blas, object_ray, tmax, on_blas_leaf);
            }
            if (t < nearest) nearest = t;
            if (Mode == TraversalMode::Closest && t < tmax) tmax = t;
            if (Mode == TraversalMode::AnyHit && t < kInfinity) break;
        }
        return nearest;
    };
    return traverse<Mode, kTlasEvents>(scene.tlas, ray.origin, inv_dir, ray.tmin, ray.tmax, sink,
                                       on_tlas_leaf);
}

}  // namespace detail

// Traces `ray` through the two levels. `on_prim(const PrimitiveQuery&)` runs for
// every primitive of every BLAS leaf the ray reaches and returns the distance
// of a hit it accepted (or +inf); it prices its own work (triangle test,
// context switch, ...) through the same sink. Returns the nearest accepted t.
//
// trace_two_level_with() lets a method traverse some BLASes its own way:
// `traverse_blas(blas index, object ray, tmax, leaf_fn)` returns the nearest
// accepted t, calling leaf_fn(first, count, tmax) as traverse() does.
template <TraversalMode Mode, class Sink, class PrimFn, class BlasFn>
float trace_two_level_with(const TwoLevel& scene, const Ray& ray, Sink& sink, PrimFn&& on_prim,
                           BlasFn&& traverse_blas) {
    return detail::trace_instances<Mode, false>(scene, ray, sink, on_prim, traverse_blas);
}

template <TraversalMode Mode, class Sink, class PrimFn>
float trace_two_level(const TwoLevel& scene, const Ray& ray, Sink& sink, PrimFn&& on_prim) {
#if defined(__SSE2__)
    if (scene.lone_identity) {
        const RayLanes lanes(ray);
        if (passes_identity(lanes)) return detail::trace_lone_identity<Mode>(scene, ray, lanes, sink, on_prim);
    }
#else
    if (scene.lone_identity && passes_identity(ray))
        return detail::trace_lone_identity<Mode>(scene, ray, sink, on_prim);
#endif
    // The BLAS traversal stays a function of its own: inlined into the TLAS
    // leaf (inlined itself) it cost case 1 ref 7 % more instructions.
    return detail::trace_instances<Mode, true>(
        scene, ray, sink, on_prim,
        [&](std::uint32_t blas, const Ray& object_ray, float tmax, auto&& on_leaf) __attribute__((noinline)) {
            return traverse<Mode, kBlasEvents>(scene.blases[blas], object_ray.origin,
                                               safe_inverse_fast(object_ray.direction), object_ray.tmin,
                                               tmax, sink, on_leaf);
        });
}

}  // namespace rtc
