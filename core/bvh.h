// The BVH as the hardware sees it: wide nodes whose children are boxes, each
// child either another node or a leaf (a range of primitives).
//
// Layout: every node is the contiguous run of its children in `entries`. A
// child entry is 32 bytes (box, index, count); there are no empty slots, so a
// 2-, 4- or 8-wide tree costs the same per child. The root node is always an
// inner entry (even over zero or one primitive), so a ray always starts with a
// node visit and every leaf is reached through a child box test, as on the
// hardware (the masquerade's unit-box BLAS relies on that: its one box test is
// the OBB test). The traversal reads a second copy of the same nodes laid out
// for SIMD lanes (`lanes`, BvhLaneBlock below); `entries` stay the tree's
// description for the builders, statistics and tests.
#pragma once

#include "core/aabb.h"
#include "core/uninitialized.h"

#include <cstdint>
#include <span>
#include <vector>

namespace rtc {

struct BvhEntry {
    static constexpr std::uint32_t kInnerBit = 0x80000000u;

    Aabb box;
    std::uint32_t first = 0;  // inner: first child entry; leaf: first slot in prim_ids
    std::uint32_t count = 0;  // number of children (with kInnerBit) or primitives

    [[nodiscard]] bool is_inner() const { return (count & kInnerBit) != 0; }
    [[nodiscard]] std::uint32_t size() const { return count & ~kInnerBit; }
};
static_assert(sizeof(BvhEntry) == 32);

// Four children of a node in SIMD lanes (structure of arrays): what the
// traversal kernel reads. A node of n children is ceil(n / 4) consecutive
// blocks; lanes past its last child repeat that child and are masked off. The
// boxes are the entries' own floats, so box tests are bit-identical; only the
// layout differs: four aligned loads per coordinate instead of a transpose of
// four 32-byte entries (20-30 instructions per node visit, see
// docs/benchmark.md), and a 4-wide node is exactly two cache lines.
struct alignas(64) BvhLaneBlock {
    float lo_x[4], lo_y[4], lo_z[4];
    float hi_x[4], hi_y[4], hi_z[4];
    // Side by side, so the traversal takes a child's pair in one 8-byte load.
    struct Child {
        std::uint32_t first;  // inner child: its node's first block; leaf: first slot in prim_ids
        std::uint32_t count;  // as BvhEntry::count
    };
    Child child[4];

    // Lane `lane` from entry `e`, whose `first` is still an entry index for an
    // inner child (the caller maps it to a block). A lane past a node's last
    // child repeats that child's box, with first = count = 0.
    void set(std::uint32_t lane, const BvhEntry& e, bool used) {
        lo_x[lane] = e.box.lo.x, lo_y[lane] = e.box.lo.y, lo_z[lane] = e.box.lo.z;
        hi_x[lane] = e.box.hi.x, hi_y[lane] = e.box.hi.y, hi_z[lane] = e.box.hi.z;
        child[lane] = used ? Child{e.first, e.count} : Child{0, 0};
    }
};
static_assert(sizeof(BvhLaneBlock) == 128);
static_assert(sizeof(BvhLaneBlock::Child) == 8);  // the traversal moves a child as one word

enum class SplitStrategy { Sah, Median };

struct BuildOptions {
    // 4-wide by default: it sits between the binary trees of the paper-era
    // software (OptiX 7's BLAS builder is not public) and the 6-8-wide nodes of
    // compressed-wide BVH hardware proposals (Ylitie et al. 2017); widths 2, 4
    // and 8 all work and the width is a config key, so the choice can be swept.
    int width = 4;
    int bins = 16;            // binned SAH (Wald 2007): candidate planes per axis = bins - 1
    int max_leaf_size = 1;    // custom primitives: one box per primitive, as on the hardware
    SplitStrategy strategy = SplitStrategy::Sah;
    float traversal_cost = 1.0f;     // SAH: relative cost of visiting a node...
    float intersection_cost = 1.0f;  // ...and of testing one primitive
    // Threads the build may use (0 = all cores); the tree does not depend on it.
    int threads = 0;
};

struct Bvh {
    BvhEntry root;                      // the root node (always inner)
    // Not zeroed either: the builders write every entry and id they size
    // (zeroing them was the last serial pass of a parallel build that grows
    // with the scene: 25 MB per 1 M primitives, with its pages' first touch).
    UninitializedVector<BvhEntry> entries;      // children of every node, node by node
    UninitializedVector<std::uint32_t> prim_ids;  // leaf ranges index into this
    // The same nodes as `entries`, in lanes (the root node's blocks first),
    // written by make_lanes(), every lane of every block, so not zeroed
    // first. traverse() reads these.
    UninitializedVector<BvhLaneBlock> lanes;
    int width = 4;

    [[nodiscard]] const Aabb& bounds() const { return root.box; }
    [[nodiscard]] std::size_t primitive_count() const { return prim_ids.size(); }
    [[nodiscard]] std::size_t node_count() const;   // inner nodes, root included
    [[nodiscard]] std::size_t leaf_count() const;
    [[nodiscard]] std::size_t memory_bytes() const {
        return sizeof(Bvh) + entries.capacity() * sizeof(BvhEntry) +
               prim_ids.capacity() * sizeof(std::uint32_t) + lanes.capacity() * sizeof(BvhLaneBlock);
    }
};

// Builds a BVH over `boxes` (one per primitive), splitting on the boxes'
// centres. Deterministic: the same input gives the same tree, ties go to the
// smallest axis, bin and primitive index, whatever the thread count. Throws
// std::invalid_argument naming the first primitive whose box or centre is
// NaN or infinite, or whose box is inverted.
[[nodiscard]] Bvh build_bvh(std::span<const Aabb> boxes, const BuildOptions& options = {});

// Derives `bvh.lanes` from `bvh.root` and `bvh.entries` on `threads` threads
// (build_bvh() calls it; call it for trees made by hand). Blocks follow the
// entries' node order, the root's first.
void make_lanes(Bvh& bvh, unsigned threads = 1);

// SAH cost of a tree (node traversal + primitive tests weighted by surface
// area relative to the root), used to compare builders.
[[nodiscard]] double sah_cost(const Bvh& bvh, const BuildOptions& costs = {});

}  // namespace rtc
