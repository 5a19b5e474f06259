// The traversal kernel: stack-based, nearest child first, over one BVH level.
//
// Policies are template parameters (no virtual call on the ray's path):
// - Mode: Closest (leaf hits shrink tmax), AnyHit (stop at the first leaf hit)
//   or AllCandidates (never shrink tmax, reach every leaf whose box the ray
//   pierces: the brute-force reference for counting tests).
// - Nodes: the node style, how a node's children are tested and read:
//   axis-aligned lane blocks (AabbNodes, core/aabb_nodes.h) or oriented
//   children (ObbNodes, core/obb_nodes.h: ObbStyle::PerChild, PerNode). It
//   gives root() (first, count), tmax(t) (tmax as its box tests take it: the
//   kernel keeps it, set up once per change), test<box test event>(first, n,
//   sink, tmax, tnear) (counts the node's box tests, returns the mask of hit
//   children) and children(first, n, tnear, descend), which calls
//   descend(child) with child(i) = hit child i as a ChildHit.
// - LeafFn: `float(std::uint32_t first, std::uint32_t count, float tmax)`
//   handles a leaf's primitives `bvh.prim_ids[first, first + count)` and
//   returns the nearest hit distance it accepted, or +inf.
// - Sink: receives one node-visit event per node (the Level parameter says
//   which, TLAS or BLAS) and, through Nodes, the box-test events.
#pragma once

#include "core/aabb_nodes.h"
#include "core/box_lanes.h"
#include "core/bvh.h"
#include "core/child_hit.h"
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

// The kernel over any node style. Inlined into each entry (traverse() below,
// core/obb_nodes.h's traverse_obb), so each compiles to one loop of its own.
template <TraversalMode Mode, LevelEvents Level, class Nodes, class Sink, class LeafFn>
[[gnu::always_inline]] inline float traverse_nodes(Nodes nodes, float tmin, float tmax, Sink& sink,
                                                   LeafFn&& on_leaf) {
    if (Mode == TraversalMode::Closest && tmin > tmax) return kInfinity;  // the root is culled
    std::uint32_t first = nodes.root().first, count = nodes.root().count;  // the node or leaf at hand
    const auto take = [&](std::uint64_t w) {
        const BvhLaneBlock::Child c = child_of_word(w);
        first = c.first, count = c.count;
    };
    ChildHit stack[kTraversalStackSize];
    int top = 0;
    float nearest = kInfinity;
    // tmax as the box tests take it, a local of the kernel: as a member of
    // `nodes` it went through memory with the ray there (case 2 ref: 2 %
    // more instructions per ray).
    auto test_tmax = nodes.tmax(tmax);
    // At hand: the root node first, then each node's nearest hit child, else
    // the next entry popped.
    for (;;) {
        if (count & BvhEntry::kInnerBit) {
            sink.on(Level.node_visit);
            const std::uint32_t n = count & ~BvhEntry::kInnerBit;
            float tnear[8];
            unsigned hits = nodes.template test<Level.box_test>(first, n, sink, test_tmax, tnear);
            // The nearest hit child goes next (of equal ones, the last); the
            // others go onto the stack sorted far to near by insertion. Stack
            // and order are those of pushing every hit child and popping the
            // top, without that push and pop. `child(i)` is hit child i.
            const auto descend = [&](auto child) __attribute__((always_inline)) {
                ChildHit next = child(static_cast<std::uint32_t>(__builtin_ctz(hits)));
                const int base = top;
                for (hits &= hits - 1; hits; hits &= hits - 1) {
                    const ChildHit hit = child(static_cast<std::uint32_t>(__builtin_ctz(hits)));
                    const bool nearer = hit.tnear <= next.tnear;
                    const ChildHit c = nearer ? next : hit;  // the one pushed
                    if (nearer) next = hit;
                    int j = top++;
                    for (; j > base && stack[j - 1].tnear < c.tnear; --j) stack[j] = stack[j - 1];
                    stack[j] = c;
                }
                return next;
            };
            if (hits) {
                const ChildHit next = nodes.children(first, n, tnear, descend);
                if (Mode != TraversalMode::Closest || next.tnear <= tmax) {
                    take(next.node);
                    continue;
                }
            }
        } else {
            const float t = on_leaf(first, count, tmax);
            if (t < nearest) nearest = t;
            if (Mode == TraversalMode::Closest && t < tmax) {
                tmax = t;
                test_tmax = nodes.tmax(t);
            }
            if (Mode == TraversalMode::AnyHit && t < kInfinity) return t;
        }
        // Pop, the word and tnear read apart (copying the 12-byte entry out
        // went through memory).
        do {
            if (top == 0) return nearest;
            --top;
        } while (Mode == TraversalMode::Closest && stack[top].tnear > tmax);  // culled after a hit
        take(stack[top].node);
    }
}

// The axis-aligned BVH (AabbNodes). kMayBeOneLeaf = false: the caller knows
// the root is not over one leaf (TwoLevel::lone_identity's BLAS), and its
// test is skipped.
template <TraversalMode Mode, LevelEvents Level, bool kMayBeOneLeaf = true, class Sink, class LeafFn>
float traverse(const Bvh& bvh, const Vec3& origin, const Vec3& inv_dir, float tmin, float tmax,
               Sink& sink, LeafFn&& on_leaf) {
    if (Mode == TraversalMode::Closest && tmin > tmax) return kInfinity;  // the root is culled
    const BvhEntry* entries = bvh.entries.data();
    if (kMayBeOneLeaf && bvh.root.count == (BvhEntry::kInnerBit | 1u) && !entries[bvh.root.first].is_inner()) {
        // A root over one leaf (the masquerade's unit-box BLAS): the same
        // events and tests as the kernel, without its stack.
        sink.on(Level.node_visit);
        sink.add(Level.box_test, 1);
        const BvhEntry& leaf = entries[bvh.root.first];
        const float t = intersect_lone_box(leaf.box, origin, inv_dir, tmin, tmax);
        if (t == kInfinity || (Mode == TraversalMode::Closest && t > tmax)) return kInfinity;
        const float hit = on_leaf(leaf.first, leaf.count, tmax);
        return hit < kInfinity ? hit : kInfinity;
    }
    return traverse_nodes<Mode, Level>(AabbNodes<>(bvh, origin, inv_dir, tmin), tmin, tmax, sink, on_leaf);
}

}  // namespace rtc
