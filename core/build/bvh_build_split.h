// Internal to the BVH builder (core/build/bvh_build_binary.cpp): the split
// of one node of the binary SAH tree (binning, the SAH choice, the stable
// partition of its references), either one big node with all threads or a
// whole subtree on the calling thread, and what the threads share for it.
#pragma once

#include "core/build/bvh_build_binary.h"
#include "core/build/bvh_build_refs.h"
#include "core/build/bvh_build_sah.h"
#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace rtc::bvh_detail {

// Past this binary depth splits fall back to the object median, which bounds
// the depth of any tree (and so the traversal stack) by kMaxSahDepth + log2(n).
inline constexpr int kMaxSahDepth = 40;
// References per chunk of a node's range binned or partitioned by one thread.
inline constexpr std::uint32_t kChunk = 16384;
// Nodes at most this big bin only into the bins they occupy.
inline constexpr std::uint32_t kSmall = 32;

struct Task {
    std::uint32_t node, begin, end;
    int depth;  // the references of the range live in buffer depth % 2
    Bounds bounds;
};

// What every thread shares: the two reference buffers (the two halves of one
// block of memory, which the collapse then reuses: BinaryTree::spare), the
// binary nodes (each subtree task owns the slice [2 begin, 2 end - 1), which
// bounds its node count; nodes above the tasks are appended after 2 n) and
// the output ids.
struct Shared {
    const BuildOptions& options;
    int bins;
    std::unique_ptr<std::byte[]> ref_memory;
    std::array<Ref*, 2> refs;
    // A big node's binning keeps each reference's three bins here (one byte
    // each, by position in the node's buffer) for its partition, which then
    // places every reference by the very bins that were counted.
    std::unique_ptr<std::uint32_t[]> ref_bins;
    BinaryNodes nodes;
    UninitializedVector<std::uint32_t>& prim_ids;
};

// A reference's three bins (0 .. 63, lane 3 is 0) as bytes 0, 1 and 2.
inline std::uint32_t pack_bins(I4 b) {
#ifdef __SSE2__
    const __m128i words = _mm_packs_epi32(reinterpret_cast<__m128i>(b), reinterpret_cast<__m128i>(b));
    return static_cast<std::uint32_t>(_mm_cvtsi128_si32(_mm_packus_epi16(words, words)));
#else
    return static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
           static_cast<std::uint32_t>(b[2]) << 16;
#endif
}

// Splits nodes, either one big node with `threads` threads or a whole subtree
// on the calling thread; owns the scratch this needs.
class Splitter {
public:
    explicit Splitter(Shared& s) : s_(s) {}

    // Sets t's node; returns false when it became a leaf, else fills the two
    // children's tasks (their `node` left for the caller to assign).
    bool split(const Task& t, Task& left, Task& right, unsigned threads) {
        const std::uint32_t count = t.end - t.begin;
        const Ref* src = s_.refs[t.depth % 2];
        Ref* dst = s_.refs[(t.depth + 1) % 2];
        const BuildOptions& o = s_.options;
        BinaryNode& node = s_.nodes[t.node];
        node.lo = t.bounds.box.lo;
        node.hi = t.bounds.box.hi;

        const auto make_leaf = [&] {
            node.left_or_first = t.begin;
            node.right_or_count = count | BinaryNode::kLeafBit;
            for (std::uint32_t i = t.begin; i < t.end; ++i) s_.prim_ids[i] = src[i].id;
            return false;
        };
        if (count == 1) return make_leaf();

        const bool fits_leaf = count <= static_cast<std::uint32_t>(o.max_leaf_size);
        const BinMap map(t.bounds.cbox, s_.bins);
        const bool small = count <= kSmall;
        Split best;
        if (o.strategy == SplitStrategy::Sah && t.depth < kMaxSahDepth) {
            const float area = t.bounds.box.surface_area();
            if (count == 2) {  // a third of all nodes: a closed form, no bins
                const Ref& r0 = src[t.begin];
                const Ref& r1 = src[t.begin + 1];
                small_bin_[0] = map.of(r0);
                small_bin_[1] = map.of(r1);
                best = find_pair_split(r0, r1, small_bin_[0], small_bin_[1], map, area, o);
            } else if (small) {
                best = find_sah_split(bin_small(src, t, map), small_used_, map, area, o);
            } else {
                const Bins& bins = bin(src, t, map, threads);
                best = find_sah_split(bins, Occupied(bins, map), map, area, o);
            }
        }
        const float leaf_cost = o.intersection_cost * static_cast<float>(count);
        if (fits_leaf && (best.axis < 0 || leaf_cost <= best.cost)) return make_leaf();
        std::uint32_t mid;
        if (best.axis < 0) {
            mid = median_split(src, dst, t, left.bounds, right.bounds);
        } else if (count == 2) {
            // The lower-bin primitive goes left; a lone reference's bounds
            // are its own box and centroid, as partition_serial folds them.
            const bool swap = small_bin_[1][best.axis] < best.bin;
            const Ref& l = src[t.begin + swap];
            const Ref& r = src[t.begin + !swap];
            dst[t.begin] = l;
            dst[t.begin + 1] = r;
            left.bounds = {l.box(), {l.centroid(), l.centroid()}};
            right.bounds = {r.box(), {r.centroid(), r.centroid()}};
            mid = t.begin + 1;
        } else if (small) {
            const auto goes_left = [&](std::uint32_t i) { return small_bin_[i - t.begin][best.axis] < best.bin; };
            std::uint32_t n_left = 0;
            for (std::uint32_t i = t.begin; i < t.end; ++i) n_left += goes_left(i);
            mid = partition_serial(src, dst, t, n_left, goes_left, left.bounds, right.bounds);
        } else {
            mid = partition(src, dst, t, best, left.bounds, right.bounds, threads);
        }
        left = {0, t.begin, mid, t.depth + 1, left.bounds};
        right = {0, mid, t.end, t.depth + 1, right.bounds};
        return true;
    }

