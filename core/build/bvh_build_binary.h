// Internal to the BVH builder: the binary SAH tree that the wide BVH is
// collapsed from.
#pragma once

#include "core/bvh.h"
#include "core/uninitialized.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace rtc::bvh_detail {

struct BinaryNode {
    static constexpr std::uint32_t kLeafBit = 0x80000000u;
    Vec3 lo;
    std::uint32_t left_or_first;   // inner: left child; leaf: first slot in prim_ids
    Vec3 hi;
    std::uint32_t right_or_count;  // inner: right child; leaf: count | kLeafBit
    [[nodiscard]] Aabb box() const { return {lo, hi}; }
    [[nodiscard]] bool is_leaf() const { return (right_or_count & kLeafBit) != 0; }
};
// Trivial, so that the node array is allocated, not zeroed.
static_assert(std::is_trivially_default_constructible_v<BinaryNode>);

// Not zeroed: every reachable node is written, unused slots are never read.
using BinaryNodes = UninitializedVector<BinaryNode>;

struct BinaryTree {
    BinaryNodes nodes;  // not all slots are used: see `count`
    std::uint32_t root = 0;
    std::size_t count = 0;          // nodes in the tree
    // The reference buffers' memory (2 n references of 32 bytes), which the
    // build has touched: the collapse's scratch, or freed for the entries to
    // take (on a VM a page new to the process cost more than the walks).
    std::unique_ptr<std::byte[]> spare;
    std::size_t spare_bytes = 0;
};

// Builds the binary tree over `boxes` (split on their centres) on `threads`
// threads, filling prim_ids (sized to the box count) with the primitives in
// leaf order. Throws std::invalid_argument naming the first invalid
// primitive. Empty input gives an empty tree.
[[nodiscard]] BinaryTree build_binary_tree(std::span<const Aabb> boxes, const BuildOptions& options,
                                           unsigned threads,
                                           UninitializedVector<std::uint32_t>& prim_ids);

}  // namespace rtc::bvh_detail
