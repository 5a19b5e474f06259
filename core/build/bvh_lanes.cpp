// Derives the lane blocks (core/bvh.h, BvhLaneBlock) of a BVH from its
// entries: each node's blocks are numbered (in the entries' node order, the
// root's first), then filled; every pass over the entries runs in chunks on
// the build's threads.
#include "core/bvh.h"
#include "core/parallel.h"

#include <algorithm>
#include <limits>

namespace rtc {

void make_lanes(Bvh& bvh, unsigned threads) {
    constexpr std::uint32_t kNotANode = std::numeric_limits<std::uint32_t>::max();
    const auto blocks_of = [](std::uint32_t count) { return ((count & ~BvhEntry::kInnerBit) + 3u) / 4u; };
    const std::size_t entries = bvh.entries.size();
    constexpr std::size_t kChunk = 16384;
    const std::size_t chunks = (entries + 1 + kChunk - 1) / kChunk;  // over size_at's entries + 1 slots
    // size_at[i]: the count of the node whose children start at entry i,
    // then rewritten in place as block_of[i], that node's first block. Every
    // pass runs in chunks on all threads (each entry links a distinct slot):
    // none over the entries is serial.
    UninitializedVector<std::uint32_t> size_at(entries + 1);
    parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
        std::fill(size_at.begin() + c * kChunk, size_at.begin() + std::min(entries + 1, (c + 1) * kChunk), kNotANode);
    });
    parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
        for (std::size_t i = c * kChunk; i < std::min(entries, (c + 1) * kChunk); ++i)
            if (bvh.entries[i].is_inner()) size_at[bvh.entries[i].first] = bvh.entries[i].count;
    });
    size_at[bvh.root.first] = bvh.root.count;
    // Blocks are numbered in slot order, the root's first: each chunk's
    // blocks, then a prefix sum over the chunks, then the numbers.
    const std::uint32_t root = bvh.root.first;
    std::vector<std::uint32_t> chunk_first(chunks + 1, 0);
    const auto blocks_in = [&](std::size_t c) {
        std::uint32_t sum = 0;
        for (std::size_t i = c * kChunk; i < std::min(entries + 1, (c + 1) * kChunk); ++i)
            if (size_at[i] != kNotANode && i != root) sum += blocks_of(size_at[i]);
        return sum;
    };
    parallel_for(chunks, threads, [&](std::size_t c, unsigned) { chunk_first[c + 1] = blocks_in(c); });
    chunk_first[0] = blocks_of(bvh.root.count);  // the root's blocks come first
    for (std::size_t c = 0; c < chunks; ++c) chunk_first[c + 1] += chunk_first[c];
    const std::uint32_t next = chunk_first.back();  // all blocks
    UninitializedVector<std::uint32_t>& block_of = size_at;  // rewritten in place
    parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
        std::uint32_t at = chunk_first[c];
        for (std::size_t i = c * kChunk; i < std::min(entries + 1, (c + 1) * kChunk); ++i) {
            if (size_at[i] == kNotANode) continue;
            const std::uint32_t blocks = blocks_of(size_at[i]);
            block_of[i] = i == root ? 0 : at;
            if (i != root) at += blocks;
        }
    });

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
    parallel_for((entries + kChunk - 1) / kChunk, threads, [&](std::size_t chunk, unsigned) {
        const std::size_t end = std::min(entries, (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i)
            if (bvh.entries[i].is_inner()) fill(bvh.entries[i].first, bvh.entries[i].count);
    });
}

}  // namespace rtc
