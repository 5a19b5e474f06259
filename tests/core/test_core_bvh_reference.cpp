// The optimized builder (core/build/) against a plain reference kept here:
// recursive binned SAH over a vector of records, with Aabb arithmetic, a
// full sweep over all bins and std::stable_partition, then the same
// collapse to the wide layout. The trees must be identical byte for byte
// (root, entries, primitive order), so that a faster builder can never
// change a result.
#include "core/bvh.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

namespace {

struct Rec {
    Aabb box;
    Vec3 c;
    std::uint32_t id;
};
struct Node {
    Aabb box;
    int left = -1, right = -1;  // inner
    std::uint32_t first = 0, count = 0;  // leaf
};

struct Reference {
    const BuildOptions& o;
    std::vector<Rec> recs;
    std::vector<Node> nodes;

    int bin(const Aabb& cbox, float scale, const Vec3& c, int axis) const {
        const float x = (c[axis] - cbox.lo[axis]) * scale;
        if (!(x < 2147483648.0f)) return 0;  // also NaN
        const int bins = std::clamp(o.bins, 2, 64);
        return static_cast<int>(std::min(std::max(x, 0.0f), static_cast<float>(bins - 1)));
    }

    int build(std::uint32_t begin, std::uint32_t end, int depth) {
        Aabb box, cbox;
        for (std::uint32_t i = begin; i < end; ++i) box.extend(recs[i].box), cbox.extend(recs[i].c);
        const int index = static_cast<int>(nodes.size());
        nodes.push_back({box});
        const std::uint32_t count = end - begin;
        const auto leaf = [&] {
            nodes[index].first = begin;
            nodes[index].count = count;
            return index;
        };
        if (count == 1) return leaf();
        const int bins = std::clamp(o.bins, 2, 64);
        int best_axis = -1, best_bin = 0;
        float best_cost = kInfinity;
        if (o.strategy == SplitStrategy::Sah && depth < 40) {
            const float area = box.surface_area();
            const float inv_area = area > 0.0f ? 1.0f / area : 0.0f;
            for (int axis = 0; axis < 3; ++axis) {
                if (!(cbox.hi[axis] > cbox.lo[axis])) continue;
                const float scale = static_cast<float>(bins) / (cbox.hi[axis] - cbox.lo[axis]);
                std::vector<Aabb> bbox(bins);
                std::vector<std::uint32_t> n(bins, 0);
                for (std::uint32_t i = begin; i < end; ++i) {
                    const int b = bin(cbox, scale, recs[i].c, axis);
                    bbox[b].extend(recs[i].box);
                    ++n[b];
                }
                Aabb left;
                std::uint32_t n_left = 0;
                for (int b = 0; b + 1 < bins; ++b) {  // plane after bin b
                    left.extend(bbox[b]);
                    n_left += n[b];
                    if (n[b] == 0 || n_left == count) continue;
                    Aabb right;
                    for (int k = b + 1; k < bins; ++k) right.extend(bbox[k]);
                    const float cost = o.traversal_cost +
                                       o.intersection_cost *
                                           (left.surface_area() * static_cast<float>(n_left) +
                                            right.surface_area() * static_cast<float>(count - n_left)) *
                                           inv_area;
                    if (cost < best_cost) best_axis = axis, best_bin = b + 1, best_cost = cost;
                }
            }
        }
        if (count <= static_cast<std::uint32_t>(o.max_leaf_size) &&
            (best_axis < 0 || o.intersection_cost * static_cast<float>(count) <= best_cost))
            return leaf();
        std::uint32_t mid;
        if (best_axis < 0) {  // object median along the widest centroid axis
            const Vec3 e = cbox.extent();
            const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(recs.begin() + begin, recs.begin() + mid, recs.begin() + end,
                             [&](const Rec& a, const Rec& b) {
                                 return a.c[axis] < b.c[axis] || (a.c[axis] == b.c[axis] && a.id < b.id);
                             });
        } else {
            const float scale = static_cast<float>(bins) / (cbox.hi[best_axis] - cbox.lo[best_axis]);
            mid = static_cast<std::uint32_t>(
                std::stable_partition(recs.begin() + begin, recs.begin() + end,
                                      [&](const Rec& r) { return bin(cbox, scale, r.c, best_axis) < best_bin; }) -
                recs.begin());
        }
        const int l = build(begin, mid, depth + 1);
        const int r = build(mid, end, depth + 1);
        nodes[index].left = l;
        nodes[index].right = r;
        return index;
    }

