// BVH builder invariants, the lane blocks the traversal reads, and bad input.
#include "core/bvh.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

namespace {

// Walks the tree checking that every child box lies inside its parent's box
// and that every primitive appears in exactly one leaf, inside the leaf's box.
void check_invariants(const Bvh& bvh, const std::vector<Aabb>& boxes) {
    std::vector<int> seen(boxes.size(), 0);
    std::vector<BvhEntry> stack{bvh.root};
    std::size_t max_children = 0;
    while (!stack.empty()) {
        const BvhEntry node = stack.back();
        stack.pop_back();
        REQUIRE(node.is_inner());
        max_children = std::max<std::size_t>(max_children, node.size());
        for (std::uint32_t i = 0; i < node.size(); ++i) {
            const BvhEntry& child = bvh.entries.at(node.first + i);
            REQUIRE(node.box.contains(child.box));
            if (child.is_inner()) {
                stack.push_back(child);
                continue;
            }
            REQUIRE(child.size() >= 1);
            for (std::uint32_t k = 0; k < child.size(); ++k) {
                const std::uint32_t prim = bvh.prim_ids.at(child.first + k);
                REQUIRE(prim < boxes.size());
                ++seen[prim];
                REQUIRE(child.box.contains(boxes[prim]));
            }
        }
    }
    CHECK(max_children <= static_cast<std::size_t>(bvh.width));
    CHECK(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool lane_box_is(const BvhLaneBlock& b, std::uint32_t l, const Aabb& box) {
    return same_bits(b.lo_x[l], box.lo.x) && same_bits(b.lo_y[l], box.lo.y) &&
           same_bits(b.lo_z[l], box.lo.z) && same_bits(b.hi_x[l], box.hi.x) &&
           same_bits(b.hi_y[l], box.hi.y) && same_bits(b.hi_z[l], box.hi.z);
}

// Walks entries and lanes together from the root; returns how often each block was reached.
std::vector<int> check_lanes_match(const Bvh& bvh) {
    std::vector<int> reached(bvh.lanes.size(), 0);
    // (first entry, first block, count) of each node still to check
    struct Node { std::uint32_t entry, block, count; };
    std::vector<Node> todo{{bvh.root.first, 0, bvh.root.count}};
    while (!todo.empty()) {
        const Node node = todo.back();
        todo.pop_back();
        const std::uint32_t n = node.count & ~BvhEntry::kInnerBit;
        const std::uint32_t blocks = (n + 3) / 4;
        REQUIRE(node.block + blocks <= bvh.lanes.size());
        for (std::uint32_t k = 0; k < blocks; ++k) ++reached[node.block + k];
        for (std::uint32_t slot = 0; slot < blocks * 4; ++slot) {
            const BvhLaneBlock& b = bvh.lanes[node.block + slot / 4];
            const std::uint32_t l = slot % 4;
            const BvhEntry& e = bvh.entries.at(node.entry + std::min(slot, n - 1));
            CAPTURE(slot);
            CHECK(lane_box_is(b, l, e.box));
            if (slot >= n) {  // padding
                CHECK(b.child[l].first == 0);
                CHECK(b.child[l].count == 0);
                continue;
            }
            REQUIRE(b.child[l].count == e.count);
            if (e.is_inner())
                todo.push_back({e.first, b.child[l].first, e.count});
            else
                CHECK(b.child[l].first == e.first);
        }
    }
    return reached;
}

// The lane blocks the traversal reads (core/bvh.h, BvhLaneBlock) hold exactly
// the tree of the entries: walked side by side, every node's children have
// the same box bits, counts and leaf ranges, inner children lead to the same
// subtrees, padding lanes repeat the last child with first = count = 0, every
// block is reached once, and make_lanes() on 2 threads gives the same bytes.
void check_lanes(const Bvh& bvh) {
    const std::vector<int> reached = check_lanes_match(bvh);
    for (std::size_t i = 0; i < reached.size(); ++i) {
        CAPTURE(i);
        CHECK(reached[i] == 1);
    }
    Bvh copy = bvh;
    copy.lanes.clear();
    make_lanes(copy, 2);
    REQUIRE(copy.lanes.size() == bvh.lanes.size());
    if (!bvh.lanes.empty())
        CHECK(std::memcmp(copy.lanes.data(), bvh.lanes.data(), bvh.lanes.size() * sizeof(BvhLaneBlock)) == 0);
}

}  // namespace

TEST_CASE("bvh: invariants hold for every width and leaf size") {
    for (int width : {2, 4, 8}) {
        for (int leaf : {1, 4}) {
            Rng rng(7 + width * 10 + leaf);
            const auto boxes = rtc::test::random_boxes(rng, 3000);
            BuildOptions o;
            o.width = width;
            o.max_leaf_size = leaf;
            const Bvh bvh = build_bvh(boxes, o);
            CAPTURE(width);
            CAPTURE(leaf);
            CHECK(bvh.primitive_count() == boxes.size());
            check_invariants(bvh, boxes);
            check_lanes(bvh);
        }
    }
}

TEST_CASE("bvh: SAH is no worse than the object median on random inputs") {
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        Rng rng(seed);
        // Clustered, mixed-size boxes: where a median split is clearly suboptimal.
        auto boxes = rtc::test::random_boxes(rng, 2000, 0.02f);
        for (int i = 0; i < 500; ++i) {
            const Vec3 c = rng.point(0.8f, 1.0f);
            boxes.push_back({c, c + rng.point(0.0f, 0.3f)});
        }
        BuildOptions sah;
        sah.width = 2;
        BuildOptions median = sah;
        median.strategy = SplitStrategy::Median;
        const double c_sah = sah_cost(build_bvh(boxes, sah));
        const double c_median = sah_cost(build_bvh(boxes, median));
        CAPTURE(seed);
        CHECK(c_sah <= c_median);
    }
}

TEST_CASE("bvh: the build is deterministic") {
    Rng rng(3);
    const auto boxes = rtc::test::random_boxes(rng, 5000);
    const Bvh a = build_bvh(boxes), b = build_bvh(boxes);
    REQUIRE(a.entries.size() == b.entries.size());
    CHECK(a.prim_ids == b.prim_ids);
    for (std::size_t i = 0; i < a.entries.size(); ++i) {
        CHECK(a.entries[i].first == b.entries[i].first);
        CHECK(a.entries[i].count == b.entries[i].count);
    }
}

TEST_CASE("bvh: empty, single and identical-centroid inputs") {
    const Bvh empty = build_bvh(std::vector<Aabb>{});
    CHECK(empty.root.is_inner());
    CHECK(empty.root.size() == 0);
    CHECK(empty.node_count() == 1);
    CHECK(empty.lanes.empty());
    check_lanes(empty);

    const std::vector<Aabb> one{{Vec3(0), Vec3(1)}};
    const Bvh single = build_bvh(one);
    REQUIRE(single.root.size() == 1);  // a lone leaf still hangs below the root node
    CHECK(!single.entries[0].is_inner());
    check_invariants(single, one);
    REQUIRE(single.lanes.size() == 1);
    check_lanes(single);

    // 1000 copies of the same box: no SAH plane separates them, yet leaves
    // must still hold one primitive each and the tree stay shallow.
    const std::vector<Aabb> same(1000, Aabb{Vec3(0), Vec3(0)});
    const Bvh deg = build_bvh(same);
    check_invariants(deg, same);
    check_lanes(deg);
    CHECK(deg.leaf_count() == 1000);
}

TEST_CASE("bvh: lane blocks of a tree made by hand") {
    // By hand: a root of two children, the second an inner node of five
    // leaves (two blocks), its entries laid out before the root's.
    Bvh hand;
    hand.width = 8;
    hand.prim_ids = {0, 1, 2, 3, 4, 5};
    for (std::uint32_t i = 0; i < 5; ++i)
        hand.entries.push_back({{Vec3(float(i)), Vec3(float(i) + 1)}, i + 1, 1});
    hand.entries.push_back({{Vec3(-1), Vec3(0)}, 0, 1});
    hand.entries.push_back({{Vec3(0), Vec3(6)}, 0, 5 | BvhEntry::kInnerBit});
    hand.root = {{Vec3(-1), Vec3(6)}, 5, 2 | BvhEntry::kInnerBit};
    make_lanes(hand);
    REQUIRE(hand.lanes.size() == 3);  // the root's block first, then two
    CHECK(hand.lanes[0].child[1].first == 1);
    CHECK(check_lanes_match(hand) == std::vector<int>{1, 1, 1});
}

TEST_CASE("bvh: non-finite or inverted boxes are rejected with the primitive index") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Aabb> boxes{{Vec3(0), Vec3(1)}, {Vec3(0, nan, 0), Vec3(1)}};
    CHECK_THROWS_WITH_AS(static_cast<void>(build_bvh(boxes)), doctest::Contains("primitive 1"),
                         std::invalid_argument);
    boxes[1] = {Vec3(0), Vec3(kInfinity)};
    CHECK_THROWS_AS(static_cast<void>(build_bvh(boxes)), std::invalid_argument);
    boxes[1] = {Vec3(1), Vec3(0)};
    CHECK_THROWS_WITH_AS(static_cast<void>(build_bvh(boxes)), doctest::Contains("inverted"), std::invalid_argument);
    BuildOptions bad;
    bad.width = 3;
    CHECK_THROWS_AS(static_cast<void>(build_bvh(std::vector<Aabb>{}, bad)), std::invalid_argument);
}

}  // namespace RTCSIM_TEST_FILE
