// The collapse of the binary SAH tree into the wide BVH (see bvh_collapse.h),
// serial at the top and in parallel below, with no buffer of its own.
//
// The serial order defines the layout: a stack of inner nodes, each given the
// next run of entries for its children when it is taken, its first inner
// child taken next. A wide node's subtree therefore fills one contiguous run
// of entries right after the block of its parent's children and after its
// earlier siblings' subtrees. So the top of the tree is walked serially down
// to subtrees of at most `task` primitives, keeping the order in which it
// meets their blocks and those subtrees ("pieces"); the subtrees' entries
// are counted in parallel (the collapse's choices without its writes); each
// piece gets its offset in that order (a sum over a few hundred pieces); then
// every subtree is collapsed in parallel straight into its run. The entries
// are bit for bit the serial collapse's, whatever the thread count
// (tests/core/test_core_parallel.cpp, test_core_bvh_reference.cpp).
#include "core/build/bvh_collapse.h"

#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <vector>

namespace rtc::bvh_detail {
namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Chooses up to `width` binary descendants of `node` to become its children in
// the wide tree: open the inner child of largest area until the node is full.
std::array<std::uint32_t, 8> collapse_children(const BinaryNodes& nodes, std::uint32_t node, int width, int& n) {
    std::array<std::uint32_t, 8> kids{nodes[node].left_or_first, nodes[node].right_or_count};
    n = 2;
    while (n < width) {
        int pick = -1;
        float pick_area = -1.0f;
        for (int i = 0; i < n; ++i) {
            const BinaryNode& k = nodes[kids[i]];
            if (!k.is_leaf() && k.box().surface_area() > pick_area) {
                pick = i;
                pick_area = k.box().surface_area();
            }
        }
        if (pick < 0) break;
        const BinaryNode& opened = nodes[kids[pick]];
        for (int i = n; i > pick + 1; --i) kids[i] = kids[i - 1];
        kids[pick] = opened.left_or_first;
        kids[pick + 1] = opened.right_or_count;
        ++n;
    }
    return kids;
}

// The entry of a binary node: a leaf's primitives, or an inner node whose
// children are linked in when it is taken.
BvhEntry entry_of(const BinaryNode& b) {
    BvhEntry e;
    e.box = b.box();
    e.first = b.is_leaf() ? b.left_or_first : 0;
    e.count = b.is_leaf() ? b.right_or_count & ~BinaryNode::kLeafBit : 0;
    return e;
}

// Where a collapse puts its entries: appended to a vector (the whole tree
// on one thread), written from a given entry on (a subtree whose run is
// known), or nowhere (counting a subtree's entries).
struct Append {
    static constexpr bool kWrites = true;
    UninitializedVector<BvhEntry>& v;
    std::uint32_t take(int k) {
        const auto first = static_cast<std::uint32_t>(v.size());
        v.resize(first + k);
        return first;
    }
    BvhEntry& operator[](std::uint32_t i) { return v[i]; }
};
struct InPlace {
    static constexpr bool kWrites = true;
    BvhEntry* entries;
    std::uint32_t next;
    std::uint32_t take(int k) { return std::exchange(next, next + static_cast<std::uint32_t>(k)); }
    BvhEntry& operator[](std::uint32_t i) { return entries[i]; }
};
struct Count {
    static constexpr bool kWrites = false;
    std::uint32_t next = 0;
    std::uint32_t take(int k) { return std::exchange(next, next + static_cast<std::uint32_t>(k)); }
    BvhEntry& operator[](std::uint32_t) { return unused; }
    BvhEntry unused;
};

// The serial collapse of the subtree below inner binary node `root` into
// `out`; returns the count (with the inner bit) of `root`'s node, whose
// children are the first run `out` gives.
template <class Out>
std::uint32_t collapse_subtree(const BinaryNodes& nodes, std::uint32_t root, int width, Out& out) {
    struct Work {
        std::uint32_t binary, slot;  // slot: the entry that points at its children (kNone: root)
    };
    std::vector<Work> work{{root, kNone}};
    std::uint32_t root_count = 0;
    while (!work.empty()) {
        const Work w = work.back();
        work.pop_back();
        int k = 0;
        const auto kids = collapse_children(nodes, w.binary, width, k);
        const std::uint32_t first = out.take(k);
        const std::uint32_t count = static_cast<std::uint32_t>(k) | BvhEntry::kInnerBit;
        if (w.slot == kNone) {
            root_count = count;
        } else if constexpr (Out::kWrites) {
            out[w.slot].first = first;
            out[w.slot].count = count;
        }
        for (int i = k - 1; i >= 0; --i) {
            if constexpr (Out::kWrites) out[first + i] = entry_of(nodes[kids[i]]);
            if (!nodes[kids[i]].is_leaf()) work.push_back({kids[i], first + static_cast<std::uint32_t>(i)});
        }
    }
    return root_count;
}

// Primitives below binary node b: its leaves hold one contiguous range of
// prim_ids (every split partitions its node's range), from its leftmost
// leaf's first slot to its rightmost leaf's end. O(depth).
std::uint32_t subtree_primitives(const BinaryNodes& nodes, std::uint32_t b) {
    std::uint32_t l = b, r = b;
    while (!nodes[l].is_leaf()) l = nodes[l].left_or_first;
    while (!nodes[r].is_leaf()) r = nodes[r].right_or_count;
    return nodes[r].left_or_first + (nodes[r].right_or_count & ~BinaryNode::kLeafBit) - nodes[l].left_or_first;
}

// What the serial walk of the top meets, in the serial collapse's order:
// the block of a top node's children, or a subtree collapsed as a task.
struct Piece {
    std::uint32_t binary;          // the top node, or the subtree's root
    std::uint32_t parent, index;   // the entry pointing at it: piece `parent`'s child `index` (kNone: the root)
    bool task;
    std::uint32_t count = 0;       // with the inner bit: the node's child count
    std::uint32_t offset = 0;      // its first entry
    std::array<std::uint32_t, 8> kids{};  // a top node's children
};

}  // namespace