    // The wide layout: open the inner child of largest area until full; the
    // children of a node are written when it is taken off a stack.
    Bvh collapse() const {
        Bvh bvh;
        bvh.width = o.width;
        bvh.root.count = BvhEntry::kInnerBit;
        for (const Rec& r : recs) bvh.prim_ids.push_back(r.id);
        if (recs.empty()) return bvh;
        const auto entry = [&](int b) {
            const Node& n = nodes[b];
            return BvhEntry{n.box, n.left < 0 ? n.first : 0, n.left < 0 ? n.count : 0};
        };
        bvh.root.box = nodes[0].box;
        if (nodes[0].left < 0) {
            bvh.entries.push_back(entry(0));
            bvh.root.count = 1 | BvhEntry::kInnerBit;
            return bvh;
        }
        std::vector<std::pair<int, std::uint32_t>> work{{0, UINT32_MAX}};
        while (!work.empty()) {
            const auto [b, slot] = work.back();
            work.pop_back();
            std::vector<int> kids{nodes[b].left, nodes[b].right};
            while (static_cast<int>(kids.size()) < o.width) {
                int pick = -1;
                float pick_area = -1.0f;
                for (int i = 0; i < static_cast<int>(kids.size()); ++i)
                    if (nodes[kids[i]].left >= 0 && nodes[kids[i]].box.surface_area() > pick_area)
                        pick = i, pick_area = nodes[kids[i]].box.surface_area();
                if (pick < 0) break;
                const Node& opened = nodes[kids[pick]];
                kids[pick] = opened.right;
                kids.insert(kids.begin() + pick, opened.left);
            }
            const auto first = static_cast<std::uint32_t>(bvh.entries.size());
            BvhEntry& parent = slot == UINT32_MAX ? bvh.root : bvh.entries[slot];
            parent.first = first;
            parent.count = static_cast<std::uint32_t>(kids.size()) | BvhEntry::kInnerBit;
            for (int k : kids) bvh.entries.push_back(entry(k));
            for (int i = static_cast<int>(kids.size()) - 1; i >= 0; --i)
                if (nodes[kids[i]].left >= 0) work.push_back({kids[i], first + i});
        }
        return bvh;
    }
};

Bvh reference_bvh(const std::vector<Aabb>& boxes, const BuildOptions& o) {
    Reference ref{o, {}, {}};
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
        ref.recs.push_back({boxes[i], boxes[i].center(), i});
    if (!boxes.empty()) ref.build(0, static_cast<std::uint32_t>(boxes.size()), 0);
    return ref.collapse();
}

void check_same(const std::vector<Aabb>& boxes, BuildOptions o) {
    const Bvh want = reference_bvh(boxes, o);
    for (int threads : {1, 2}) {
        o.threads = threads;
        const Bvh got = build_bvh(boxes, o);
        CAPTURE(threads);
        REQUIRE(got.entries.size() == want.entries.size());
        CHECK(got.prim_ids == want.prim_ids);
        CHECK(std::memcmp(&got.root, &want.root, sizeof(BvhEntry)) == 0);
        if (!got.entries.empty())  // (memcmp of an empty vector's null data is undefined)
            CHECK(std::memcmp(got.entries.data(), want.entries.data(), got.entries.size() * sizeof(BvhEntry)) == 0);
        CHECK(got.node_count() == want.node_count());
        CHECK(sah_cost(got) == sah_cost(want));
    }
}

// Capsule boxes of polylines: `strands` random walks of `points` points.
std::vector<Aabb> strand_boxes(Rng& rng, int strands, int points, float step, float radius) {
    std::vector<Aabb> boxes;
    for (int s = 0; s < strands; ++s) {
        Vec3 p = rng.point(-1.0f, 1.0f);
        for (int k = 1; k < points; ++k) {
            const Vec3 q = p + step * rng.direction();
            boxes.push_back({glm::min(p, q) - radius, glm::max(p, q) + radius});
            p = q;
        }
    }
    return boxes;
}

// A bundle: parallel segments of length 1 tilted in the X-Y plane.
std::vector<Aabb> bundle_boxes(Rng& rng, int n) {
    std::vector<Aabb> boxes;
    const Vec3 axis{std::sin(0.7f), std::cos(0.7f), 0.0f};
    for (int i = 0; i < n; ++i) {
        const Vec3 base{rng.uniform(-0.5f, 0.5f), 0.0f, rng.uniform(-0.5f, 0.5f)};
        const Vec3 p = base - 0.5f * axis, q = base + 0.5f * axis;
        boxes.push_back({glm::min(p, q) - 0.002f, glm::max(p, q) + 0.002f});
    }
    return boxes;
}

// Triangles of a height field (a grid, many boxes flat along Y).
std::vector<Aabb> grid_triangles(int side) {
    std::vector<Aabb> boxes;
    const auto v = [&](int i, int j) {
        return Vec3{static_cast<float>(i), 0.1f * std::sin(0.3f * static_cast<float>(i * j)), static_cast<float>(j)};
    };
    for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
            for (const auto& t : {std::array{v(i, j), v(i + 1, j), v(i, j + 1)},
                                  std::array{v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)}}) {
                Aabb b = Aabb::from_point(t[0]);
                b.extend(t[1]);
                b.extend(t[2]);
                boxes.push_back(b);
            }
    return boxes;
}

}  // namespace

