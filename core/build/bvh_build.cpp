// Builds the wide BVH: a binary SAH tree (core/bvh_build_binary.cpp, with the
// binned SAH of core/bvh_build_sah.cpp) collapsed into nodes of the requested
// width by repeatedly opening the child with the largest surface area (the
// usual collapse used for wide hardware BVHs, e.g. Ylitie et al. 2017 use a
// cost-based variant).
#include "core/bvh.h"
#include "core/build/bvh_build_binary.h"
#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace rtc {
namespace {

using bvh_detail::BinaryNode;

// Chooses up to `width` binary descendants of `node` to become its children in
// the wide tree: open the inner child of largest area until the node is full.
std::array<std::uint32_t, 8> collapse_children(const bvh_detail::BinaryNodes& nodes,
                                               std::uint32_t node, int width, int& n) {
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
}  // namespace

Bvh build_bvh(std::span<const Aabb> boxes, const BuildOptions& options) {
    if (options.width != 2 && options.width != 4 && options.width != 8)
        throw std::invalid_argument("BVH build: width must be 2, 4 or 8, got " +
                                    std::to_string(options.width));
    if (options.max_leaf_size < 1)
        throw std::invalid_argument("BVH build: max_leaf_size must be at least 1");
    const unsigned threads =
        options.threads > 0 ? static_cast<unsigned>(options.threads) : hardware_threads();

    Bvh bvh;
    bvh.width = options.width;
    bvh.root.count = BvhEntry::kInnerBit;  // empty root node
    const std::size_t n = boxes.size();
    bvh.prim_ids.resize(n);
    bvh_detail::BinaryTree tree = bvh_detail::build_binary_tree(boxes, options, threads, bvh.prim_ids);
    if (n == 0) return bvh;
    const bvh_detail::BinaryNodes& nodes = tree.nodes;
    const std::uint32_t root = tree.root;
    const std::size_t binary_nodes = tree.count;

    // As many slots as binary nodes, like the serial builder always reserved
    // (memory_bytes() counts the capacity).
    bvh.entries.reserve(binary_nodes);
    const auto fill = [&](std::uint32_t slot, std::uint32_t b) {
        BvhEntry& e = bvh.entries[slot];
        e.box = nodes[b].box();
        e.first = nodes[b].is_leaf() ? nodes[b].left_or_first : 0;
        e.count = nodes[b].is_leaf() ? nodes[b].right_or_count & ~BinaryNode::kLeafBit : 0;
    };
    // Work list of (binary inner node, entry slot that will point at its children;
    // UINT32_MAX for the root).
    struct Work { std::uint32_t binary, slot; };
    std::vector<Work> work;
    bvh.root.box = nodes[root].box();
    if (nodes[root].is_leaf()) {  // a lone leaf still hangs below a root node
        bvh.entries.resize(1);
        fill(0, root);
        bvh.root.first = 0;
        bvh.root.count = 1 | BvhEntry::kInnerBit;
        make_lanes(bvh, threads);
        return bvh;
    }
    work.push_back({root, UINT32_MAX});
    while (!work.empty()) {
        const Work w = work.back();
        work.pop_back();
        int k = 0;
        const auto kids = collapse_children(nodes, w.binary, options.width, k);
        const auto first = static_cast<std::uint32_t>(bvh.entries.size());
        bvh.entries.resize(first + k);
        BvhEntry& parent = w.slot == UINT32_MAX ? bvh.root : bvh.entries[w.slot];
        parent.first = first;
        parent.count = static_cast<std::uint32_t>(k) | BvhEntry::kInnerBit;
        for (int i = k - 1; i >= 0; --i) {
            fill(first + i, kids[i]);
            if (!nodes[kids[i]].is_leaf()) work.push_back({kids[i], first + i});
        }
    }
    // The binary nodes are done with: freed before the lanes are allocated,
    // their pages (2 n nodes, 64 MB per 1 M primitives) serve the lanes'
    // 60 MB instead of pages new to the process (docs/benchmark.md, issue
    // 19 round 11: on a VM a page new to the guest cost 1.4-1.9 ms per MB).
    bvh_detail::BinaryNodes().swap(tree.nodes);
    // The lane blocks the traversal reads, from the finished entries, on the
    // build's threads (per 1 M primitives: 40 ms on one thread, 23 ms on two,
    // about half of it the first touch of the blocks' 60 MB). Written inside
    // the serial loop above instead, they cost as much, in less simple code.
    make_lanes(bvh, threads);
    return bvh;
}

std::size_t Bvh::node_count() const {
    return 1 + static_cast<std::size_t>(
                   std::count_if(entries.begin(), entries.end(), [](auto& e) { return e.is_inner(); }));
}

std::size_t Bvh::leaf_count() const { return entries.size() + 1 - node_count(); }

double sah_cost(const Bvh& bvh, const BuildOptions& costs) {
    const double root_area = bvh.root.box.surface_area();
    if (!(root_area > 0.0)) return 0.0;
    double cost = costs.traversal_cost;  // the root node
    for (const BvhEntry& e : bvh.entries) {
        const double rel = e.box.surface_area() / root_area;
        cost += e.is_inner() ? costs.traversal_cost * rel
                             : costs.intersection_cost * e.size() * rel;
    }
    return cost;
}

}  // namespace rtc