    // Builds the subtree below t (whose node is the first of its slice);
    // returns its node count.
    std::uint32_t build_subtree(const Task& root) {
        std::uint32_t next = root.node + 1;
        std::vector<Task> stack;
        Task t = root;
        for (;;) {  // depth first, left child next: it skips the stack
            Task left, right;
            if (split(t, left, right, 1)) {
                left.node = next++;
                right.node = next++;
                s_.nodes[t.node].left_or_first = left.node;
                s_.nodes[t.node].right_or_count = right.node;
                // Half of all nodes are single-primitive leaves: written
                // here, they skip split()'s entry and the stack.
                if (right.end - right.begin == 1) leaf_of_one(right);
                else stack.push_back(right);
                if (left.end - left.begin > 1) {
                    t = left;
                    continue;
                }
                leaf_of_one(left);
            }
            if (stack.empty()) break;
            t = stack.back();
            stack.pop_back();
        }
        return next - root.node;
    }

private:
    // What split() makes of a one-reference task.
    void leaf_of_one(const Task& t) {
        BinaryNode& node = s_.nodes[t.node];
        node.lo = t.bounds.box.lo;
        node.hi = t.bounds.box.hi;
        node.left_or_first = t.begin;
        node.right_or_count = 1u | BinaryNode::kLeafBit;
        s_.prim_ids[t.begin] = s_.refs[t.depth % 2][t.begin].id;
    }

    // Big nodes go in chunks of kChunk references, the last one taking the rest.
    static std::uint32_t chunks(const Task& t, unsigned threads) {
        const std::uint32_t count = t.end - t.begin;
        return threads > 1 && count >= 2 * kChunk ? count / kChunk : 1;
    }
    static std::pair<std::uint32_t, std::uint32_t> chunk(const Task& t, std::size_t k,
                                                         std::uint32_t n) {
        const auto begin = t.begin + static_cast<std::uint32_t>(k) * kChunk;
        return {begin, k + 1 == n ? t.end : begin + kChunk};
    }

    const Bins& bin(const Ref* src, const Task& t, const BinMap& map, unsigned threads) {
        const std::uint32_t n = chunks(t, threads);
        chunk_bins_.resize(std::max<std::size_t>(chunk_bins_.size(), n));
        std::uint32_t* ref_bins = s_.ref_bins.get();
        parallel_for(n, threads, [&](std::size_t k, unsigned) {
            const auto [begin, end] = chunk(t, k, n);
            Bins& bins = chunk_bins_[k];
            bins.reset(map.bins);
            for (std::uint32_t i = begin; i < end; ++i) {
                const I4 b = map.of(src[i]);
                ref_bins[i] = pack_bins(b);
                bins.add(src[i], b);
            }
        }, 1);
        for (std::uint32_t k = 1; k < n; ++k) chunk_bins_[0].add(chunk_bins_[k], map.bins);
        return chunk_bins_[0];  // chunks beyond the first keep their own counts
    }

    // Small nodes: the same bins, prices and ties, but only the occupied bins
    // are reset and filled (resetting all 3 x 16 bins costs more than binning
    // a few primitives), and each primitive's bins are kept for the partition.
    const Bins& bin_small(const Ref* src, const Task& t, const BinMap& map) {
        std::array<std::uint64_t, 3> mask{};
        for (std::uint32_t i = t.begin; i < t.end; ++i) {
            const I4 b = small_bin_[i - t.begin] = map.of(src[i]);
            for (int axis = 0; axis < 3; ++axis) mask[axis] |= std::uint64_t{1} << b[axis];
        }
        small_used_.count = {};
        for (int axis = 0; axis < 3; ++axis) {
            for (std::uint64_t m = mask[axis]; m != 0; m &= m - 1) {
                const int b = std::countr_zero(m);
                small_used_.bin[axis][small_used_.count[axis]++] = b;
                small_bins_.bin[axis][b] = {};
            }
        }
        for (std::uint32_t i = t.begin; i < t.end; ++i) small_bins_.add(src[i], small_bin_[i - t.begin]);
        return small_bins_;
    }

