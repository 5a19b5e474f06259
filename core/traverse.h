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

#include "core/box_lanes.h"
#include "core/bvh.h"
#include "core/events.h"

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

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

// The ray as the box tests of one traversal use it (broadcast once per call).
struct BoxRay {
#if defined(__SSE2__)
    __m128 ox, oy, oz, ix, iy, iz, tmin;
    BoxRay(const Vec3& origin, const Vec3& inv_dir, float t0)
        : ox(_mm_set1_ps(origin.x)), oy(_mm_set1_ps(origin.y)), oz(_mm_set1_ps(origin.z)),
          ix(_mm_set1_ps(inv_dir.x)), iy(_mm_set1_ps(inv_dir.y)), iz(_mm_set1_ps(inv_dir.z)),
          tmin(_mm_set1_ps(t0)) {}
#else
    Vec3 origin, inv_dir;
    float tmin;
    BoxRay(const Vec3& o, const Vec3& i, float t0) : origin(o), inv_dir(i), tmin(t0) {}
#endif
};

// tmax as the box tests use it: broadcast to the lanes once per change (a
// hit), not at every node.
#if defined(__SSE2__)
using LaneTmax = __m128;
[[nodiscard, gnu::always_inline]] inline LaneTmax lane_tmax(float t) { return _mm_set1_ps(t); }
#else
using LaneTmax = float;
[[nodiscard]] inline LaneTmax lane_tmax(float t) { return t; }
#endif

#if defined(__SSE2__)
// Constants of the lane box test, in memory where the compiler cannot see
// their values: it reads them as operands of the instructions that use them.
// As known values they were rebuilt in a register at every node (a load and a
// shuffle each: every register holds the ray or the box's products).
struct alignas(16) LaneConstants {
    float slab_pad[4];
    float infinity[4];
    float minus_zero[4];  // -0.0f: its bits (0x80000000) for integer compares
};
extern const LaneConstants kLaneConstants;

// The four children of one lane block: the hit mask (bit i for lane i) and
// their entry distances in tnear[0, 4).
[[nodiscard, gnu::always_inline]] inline unsigned intersect_block(const BvhLaneBlock& b, const BoxRay& r,
                                                                  __m128 vtmax, float* tnear) {
    const __m128 tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_x), r.ox), r.ix);
    const __m128 tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_x), r.ox), r.ix);
    const __m128 ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_y), r.oy), r.iy);
    const __m128 ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_y), r.oy), r.iy);
    const __m128 tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_z), r.oz), r.iz);
    const __m128 tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_z), r.oz), r.iz);
    // std::min(a, b) is _mm_min_ps(b, a) and std::max(a, b) is _mm_max_ps(b, a).
    const auto mn = [](__m128 a, __m128 b) { return _mm_min_ps(b, a); };
    const auto mx = [](__m128 a, __m128 b) { return _mm_max_ps(b, a); };
    const __m128 near = mx(mx(mn(tx0, tx1), mn(ty0, ty1)), mx(mn(tz0, tz1), r.tmin));
    const __m128 far = mn(mn(mx(tx0, tx1), mx(ty0, ty1)), mn(mx(tz0, tz1), vtmax));
    _mm_storeu_ps(tnear, near);
    // A hit: near <= far * pad, and near finite (intersect_box's +inf is a miss).
    const __m128 pad = _mm_load_ps(kLaneConstants.slab_pad), inf = _mm_load_ps(kLaneConstants.infinity);
    const __m128 hit = _mm_and_ps(_mm_cmple_ps(near, _mm_mul_ps(far, pad)), _mm_cmpneq_ps(near, inf));
    return static_cast<unsigned>(_mm_movemask_ps(hit));
}
#endif

// Tests the n children (n <= 8) of the node whose lane blocks start at
// `block` and returns a mask of the hit ones, with their entry distances in
// tnear[i]. Exactly intersect_box() per child (the same float operations in
// the same order, min/max with the same operand order, so NaNs and signed
// zeros resolve alike), four children per SSE instruction.
[[nodiscard, gnu::always_inline]] inline unsigned intersect_children(const BvhLaneBlock* block,
                                                                     std::uint32_t n, const BoxRay& r,
                                                                     LaneTmax vtmax, float* tnear) {
#if defined(__SSE2__)
    // Nodes of one to four children (the default width) in one block, no loop;
    // an empty root (a BVH over no primitives) has no block to read.
    if (n - 1u < 4u) return intersect_block(*block, r, vtmax, tnear) & ((1u << n) - 1u);
    unsigned mask = 0;
    for (std::uint32_t base = 0; base < n; base += 4)
        mask |= intersect_block(block[base / 4], r, vtmax, tnear + base) << base;
    return mask & ((1u << n) - 1u);
#else
    unsigned mask = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const BvhLaneBlock& b = block[i / 4];
        const std::uint32_t l = i % 4;
        const Aabb box{{b.lo_x[l], b.lo_y[l], b.lo_z[l]}, {b.hi_x[l], b.hi_y[l], b.hi_z[l]}};
        tnear[i] = intersect_box(box, r.origin, r.inv_dir, r.tmin, vtmax);
        if (tnear[i] != kInfinity) mask |= 1u << i;
    }
    return mask;
