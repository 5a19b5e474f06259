// Binned SAH builder (Wald 2007, "On fast construction of SAH-based bounding
// volume hierarchies") producing a binary tree, then collapsed into nodes of
// the requested width by repeatedly opening the child with the largest surface
// area (the usual collapse used for wide hardware BVHs, e.g. Ylitie et al.
// 2017 use a cost-based variant).
#include "core/bvh.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace rtc {
namespace {

struct BinaryNode {
    Aabb box;
    std::uint32_t left = 0, right = 0;  // inner node children
    std::uint32_t first = 0, count = 0; // leaf: range in the id array (count > 0)
    [[nodiscard]] bool is_leaf() const { return count > 0; }
};

// Past this binary depth splits fall back to the object median, which bounds
// the depth of any tree (and so the traversal stack) by kMaxSahDepth + log2(n).
constexpr int kMaxSahDepth = 40;
constexpr int kMaxBins = 64;

struct Split {
    int axis = -1;
    int bin = 0;  // primitives in bins [0, bin) go left
    float cost = kInfinity;
};

class BinaryBuilder {
public:
    BinaryBuilder(std::span<const Aabb> boxes, std::span<const Vec3> centroids,
                  const BuildOptions& o)
        : boxes_(boxes), centroids_(centroids), o_(o) {}

    std::vector<BinaryNode> build(std::vector<std::uint32_t>& ids) {
        ids.resize(boxes_.size());
        for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i;
        ids_ = &ids;
        if (ids.empty()) return nodes_;
        nodes_.reserve(2 * ids.size());
        nodes_.push_back({});
        struct Task { std::uint32_t node, begin, end; int depth; };
        std::vector<Task> stack{{0, 0, static_cast<std::uint32_t>(ids.size()), 0}};
        while (!stack.empty()) {
            const Task t = stack.back();
            stack.pop_back();
            const std::uint32_t mid = split(t.node, t.begin, t.end, t.depth);
            if (mid == t.begin) continue;  // became a leaf
            const auto left = static_cast<std::uint32_t>(nodes_.size());
            nodes_.push_back({});
            nodes_.push_back({});
            nodes_[t.node].left = left;
            nodes_[t.node].right = left + 1;
            stack.push_back({left + 1, mid, t.end, t.depth + 1});
            stack.push_back({left, t.begin, mid, t.depth + 1});
        }
        return std::move(nodes_);
    }

private:
    // Sets the node's box; makes it a leaf (returns begin) or partitions the
    // range and returns the first index of the right half.
    std::uint32_t split(std::uint32_t node, std::uint32_t begin, std::uint32_t end, int depth) {
        auto& ids = *ids_;
        Aabb box, cbox;
        for (std::uint32_t i = begin; i < end; ++i) {
            box.extend(boxes_[ids[i]]);
            cbox.extend(centroids_[ids[i]]);
        }
        nodes_[node].box = box;
        const std::uint32_t count = end - begin;
        const auto make_leaf = [&] {
            nodes_[node].first = begin;
            nodes_[node].count = count;
            return begin;
        };
        if (count == 1) return make_leaf();

        const bool fits_leaf = count <= static_cast<std::uint32_t>(o_.max_leaf_size);
        Split best;
        if (o_.strategy == SplitStrategy::Sah && depth < kMaxSahDepth)
            best = find_sah_split(begin, end, cbox, box.surface_area());
        if (fits_leaf) {
            const float leaf_cost = o_.intersection_cost * static_cast<float>(count);
            if (best.axis < 0 || leaf_cost <= best.cost) return make_leaf();
        }
        if (best.axis >= 0) {
            const int axis = best.axis;
            const auto mid_it = std::stable_partition(
                ids.begin() + begin, ids.begin() + end,
                [&](std::uint32_t id) { return bin_of(centroids_[id], cbox, axis) < best.bin; });
            return static_cast<std::uint32_t>(mid_it - ids.begin());
        }
        return median_split(begin, end, cbox);
    }

    [[nodiscard]] int bins() const { return std::clamp(o_.bins, 2, kMaxBins); }

    [[nodiscard]] int bin_of(const Vec3& c, const Aabb& cbox, int axis) const {
        const float extent = cbox.hi[axis] - cbox.lo[axis];
        const float scale = static_cast<float>(bins()) / extent;
        const int b = static_cast<int>((c[axis] - cbox.lo[axis]) * scale);
        return std::clamp(b, 0, bins() - 1);
    }

