// The traversal kernel: stack-based, nearest child first, over one BVH level.
//
// Policies are template parameters (no virtual call on the ray's path):
// - Mode: Closest (leaf hits shrink tmax), AnyHit (stop at the first leaf hit)
//   or AllCandidates (never shrink tmax, reach every leaf whose box the ray
//   pierces: the brute-force reference for counting tests).
// - LeafFn: `float(std::uint32_t first, std::uint32_t count, float tmax)`
//   handles a leaf's primitives `bvh.prim_ids[first, first + count)` and
//   returns the nearest hit distance it accepted, or +inf.
// - Sink: receives one node-visit event per node and one box-test event per
//   child box (which events, TLAS or BLAS, is the Level parameter).
#pragma once

#include "core/bvh.h"
#include "core/events.h"

#include <cstdint>

namespace rtc {

enum class TraversalMode { Closest, AnyHit, AllCandidates };

struct LevelEvents {
    Event node_visit;
    Event box_test;
};
inline constexpr LevelEvents kTlasEvents{Event::TlasNodeVisit, Event::TlasBoxTest};
inline constexpr LevelEvents kBlasEvents{Event::BlasNodeVisit, Event::BlasBoxTest};

// Stack bound: the builder limits a tree's depth (see bvh_build.cpp), and each
// visited node pushes at most width - 1 entries beyond the one popped next.
inline constexpr int kTraversalStackSize = 96 * 8;

template <TraversalMode Mode, LevelEvents Level, class Sink, class LeafFn>
float traverse(const Bvh& bvh, const Vec3& origin, const Vec3& inv_dir, float tmin, float tmax,
               Sink& sink, LeafFn&& on_leaf) {
    struct Pending { std::uint32_t first, count; float tnear; };
    Pending stack[kTraversalStackSize];
    int top = 0;
    stack[top++] = {bvh.root.first, bvh.root.count, tmin};
    float nearest = kInfinity;
    while (top > 0) {
        const Pending p = stack[--top];
        if (Mode == TraversalMode::Closest && p.tnear > tmax) continue;  // culled after a hit
        if (!(p.count & BvhEntry::kInnerBit)) {
            const float t = on_leaf(p.first, p.count, tmax);
            if (t < nearest) nearest = t;
            if (Mode == TraversalMode::Closest && t < tmax) tmax = t;
            if (Mode == TraversalMode::AnyHit && t < kInfinity) return t;
            continue;
        }
        sink.on(Level.node_visit);
        const std::uint32_t n = p.count & ~BvhEntry::kInnerBit;
        sink.add(Level.box_test, n);
        const BvhEntry* child = bvh.entries.data() + p.first;
        // Hit children go straight onto the stack, kept sorted far to near by
        // insertion so the nearest is popped first (equal distances pop in
        // reverse child order).
        const int base = top;
        for (std::uint32_t i = 0; i < n; ++i) {
            const float t = intersect_box(child[i].box, origin, inv_dir, tmin, tmax);
            if (t == kInfinity) continue;
            int j = top++;
            for (; j > base && stack[j - 1].tnear < t; --j) stack[j] = stack[j - 1];
            stack[j] = {child[i].first, child[i].count, t};
        }
    }
    return nearest;
}

}  // namespace rtc