TEST_CASE("bvh build: identical to the reference builder on capsule and triangle scenes") {
    Rng rng(5);
    const std::vector<std::vector<Aabb>> scenes{
        strand_boxes(rng, 3000, 12, 0.01f, 0.001f),  // hair-like: 33 k segments
        bundle_boxes(rng, 40000),                    // over the parallel chunk size
        grid_triangles(90),                          // 16 k triangles
        rtc::test::random_boxes(rng, 5000, 0.05f),
    };
    for (std::size_t s = 0; s < scenes.size(); ++s) {
        for (int width : {2, 4, 8}) {
            BuildOptions o;
            o.width = width;
            o.max_leaf_size = width == 8 ? 4 : 1;
            CAPTURE(s);
            CAPTURE(width);
            check_same(scenes[s], o);
        }
    }
}

TEST_CASE("bvh build: identical to the reference builder on degenerate input and the median split") {
    std::vector<Aabb> same(300, Aabb{Vec3{0.0f}, Vec3{1.0f}});  // one centroid: median splits only
    Rng rng(9);
    std::vector<Aabb> mixed = rtc::test::random_boxes(rng, 2000, 0.0f);  // points
    for (int i = 0; i < 500; ++i) mixed.push_back(mixed[static_cast<std::size_t>(i) * 3]);
    BuildOptions o;
    check_same(same, o);
    check_same(mixed, o);
    o.strategy = SplitStrategy::Median;
    check_same(mixed, o);
    o.strategy = SplitStrategy::Sah;
    o.bins = 7;
    o.max_leaf_size = 3;
    check_same(mixed, o);
    check_same({}, o);
    check_same({Aabb{Vec3{0.0f}, Vec3{1.0f}}}, o);
}

}  // namespace RTCSIM_TEST_FILE