    Split find_sah_split(std::uint32_t begin, std::uint32_t end, const Aabb& cbox, float area) {
        const auto& ids = *ids_;
        const int n_bins = bins();
        Split best;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(cbox.hi[axis] > cbox.lo[axis])) continue;
            std::array<Aabb, kMaxBins> bin_box{};
            std::array<std::uint32_t, kMaxBins> bin_count{};
            for (std::uint32_t i = begin; i < end; ++i) {
                const int b = bin_of(centroids_[ids[i]], cbox, axis);
                bin_box[b].extend(boxes_[ids[i]]);
                ++bin_count[b];
            }
            // Right-to-left sweep stores the cost of each right part.
            std::array<float, kMaxBins> right_cost{};
            Aabb acc;
            std::uint32_t n = 0;
            for (int b = n_bins - 1; b > 0; --b) {
                acc.extend(bin_box[b]);
                n += bin_count[b];
                right_cost[b] = acc.surface_area() * static_cast<float>(n);
            }
            acc = {};
            n = 0;
            for (int b = 1; b < n_bins; ++b) {
                acc.extend(bin_box[b - 1]);
                n += bin_count[b - 1];
                const std::uint32_t right_n = (end - begin) - n;
                if (n == 0 || right_n == 0) continue;
                const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
                const float cost =
                    o_.traversal_cost + o_.intersection_cost *
                                            (acc.surface_area() * static_cast<float>(n) +
                                             right_cost[b]) * inv_area;
                if (cost < best.cost) best = {axis, b, cost};  // strict: ties keep the first
            }
        }
        return best;
    }

    // Object median along the widest centroid axis; ties by primitive index.
    std::uint32_t median_split(std::uint32_t begin, std::uint32_t end, const Aabb& cbox) {
        auto& ids = *ids_;
        const Vec3 e = cbox.extent();
        const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
        const std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             const float ca = centroids_[a][axis], cb = centroids_[b][axis];
                             return ca < cb || (ca == cb && a < b);
                         });
        return mid;
    }

    std::span<const Aabb> boxes_;
    std::span<const Vec3> centroids_;
    const BuildOptions& o_;
    std::vector<std::uint32_t>* ids_ = nullptr;
    std::vector<BinaryNode> nodes_;
};

// Chooses up to `width` binary descendants of `node` to become its children in
// the wide tree: open the inner child of largest area until the node is full.
std::array<std::uint32_t, 8> collapse_children(const std::vector<BinaryNode>& nodes,
                                               std::uint32_t node, int width, int& n) {
    std::array<std::uint32_t, 8> kids{nodes[node].left, nodes[node].right};
    n = 2;
    while (n < width) {
        int pick = -1;
        float pick_area = -1.0f;
        for (int i = 0; i < n; ++i) {
            const BinaryNode& k = nodes[kids[i]];
            if (!k.is_leaf() && k.box.surface_area() > pick_area) {
                pick = i;
                pick_area = k.box.surface_area();
            }
        }
        if (pick < 0) break;
        const BinaryNode& opened = nodes[kids[pick]];
        for (int i = n; i > pick + 1; --i) kids[i] = kids[i - 1];
        kids[pick] = opened.left;
        kids[pick + 1] = opened.right;
        ++n;
    }
    return kids;
}

void validate(std::span<const Aabb> boxes, std::span<const Vec3> centroids) {
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const Vec3& c = centroids[i];
        if (!boxes[i].finite() || !std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z))
            throw std::invalid_argument("BVH build: primitive " + std::to_string(i) +
                                        " has a NaN or infinite bounding box");
        if (boxes[i].empty())
            throw std::invalid_argument("BVH build: primitive " + std::to_string(i) +
                                        " has an inverted (empty) bounding box");
    }
}

}  // namespace

Bvh build_bvh(std::span<const Aabb> boxes, const BuildOptions& options,
              std::span<const Vec3> centroids) {
    if (options.width != 2 && options.width != 4 && options.width != 8)
        throw std::invalid_argument("BVH build: width must be 2, 4 or 8, got " +
                                    std::to_string(options.width));
    if (options.max_leaf_size < 1)
        throw std::invalid_argument("BVH build: max_leaf_size must be at least 1");
    std::vector<Vec3> own_centroids;
    if (centroids.empty()) {
        own_centroids.reserve(boxes.size());
        for (const Aabb& b : boxes) own_centroids.push_back(b.center());
        centroids = own_centroids;
    }
    if (centroids.size() != boxes.size())
        throw std::invalid_argument("BVH build: one centroid per box expected");
    validate(boxes, centroids);

    Bvh bvh;
    bvh.width = options.width;
    const std::vector<BinaryNode> nodes =
        BinaryBuilder(boxes, centroids, options).build(bvh.prim_ids);
    bvh.root.count = BvhEntry::kInnerBit;  // empty root node
    if (nodes.empty()) return bvh;

    bvh.entries.reserve(nodes.size());
    const auto fill = [&](std::uint32_t slot, std::uint32_t b) {
        BvhEntry& e = bvh.entries[slot];
        e.box = nodes[b].box;
        e.first = nodes[b].first;
        e.count = nodes[b].count;
    };
    // Work list of (binary inner node, entry slot that will point at its children;
    // UINT32_MAX for the root).
    struct Work { std::uint32_t binary, slot; };
    std::vector<Work> work;
    bvh.root.box = nodes[0].box;
    if (nodes[0].is_leaf()) {  // a lone leaf still hangs below a root node
        bvh.entries.resize(1);
        fill(0, 0);
        bvh.root.first = 0;
        bvh.root.count = 1 | BvhEntry::kInnerBit;
        return bvh;
    }
    work.push_back({0, UINT32_MAX});
    while (!work.empty()) {
        const Work w = work.back();
        work.pop_back();
        int n = 0;
        const auto kids = collapse_children(nodes, w.binary, options.width, n);
        const auto first = static_cast<std::uint32_t>(bvh.entries.size());
        bvh.entries.resize(first + n);
        BvhEntry& parent = w.slot == UINT32_MAX ? bvh.root : bvh.entries[w.slot];
        parent.first = first;
        parent.count = static_cast<std::uint32_t>(n) | BvhEntry::kInnerBit;
        for (int i = n - 1; i >= 0; --i) {
            fill(first + i, kids[i]);
            if (!nodes[kids[i]].is_leaf()) work.push_back({kids[i], first + i});
        }
    }
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
