// The binary SAH builder. Primitives travel as packed references (box,
// centroid, id) that each split stably partitions from one buffer into the
// other, so every pass reads memory in order, and a node's bounds come from
// its parent's partition pass. Large nodes bin and partition in chunks on all
// threads; below a size threshold the subtrees are built as independent
// tasks, each into its own slice of the node array. Every reduction is folded
// in primitive order, so the tree (down to the sign of zero in a box) is the
// same for any thread count, and the same as the plain serial algorithm.
// This file: the references' loading, the top of the tree and the subtree
// tasks; the split of one node is bvh_build_split.h.
#include "core/build/bvh_build_binary.h"
#include "core/build/bvh_build_split.h"
#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace rtc::bvh_detail {
namespace {

// Subtrees at most this big (or n / (8 threads)) are built as one serial task.
constexpr std::uint32_t kMinTask = 4096;

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Fills buffer 0 with the references and returns the root's bounds; throws
// for the first invalid primitive, whichever thread met it.
Bounds load(Shared& s, std::span<const Aabb> boxes, unsigned threads) {
    const std::size_t n = boxes.size();
    const std::size_t n_chunks = (n + kChunk - 1) / kChunk;
    std::vector<Bounds> parts(n_chunks);
    std::vector<std::size_t> first_bad(n_chunks, n);
    Ref* refs = s.refs[0];
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
// number of binary nodes. Nodes bigger than the task size (the top) are split
// a level at a time: while a level has fewer nodes than threads, or a node has
// enough chunks to keep every thread busy, that node is split with all threads,
// one node after another; the rest of a level of at least `threads` nodes are
// split side by side, one per thread, biggest first. A node of a few chunks on
// all threads left threads idle (3 chunks on 2 threads: a third of the time),
// and one parallel call per node cost a wake-up each. The rest are subtree
// tasks spread over the threads, biggest first. A node's split is the same on
// one thread as on many, so the tree does not depend on which way it went.
std::pair<std::uint32_t, std::size_t> build_binary(Shared& s, const Bounds& root_bounds,
                                                   unsigned threads) {
    const auto n = static_cast<std::uint32_t>(s.prim_ids.size());
    const std::uint32_t task_size = threads > 1 ? std::max(kMinTask, n / (8 * threads)) : n;
    // Split with all threads at any level: at least four chunks per thread.
    const std::uint64_t alone_size = std::uint64_t{4} * threads * kChunk;
    // Room for the nodes above the tasks too (usually fewer than 4 n /
    // task_size), so that appending them does not copy the whole array.
    s.nodes.reserve(2 * std::size_t{n} + 4 * std::size_t{n / task_size} + 16);
    s.nodes.resize(2 * std::size_t{n});
    std::vector<Task> level, next, tasks;
    const auto place = [&](Task t) {
        if (t.end - t.begin <= task_size) {
            t.node = 2 * t.begin;
            tasks.push_back(t);
        } else {
            t.node = static_cast<std::uint32_t>(s.nodes.size());
            s.nodes.emplace_back();
            next.push_back(t);
        }
        return t.node;
    };
    const auto link = [&](const Task& t, const Task& left, const Task& right) {
        const std::uint32_t l = place(left), r = place(right);
        s.nodes[t.node].left_or_first = l;
        s.nodes[t.node].right_or_count = r;
    };
    std::vector<std::unique_ptr<Splitter>> splitters(threads);
    const auto splitter = [&](unsigned thread) -> Splitter& {
        if (!splitters[thread]) splitters[thread] = std::make_unique<Splitter>(s);
        return *splitters[thread];
    };
    const std::uint32_t root = place({0, 0, n, 0, root_bounds});
    struct SideSplit {
        Task left, right;
        bool inner = false;  // split() made the node inner (else a leaf)
    };
    std::vector<Task> side;
    std::vector<SideSplit> side_split;
    while (!next.empty()) {
        level.swap(next);
        next.clear();
        side.clear();
        const bool side_by_side = level.size() >= threads && threads > 1;
        for (const Task& t : level) {
            if (side_by_side && t.end - t.begin < alone_size) {
                side.push_back(t);
                continue;
            }
            Task left, right;
            if (splitter(0).split(t, left, right, threads)) link(t, left, right);
        }
        if (side.empty()) continue;
        std::stable_sort(side.begin(), side.end(),
                         [](const Task& a, const Task& b) { return a.end - a.begin > b.end - b.begin; });
        side_split.assign(side.size(), {});
        parallel_for(side.size(), threads, [&](std::size_t i, unsigned thread) {
            SideSplit& r = side_split[i];
            r.inner = splitter(thread).split(side[i], r.left, r.right, 1);
        }, 1);
        // Placed after the round, in the sorted order: the node indices do
        // not depend on which thread finished first.
        for (std::size_t i = 0; i < side.size(); ++i)
            if (side_split[i].inner) link(side[i], side_split[i].left, side_split[i].right);
    }
    std::stable_sort(tasks.begin(), tasks.end(),
                     [](const Task& a, const Task& b) { return a.end - a.begin > b.end - b.begin; });
    std::vector<std::uint32_t> sizes(tasks.size());
    parallel_for(tasks.size(), threads, [&](std::size_t i, unsigned thread) {
        sizes[i] = splitter(thread).build_subtree(tasks[i]);
    }, 1);
    std::size_t count = s.nodes.size() - 2 * std::size_t{n};
    for (const std::uint32_t size : sizes) count += size;
    return {root, count};
}
}  // namespace

BinaryTree build_binary_tree(std::span<const Aabb> boxes, const BuildOptions& options, unsigned threads,
                             UninitializedVector<std::uint32_t>& prim_ids) {
    const std::size_t n = boxes.size();
    Shared s{options, std::clamp(options.bins, 2, kMaxBins), {}, {}, {}, {}, prim_ids};
    // Bytes, in which the references are created (an array of bytes
    // implicitly creates them), so that the collapse can then place its
    // entries there.
    static_assert(alignof(Ref) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__);
    const std::size_t bytes = 2 * n * sizeof(Ref);
    s.ref_memory = std::make_unique_for_overwrite<std::byte[]>(bytes);
    Ref* const refs = n > 0 ? std::launder(reinterpret_cast<Ref*>(s.ref_memory.get())) : nullptr;
    s.refs = {refs, refs + n};
    const Bounds root_bounds = load(s, boxes, threads);
    BinaryTree tree;
    if (n == 0) return tree;
    s.ref_bins = std::make_unique_for_overwrite<std::uint32_t[]>(n);
    std::tie(tree.root, tree.count) = build_binary(s, root_bounds, threads);
    tree.nodes = std::move(s.nodes);
    tree.spare = std::move(s.ref_memory);
    tree.spare_bytes = bytes;
    return tree;
}

}  // namespace rtc::bvh_detail