void collapse_tree(const BinaryTree& tree, std::size_t primitives, int width, unsigned threads, Bvh& bvh) {
    const BinaryNodes& nodes = tree.nodes;
    // As many slots as binary nodes, like the serial builder always reserved
    // (memory_bytes() counts the capacity).
    bvh.entries.reserve(tree.count);
    const auto task = static_cast<std::uint32_t>(std::max<std::size_t>(4096, primitives / (8 * std::size_t{threads})));
    if (threads <= 1 || primitives <= task) {
        Append out{bvh.entries};
        bvh.root.count = collapse_subtree(nodes, tree.root, width, out);
        bvh.root.first = 0;
        return;
    }
    // The top, serially: the pieces in the serial collapse's order.
    std::vector<Piece> pieces;
    struct Work {
        std::uint32_t binary, parent, index;
    };
    std::vector<Work> work{{tree.root, kNone, 0}};
    while (!work.empty()) {
        const Work w = work.back();
        work.pop_back();
        Piece p{w.binary, w.parent, w.index, w.parent != kNone && subtree_primitives(nodes, w.binary) <= task};
        if (!p.task) {
            int k = 0;
            p.kids = collapse_children(nodes, w.binary, width, k);
            p.count = static_cast<std::uint32_t>(k) | BvhEntry::kInnerBit;
            const auto self = static_cast<std::uint32_t>(pieces.size());
            for (int i = k - 1; i >= 0; --i)
                if (!nodes[p.kids[i]].is_leaf()) work.push_back({p.kids[i], self, static_cast<std::uint32_t>(i)});
        }
        pieces.push_back(p);
    }
    // The subtrees' entries, counted biggest first.
    std::vector<std::uint32_t> tasks;
    for (std::uint32_t i = 0; i < pieces.size(); ++i)
        if (pieces[i].task) tasks.push_back(i);
    std::vector<std::uint32_t> primitives_in(tasks.size());
    for (std::size_t t = 0; t < tasks.size(); ++t) primitives_in[t] = subtree_primitives(nodes, pieces[tasks[t]].binary);
    std::vector<std::uint32_t> order(tasks.size());
    for (std::uint32_t t = 0; t < order.size(); ++t) order[t] = t;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return primitives_in[a] > primitives_in[b]; });
    std::vector<std::uint32_t> entries_in(tasks.size());
    parallel_for(order.size(), threads, [&](std::size_t i, unsigned) {
        Count count;
        (void)collapse_subtree(nodes, pieces[tasks[order[i]]].binary, width, count);
        entries_in[order[i]] = count.next;
    }, 1);
    // Offsets in the serial order; the top's blocks and links.
    std::size_t next = 0;
    std::vector<std::uint32_t> task_of(pieces.size(), kNone);
    for (std::uint32_t t = 0; t < tasks.size(); ++t) task_of[tasks[t]] = t;
    for (std::uint32_t i = 0; i < pieces.size(); ++i) {
        pieces[i].offset = static_cast<std::uint32_t>(next);
        next += pieces[i].task ? entries_in[task_of[i]] : pieces[i].count & ~BvhEntry::kInnerBit;
    }
    bvh.entries.resize(next);
    for (const Piece& p : pieces) {
        if (p.task) continue;  // linked by its own collapse below
        BvhEntry& parent = p.parent == kNone ? bvh.root : bvh.entries[pieces[p.parent].offset + p.index];
        parent.first = p.offset;
        parent.count = p.count;
        // Its inner children are linked when their pieces come (after this one).
        for (std::uint32_t i = 0; i < (p.count & ~BvhEntry::kInnerBit); ++i)
            bvh.entries[p.offset + i] = entry_of(nodes[p.kids[i]]);
    }
    // The subtrees, each straight into its run, biggest first.
    parallel_for(order.size(), threads, [&](std::size_t i, unsigned) {
        const Piece& p = pieces[tasks[order[i]]];
        InPlace out{bvh.entries.data(), p.offset};
        const std::uint32_t count = collapse_subtree(nodes, p.binary, width, out);
        BvhEntry& parent = bvh.entries[pieces[p.parent].offset + p.index];
        parent.first = p.offset;
        parent.count = count;
    }, 1);
}

}  // namespace rtc::bvh_detail
