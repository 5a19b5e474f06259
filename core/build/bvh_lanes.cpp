// Derives the lane blocks (core/bvh.h, BvhLaneBlock) of a BVH from its
// entries: one serial pass numbers each node's blocks (in the entries' node
// order, the root's first), a parallel one fills them.
#include "core/bvh.h"
#include "core/parallel.h"

#include <algorithm>
#include <limits>

namespace rtc {

void make_lanes(Bvh& bvh, unsigned threads) {
    constexpr std::uint32_t kNotANode = std::numeric_limits<std::uint32_t>::max();
    const auto blocks_of = [](std::uint32_t count) { return ((count & ~BvhEntry::kInnerBit) + 3u) / 4u; };
    // size_at[i]: the count of the node whose children start at entry i,
    // then rewritten in place as block_of[i], that node's first block.
    std::vector<std::uint32_t> size_at(bvh.entries.size() + 1, kNotANode);
    size_at[bvh.root.first] = bvh.root.count;
    for (const BvhEntry& e : bvh.entries)
        if (e.is_inner()) size_at[e.first] = e.count;
    std::vector<std::uint32_t>& block_of = size_at;  // rewritten in place
    std::uint32_t next = blocks_of(bvh.root.count);  // the root's blocks come first
    for (std::size_t i = 0; i < size_at.size(); ++i) {
        if (size_at[i] == kNotANode) continue;
        const std::uint32_t blocks = blocks_of(size_at[i]);
        block_of[i] = i == bvh.root.first ? 0 : next;
        if (i != bvh.root.first) next += blocks;
    }

    bvh.lanes.clear();
    bvh.lanes.resize(next);  // not zeroed: every lane of every block is written below
    const auto fill = [&](std::uint32_t first, std::uint32_t count) {
        const std::uint32_t n = count & ~BvhEntry::kInnerBit;
        BvhLaneBlock* block = bvh.lanes.data() + block_of[first];
        for (std::uint32_t slot = 0; slot < blocks_of(count) * 4u; ++slot) {
            const BvhEntry& e = bvh.entries[first + std::min(slot, n - 1u)];
            BvhLaneBlock& b = block[slot / 4u];
            b.set(slot % 4u, e, slot < n);
            if (slot < n && e.is_inner()) b.child[slot % 4u].first = block_of[e.first];
        }
    };
    fill(bvh.root.first, bvh.root.count);
    // Each inner entry fills its node's blocks: disjoint writes, any order.
    const std::size_t entries = bvh.entries.size();
    constexpr std::size_t kChunk = 16384;
    parallel_for((entries + kChunk - 1) / kChunk, threads, [&](std::size_t chunk, unsigned) {
        const std::size_t end = std::min(entries, (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i)
            if (bvh.entries[i].is_inner()) fill(bvh.entries[i].first, bvh.entries[i].count);
    });
}

}  // namespace rtc
