// The binary SAH builder. Primitives travel as packed references (box,
// centroid, id) that each split stably partitions from one buffer into the
// other, so every pass reads memory in order, and a node's bounds come from
// its parent's partition pass. Large nodes bin and partition in chunks on all
// threads; below a size threshold the subtrees are built as independent
// tasks, each into its own slice of the node array. Every reduction is folded
// in primitive order, so the tree (down to the sign of zero in a box) is the
// same for any thread count, and the same as the plain serial algorithm.
#include "core/build/bvh_build_binary.h"
#include "core/build/bvh_build_refs.h"
#include "core/build/bvh_build_sah.h"
#include "core/parallel.h"

#include <algorithm>
#include <array>
#include <bit>
#include <memory>
#include <stdexcept>
#include <string>

namespace rtc::bvh_detail {
namespace {

// Past this binary depth splits fall back to the object median, which bounds
// the depth of any tree (and so the traversal stack) by kMaxSahDepth + log2(n).
constexpr int kMaxSahDepth = 40;
// References per chunk of a node's range binned or partitioned by one thread.
constexpr std::uint32_t kChunk = 16384;
// Subtrees at most this big (or n / (8 threads)) are built as one serial task.
constexpr std::uint32_t kMinTask = 4096;
// Nodes at most this big bin only into the bins they occupy.
constexpr std::uint32_t kSmall = 32;

struct Task {
    std::uint32_t node, begin, end;
    int depth;  // the references of the range live in buffer depth % 2
    Bounds bounds;
};

// What every thread shares: the two reference buffers, the binary nodes (each
// subtree task owns the slice [2 begin, 2 end - 1), which bounds its node
// count; nodes above the tasks are appended after 2 n) and the output ids.
struct Shared {
    const BuildOptions& options;
    int bins;
    std::array<std::unique_ptr<Ref[]>, 2> refs;
    // A big node's binning keeps each reference's three bins here (one byte
    // each, by position in the node's buffer) for its partition, which then
    // places every reference by the very bins that were counted.
    std::unique_ptr<std::uint32_t[]> ref_bins;
    BinaryNodes nodes;
    UninitializedVector<std::uint32_t>& prim_ids;
};

// A reference's three bins (0 .. 63, lane 3 is 0) as bytes 0, 1 and 2.
std::uint32_t pack_bins(I4 b) {
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
        const Ref* src = s_.refs[t.depth % 2].get();
        Ref* dst = s_.refs[(t.depth + 1) % 2].get();
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
bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Fills buffer 0 with the references and returns the root's bounds; throws
// for the first invalid primitive, whichever thread met it.
Bounds load(Shared& s, std::span<const Aabb> boxes, unsigned threads) {
    const std::size_t n = boxes.size();
    const std::size_t n_chunks = (n + kChunk - 1) / kChunk;
    std::vector<Bounds> parts(n_chunks);
    std::vector<std::size_t> first_bad(n_chunks, n);
    Ref* refs = s.refs[0].get();
    parallel_for(n_chunks, threads, [&](std::size_t k, unsigned) {
        Box4 box, cbox;  // the comparisons of Bounds::add, on lanes
        for (std::size_t i = k * kChunk; i < std::min(n, (k + 1) * kChunk); ++i) {
            const Aabb& b = boxes[i];
            // A finite box whose centre overflows is refused too: every
            // split works with the centres.
            if (first_bad[k] == n && (!b.finite() || !finite(b.center()) || b.empty())) first_bad[k] = i;
            const Ref& r = refs[i] = {b.lo, static_cast<std::uint32_t>(i), b.hi, 0.0f};
            box.extend(r.lanes(r.lo), r.lanes(r.hi));
            const V4 c = r.centroid_lanes();
            cbox.extend(c, c);
        }
        parts[k] = {box.aabb(), cbox.aabb()};
    }, 1);
    for (std::size_t k = 0; k < n_chunks; ++k) {
        const std::size_t i = first_bad[k];
        if (i == n) continue;
        throw std::invalid_argument("BVH build: primitive " + std::to_string(i) +
                                    (boxes[i].finite() && finite(boxes[i].center())
                                         ? " has an inverted (empty) bounding box"
                                         : " has a NaN or infinite bounding box"));
    }
    Bounds root;
    for (const Bounds& p : parts) root.add(p);
    return root;
}

// Builds the binary tree into s.nodes and returns the root's index and the
// number of binary nodes: nodes
// bigger than the task size are split one at a time with all threads, the
// rest are subtree tasks spread over the threads, biggest first.
std::pair<std::uint32_t, std::size_t> build_binary(Shared& s, const Bounds& root_bounds,
                                                   unsigned threads) {
    const auto n = static_cast<std::uint32_t>(s.prim_ids.size());
    const std::uint32_t task_size = threads > 1 ? std::max(kMinTask, n / (8 * threads)) : n;
    // Room for the nodes above the tasks too (usually fewer than 4 n /
    // task_size), so that appending them does not copy the whole array.
    s.nodes.reserve(2 * std::size_t{n} + 4 * std::size_t{n / task_size} + 16);
    s.nodes.resize(2 * std::size_t{n});
    std::vector<Task> stack, tasks;
    const auto place = [&](Task t) {
        if (t.end - t.begin <= task_size) {
            t.node = 2 * t.begin;
            tasks.push_back(t);
        } else {
            t.node = static_cast<std::uint32_t>(s.nodes.size());
            s.nodes.emplace_back();
            stack.push_back(t);
        }
        return t.node;
    };
    const std::uint32_t root = place({0, 0, n, 0, root_bounds});
    Splitter top(s);
    while (!stack.empty()) {
        const Task t = stack.back();
        stack.pop_back();
        Task left, right;
        if (!top.split(t, left, right, threads)) continue;
        const std::uint32_t l = place(left), r = place(right);
        s.nodes[t.node].left_or_first = l;
        s.nodes[t.node].right_or_count = r;
    }
    std::stable_sort(tasks.begin(), tasks.end(),
                     [](const Task& a, const Task& b) { return a.end - a.begin > b.end - b.begin; });
    std::vector<std::unique_ptr<Splitter>> splitters(threads);
    std::vector<std::uint32_t> sizes(tasks.size());
    parallel_for(tasks.size(), threads, [&](std::size_t i, unsigned thread) {
        if (!splitters[thread]) splitters[thread] = std::make_unique<Splitter>(s);
        sizes[i] = splitters[thread]->build_subtree(tasks[i]);
    }, 1);
    std::size_t count = s.nodes.size() - 2 * std::size_t{n};
    for (const std::uint32_t size : sizes) count += size;
    return {root, count};
}
}  // namespace

BinaryTree build_binary_tree(std::span<const Aabb> boxes, const BuildOptions& options, unsigned threads,
                             UninitializedVector<std::uint32_t>& prim_ids) {
    const std::size_t n = boxes.size();
    Shared s{options, std::clamp(options.bins, 2, kMaxBins), {}, {}, {}, prim_ids};
    s.refs[0] = std::make_unique_for_overwrite<Ref[]>(n);
    const Bounds root_bounds = load(s, boxes, threads);
    BinaryTree tree;
    if (n == 0) return tree;
    s.refs[1] = std::make_unique_for_overwrite<Ref[]>(n);
    s.ref_bins = std::make_unique_for_overwrite<std::uint32_t[]>(n);
    std::tie(tree.root, tree.count) = build_binary(s, root_bounds, threads);
    tree.nodes = std::move(s.nodes);
    return tree;
}

}  // namespace rtc::bvh_detail