#endif
}

// kMayBeOneLeaf = false: the caller knows the root is not over one leaf
// (TwoLevel::lone_identity's BLAS), and its test is skipped.
template <TraversalMode Mode, LevelEvents Level, bool kMayBeOneLeaf = true, class Sink, class LeafFn>
float traverse(const Bvh& bvh, const Vec3& origin, const Vec3& inv_dir, float tmin, float tmax,
               Sink& sink, LeafFn&& on_leaf) {
    if (Mode == TraversalMode::Closest && tmin > tmax) return kInfinity;  // the root is culled
    const BvhEntry* entries = bvh.entries.data();
    if (kMayBeOneLeaf && bvh.root.count == (BvhEntry::kInnerBit | 1u) && !entries[bvh.root.first].is_inner()) {
        // A root over one leaf (the masquerade's unit-box BLAS): the same
        // events and tests as the loop below, without its stack.
        sink.on(Level.node_visit);
        sink.add(Level.box_test, 1);
        const BvhEntry& leaf = entries[bvh.root.first];
        const float t = intersect_lone_box(leaf.box, origin, inv_dir, tmin, tmax);
        if (t == kInfinity || (Mode == TraversalMode::Closest && t > tmax)) return kInfinity;
        const float hit = on_leaf(leaf.first, leaf.count, tmax);
        return hit < kInfinity ? hit : kInfinity;
    }
    // A child's (first, count) as one 64-bit word, so that it moves in one
    // register: as a pair of fields it went through the stack frame (the
    // head frame's traces wrote 10 % more and ran 3-5 % slower).
    struct Pending {
        std::uint64_t node;
        float tnear;
    };
    const auto word = [](const BvhLaneBlock::Child& c) {
        std::uint64_t w;
        std::memcpy(&w, &c, sizeof w);
        return w;
    };
    std::uint32_t first = 0, count = bvh.root.count;  // the node or leaf at hand
    const auto take = [&](std::uint64_t w) {
        BvhLaneBlock::Child c;
        std::memcpy(&c, &w, sizeof c);
        first = c.first, count = c.count;
    };
    Pending stack[kTraversalStackSize];
    int top = 0;
    float nearest = kInfinity;
    BoxRay box_ray(origin, inv_dir, tmin);
    LaneTmax vtmax = lane_tmax(tmax);
    // At hand: the root node first (its blocks come first), then each node's
    // nearest hit child, else the next entry popped.
    for (;;) {
        if (count & BvhEntry::kInnerBit) {
            sink.on(Level.node_visit);
            const std::uint32_t n = count & ~BvhEntry::kInnerBit;
            sink.add(Level.box_test, n);
#if defined(__SSE2__)
            // The ray's broadcasts, as far as the compiler knows, changed in
            // memory: each box test reads them as operands of its subtracts
            // and multiplies (no extra instruction). Held in registers, they
            // were live across every leaf, whose calls clobber all vector
            // registers, and were saved and restored at each leaf (obb's
            // instance leaves: 14 moves each; cases 1 and 3 obb 4 % fewer
            // instructions per ray).
            asm("" : "+m"(box_ray));
#endif
            const BvhLaneBlock* block = bvh.lanes.data() + first;
            float tnear[8];
            unsigned hits = intersect_children(block, n, box_ray, vtmax, tnear);
            // The nearest hit child goes next (of equal ones, the last); the
            // others go onto the stack sorted far to near by insertion. Stack
            // and order are those of pushing every hit child and popping the
            // top, without that push and pop. `child(i)` is hit child i.
            const auto descend = [&](auto child) __attribute__((always_inline)) {
                Pending next = child(static_cast<std::uint32_t>(__builtin_ctz(hits)));
                const int base = top;
                for (hits &= hits - 1; hits; hits &= hits - 1) {
                    const Pending hit = child(static_cast<std::uint32_t>(__builtin_ctz(hits)));
                    const bool nearer = hit.tnear <= next.tnear;
                    const Pending c = nearer ? next : hit;  // the one pushed
                    if (nearer) next = hit;
                    int j = top++;
                    for (; j > base && stack[j - 1].tnear < c.tnear; --j) stack[j] = stack[j - 1];
                    stack[j] = c;
                }
                return next;
            };
            if (hits) {
                // One block (the default width): no block index per child
                // (case 1 and 2: 3-4 % fewer instructions per ray).
                const auto in_one_block = [&](std::uint32_t i) {
                    return Pending{word(block->child[i & 3u]), tnear[i & 3u]};
                };
                const auto in_blocks = [&](std::uint32_t i) {
                    return Pending{word(block[i / 4].child[i % 4]), tnear[i]};
                };
                const Pending next = n <= 4 ? descend(in_one_block) : descend(in_blocks);
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
                vtmax = lane_tmax(t);
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

}  // namespace rtc