    // Stable partition of src[begin, end) into dst: the references for which
    // goes_left(i) holds go to dst[l, ...) in order, the rest to dst[r, ...);
    // also the bounds of each side. Returns the end of the left part.
    template <class GoesLeft>
    static std::uint32_t partition_range(const Ref* src, Ref* dst, std::uint32_t begin, std::uint32_t end,
                                         std::uint32_t l, std::uint32_t r, GoesLeft goes_left, Bounds& left,
                                         Bounds& right) {
        std::array<Box4, 2> box, cbox;  // left, right: Bounds::add's comparisons, on lanes
        for (std::uint32_t i = begin; i < end; ++i) {
            const Ref& ref = src[i];
            const bool to_left = goes_left(i);
            // Branch-free: the side is a coin toss per reference, and GCC
            // compiled `dst[to_left ? l++ : r++]` into a branch that missed
            // 8.4 times per primitive (callgrind --branch-sim, 200,000 bundle capsules).
            dst[to_left ? l : r] = ref;
            l += to_left;
            r += !to_left;
            box[!to_left].extend(ref.lanes(ref.lo), ref.lanes(ref.hi));
            const V4 c = ref.centroid_lanes();
            cbox[!to_left].extend(c, c);
        }
        left = {box[0].aabb(), cbox[0].aabb()};
        right = {box[1].aabb(), cbox[1].aabb()};
        return l;
    }
    // The whole range of t, its n_left left references first.
    template <class GoesLeft>
    static std::uint32_t partition_serial(const Ref* src, Ref* dst, const Task& t, std::uint32_t n_left,
                                          GoesLeft goes_left, Bounds& left, Bounds& right) {
        return partition_range(src, dst, t.begin, t.end, t.begin, t.begin + n_left, goes_left, left, right);
    }

    // Stable partition by bin into dst; each chunk's left part starts after the
    // left parts of the chunks before it, known from the chunk's bin counts.
    std::uint32_t partition(const Ref* src, Ref* dst, const Task& t, const Split& best, Bounds& left,
                            Bounds& right, unsigned threads) {
        const std::uint32_t n = chunks(t, threads);
        const std::uint32_t* ref_bins = s_.ref_bins.get();
        const int shift = 8 * best.axis;
        const auto below = [&, bin = static_cast<std::uint32_t>(best.bin)](std::uint32_t i) {
            return ((ref_bins[i] >> shift) & 0xFFu) < bin;
        };
        if (n == 1) {
            std::uint32_t n_left = 0;
            for (int b = 0; b < best.bin; ++b) n_left += chunk_bins_[0].bin[best.axis][b].count;
            return partition_serial(src, dst, t, n_left, below, left, right);
        }
        // Left counts per chunk; chunk 0's bins were summed into the node's.
        std::vector<std::uint32_t> left_at(n + 1, 0);
        for (std::uint32_t k = 0; k < n; ++k)
            for (int b = 0; b < best.bin; ++b) left_at[k + 1] += chunk_bins_[k].bin[best.axis][b].count;
        const std::uint32_t n_left = left_at[1];
        for (std::uint32_t k = 1; k < n; ++k) left_at[1] -= left_at[k + 1];
        left_at[0] = t.begin;
        for (std::uint32_t k = 0; k < n; ++k) left_at[k + 1] += left_at[k];
        std::vector<std::array<Bounds, 2>> parts(n);
        parallel_for(n, threads, [&](std::size_t k, unsigned) {
            const auto [begin, end] = chunk(t, k, n);
            const std::uint32_t r = t.begin + n_left + (begin - t.begin) - (left_at[k] - t.begin);
            (void)partition_range(src, dst, begin, end, left_at[k], r, below, parts[k][0], parts[k][1]);
        }, 1);
        left = right = {};
        for (const auto& p : parts) left.add(p[0]), right.add(p[1]);
        return t.begin + n_left;
    }

    // Object median along the widest centroid axis; ties by primitive index.
    static std::uint32_t median_split(const Ref* src, Ref* dst, const Task& t, Bounds& left,
                                      Bounds& right) {
        const Vec3 e = t.bounds.cbox.extent();
        const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
        const std::uint32_t mid = t.begin + (t.end - t.begin) / 2;
        std::copy(src + t.begin, src + t.end, dst + t.begin);
        std::nth_element(dst + t.begin, dst + mid, dst + t.end, [&](const Ref& a, const Ref& b) {
            const float ca = a.centroid()[axis], cb = b.centroid()[axis];
            return ca < cb || (ca == cb && a.id < b.id);
        });
        left = right = {};
        for (std::uint32_t i = t.begin; i < mid; ++i) left.add(dst[i]);
        for (std::uint32_t i = mid; i < t.end; ++i) right.add(dst[i]);
        return mid;
    }

    Shared& s_;
    std::vector<Bins> chunk_bins_;
    Bins small_bins_;  // only the occupied bins are ever reset
    Occupied small_used_;
    std::array<I4, kSmall> small_bin_;  // each reference's bins, for the partition
};

}  // namespace rtc::bvh_detail
