// The collapse of the binary SAH tree into the wide BVH (see bvh_collapse.h),
// serial at the top and in parallel below.
//
// The serial order defines the layout: a stack of inner nodes, each given the
// next run of entries for its children when it is taken, its first inner
// child taken next. A wide node's subtree therefore fills one contiguous run
// of entries right after the block of its parent's children and after its
// earlier siblings' subtrees. So the top of the tree is walked serially down
// to subtrees of at most `task` primitives, keeping the order in which it
// meets their blocks and those subtrees ("pieces"); the subtrees are
// collapsed in parallel into scratch memory, which gives their sizes; each
// piece gets its offset in that order (a sum over a few hundred pieces); then
// every subtree is copied in parallel into its run. The entries are bit for
// bit the serial collapse's, whatever the thread count
// (tests/core/test_core_parallel.cpp, test_core_bvh_reference.cpp).
//
// The scratch is the builder's reference buffers (BinaryTree::spare), whose
// pages the build has touched: counting each subtree's entries first and
// writing them in place walked every subtree twice (on two threads as long
// as one walk on one), and a scratch array of its own was 64 MB of fresh
// pages per million primitives, which on a VM cost more than the walk.
#include "core/build/bvh_collapse.h"

#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <limits>
#include <new>
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
// on one thread), or placed from a given slot of scratch memory on (a
// subtree, its links relative to its first entry). put() writes an entry,
// link() points an entry written before at its children.
struct Append {
    UninitializedVector<BvhEntry>& v;
    std::uint32_t take(int k) {
        const auto first = static_cast<std::uint32_t>(v.size());
        v.resize(first + k);
        return first;
    }
    void put(std::uint32_t i, const BvhEntry& e) { v[i] = e; }
    void link(std::uint32_t i, std::uint32_t first, std::uint32_t count) { v[i].first = first, v[i].count = count; }
};
struct InScratch {
    std::byte* base;  // slot 0; the entries are created in it as they are placed
    std::uint32_t next = 0;
    std::uint32_t take(int k) { return std::exchange(next, next + static_cast<std::uint32_t>(k)); }
    void put(std::uint32_t i, const BvhEntry& e) { ::new (base + std::size_t{i} * sizeof(BvhEntry)) BvhEntry(e); }
    void link(std::uint32_t i, std::uint32_t first, std::uint32_t count) {
        BvhEntry* e = std::launder(reinterpret_cast<BvhEntry*>(base + std::size_t{i} * sizeof(BvhEntry)));
        e->first = first, e->count = count;
    }
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
        if (w.slot == kNone) root_count = count;
        else out.link(w.slot, first, count);
        for (int i = k - 1; i >= 0; --i) {
            out.put(first + static_cast<std::uint32_t>(i), entry_of(nodes[kids[i]]));
            if (!nodes[kids[i]].is_leaf()) work.push_back({kids[i], first + static_cast<std::uint32_t>(i)});
        }
    }
    return root_count;
}

// The first prim_ids slot below binary node b: its leftmost leaf's. O(depth).
std::uint32_t first_primitive(const BinaryNodes& nodes, std::uint32_t b) {
    while (!nodes[b].is_leaf()) b = nodes[b].left_or_first;
    return nodes[b].left_or_first;
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
    std::array<BvhEntry, 8> children{};  // a top node's children (their links made later)
};

}  // namespace

