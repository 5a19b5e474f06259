// Builds the wide BVH: a binary SAH tree (core/build/bvh_build_binary.cpp,
// with the binned SAH of bvh_build_sah.cpp) collapsed into nodes of the
// requested width (bvh_collapse.cpp), then its lane blocks (bvh_lanes.cpp).
#include "core/bvh.h"
#include "core/build/bvh_build_binary.h"
#include "core/build/bvh_collapse.h"
#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

namespace rtc {

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
    bvh.root.box = tree.nodes[tree.root].box();
    if (tree.nodes[tree.root].is_leaf()) {  // a lone leaf still hangs below a root node
        const bvh_detail::BinaryNode& leaf = tree.nodes[tree.root];
        bvh.entries.reserve(tree.count);
        bvh.entries.push_back({leaf.box(), leaf.left_or_first, leaf.right_or_count & ~bvh_detail::BinaryNode::kLeafBit});
        bvh.root.first = 0;
        bvh.root.count = 1 | BvhEntry::kInnerBit;
        make_lanes(bvh, threads);
        return bvh;
    }
    // The collapse frees the binary nodes and the reference buffers' memory
    // as it is done with them: their pages (64 MB each per 1 M primitives)
    // serve the entries and the lanes' 60 MB instead of pages new to the
    // process (docs/benchmark.md, issue 19 round 11: on a VM a page new to
    // the guest cost 1.4-1.9 ms per MB).
    bvh_detail::collapse_tree(std::move(tree), n, options.width, threads, bvh);
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