void collapse_tree(BinaryTree tree, std::size_t primitives, int width, unsigned threads, Bvh& bvh) {
    BinaryNodes& nodes = tree.nodes;
    const auto task = static_cast<std::uint32_t>(std::max<std::size_t>(4096, primitives / (8 * std::size_t{threads})));
    if (threads <= 1 || primitives <= task || tree.spare_bytes < 2 * primitives * sizeof(BvhEntry)) {
        tree.spare.reset();  // the entries take its pages
        // As many slots as binary nodes, like the serial builder always
        // reserved (memory_bytes() counts the capacity).
        bvh.entries.reserve(tree.count);
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
            const auto kids = collapse_children(nodes, w.binary, width, k);
            p.count = static_cast<std::uint32_t>(k) | BvhEntry::kInnerBit;
            const auto self = static_cast<std::uint32_t>(pieces.size());
            for (int i = k - 1; i >= 0; --i) {
                p.children[i] = entry_of(nodes[kids[i]]);
                if (!nodes[kids[i]].is_leaf()) work.push_back({kids[i], self, static_cast<std::uint32_t>(i)});
            }
        }
        pieces.push_back(p);
    }
    // The subtrees, biggest first, each into its own part of the scratch:
    // a subtree of p primitives has at most 2 p - 2 entries (each binary
    // node but its root is at most one entry), so 2 p slots from twice its
    // first primitive on.
    std::vector<std::uint32_t> tasks;
    for (std::uint32_t i = 0; i < pieces.size(); ++i)
        if (pieces[i].task) tasks.push_back(i);
    std::vector<std::uint32_t> primitives_in(tasks.size()), first_prim(tasks.size());
    for (std::size_t t = 0; t < tasks.size(); ++t) {
        primitives_in[t] = subtree_primitives(nodes, pieces[tasks[t]].binary);
        first_prim[t] = first_primitive(nodes, pieces[tasks[t]].binary);
    }
    std::vector<std::uint32_t> order(tasks.size());
    for (std::uint32_t t = 0; t < order.size(); ++t) order[t] = t;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return primitives_in[a] > primitives_in[b]; });
    std::byte* const scratch = tree.spare.get();
    const auto scratch_of = [&](std::uint32_t t) { return scratch + 2 * std::size_t{first_prim[t]} * sizeof(BvhEntry); };
    std::vector<std::uint32_t> entries_in(tasks.size()), root_count(tasks.size());
    parallel_for(order.size(), threads, [&](std::size_t i, unsigned) {
        const std::uint32_t t = order[i];
        InScratch out{scratch_of(t)};
        root_count[t] = collapse_subtree(nodes, pieces[tasks[t]].binary, width, out);
        entries_in[t] = out.next;
    }, 1);
    // Done with the binary nodes: the entries take their pages.
    BinaryNodes().swap(nodes);
    // Offsets in the serial order; the top's blocks and links.
    std::size_t next = 0;
    std::vector<std::uint32_t> task_of(pieces.size(), kNone);
    for (std::uint32_t t = 0; t < tasks.size(); ++t) task_of[tasks[t]] = t;
    for (std::uint32_t i = 0; i < pieces.size(); ++i) {
        pieces[i].offset = static_cast<std::uint32_t>(next);
        next += pieces[i].task ? entries_in[task_of[i]] : pieces[i].count & ~BvhEntry::kInnerBit;
    }
    bvh.entries.reserve(tree.count);
    bvh.entries.resize(next);
    for (const Piece& p : pieces) {
        if (p.task) continue;  // linked when its entries are copied below
        BvhEntry& parent = p.parent == kNone ? bvh.root : bvh.entries[pieces[p.parent].offset + p.index];
        parent.first = p.offset;
        parent.count = p.count;
        // Its inner children are linked when their pieces come (after this one).
        for (std::uint32_t i = 0; i < (p.count & ~BvhEntry::kInnerBit); ++i) bvh.entries[p.offset + i] = p.children[i];
    }
    // The subtrees copied into their runs, their links made absolute.
    parallel_for(order.size(), threads, [&](std::size_t i, unsigned) {
        const std::uint32_t t = order[i];
        const Piece& p = pieces[tasks[t]];
        const BvhEntry* from = std::launder(reinterpret_cast<const BvhEntry*>(scratch_of(t)));
        BvhEntry* to = bvh.entries.data() + p.offset;
        for (std::uint32_t e = 0; e < entries_in[t]; ++e) {
            BvhEntry entry = from[e];
            if (entry.is_inner()) entry.first += p.offset;
            to[e] = entry;
        }
        BvhEntry& parent = bvh.entries[pieces[p.parent].offset + p.index];
        parent.first = p.offset;
        parent.count = root_count[t];
    }, 1);
}

}  // namespace rtc::bvh_detail
