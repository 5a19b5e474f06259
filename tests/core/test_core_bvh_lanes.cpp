// The lane blocks the traversal reads (core/bvh.h, BvhLaneBlock) hold exactly
// the tree of the entries: walked side by side, every node's children have
// the same box bits, counts and leaf ranges, inner children lead to the same
// subtrees, padding lanes repeat the last child with first = count = 0, and
// every block is reached once. make_lanes() again, on another thread count,
// gives the same bytes.
#include "core/bvh.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <cstring>
#include <utility>
#include <vector>

using namespace rtc;
using rtc::test::Rng;

namespace {

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
                CHECK(b.first[l] == 0);
                CHECK(b.count[l] == 0);
                continue;
            }
            REQUIRE(b.count[l] == e.count);
            if (e.is_inner())
                todo.push_back({e.first, b.first[l], e.count});
            else
                CHECK(b.first[l] == e.first);
        }
    }
    return reached;
}

void check_tree(const Bvh& bvh) {
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

TEST_CASE("bvh lanes: the blocks hold the entries' tree for every width and leaf size") {
    for (int width : {2, 4, 8}) {
        for (int leaf : {1, 3}) {
            Rng rng(11 + width * 10 + leaf);
            const auto boxes = rtc::test::random_boxes(rng, 2500);
            BuildOptions o;
            o.width = width;
            o.max_leaf_size = leaf;
            CAPTURE(width);
            CAPTURE(leaf);
            check_tree(build_bvh(boxes, o));
        }
    }
}

TEST_CASE("bvh lanes: empty, single-leaf and hand-made trees") {
    const Bvh empty = build_bvh(std::vector<Aabb>{});
    CHECK(empty.lanes.empty());
    check_tree(empty);

    const Bvh single = build_bvh(std::vector<Aabb>{{Vec3(0), Vec3(1)}});
    REQUIRE(single.lanes.size() == 1);
    check_tree(single);

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
    CHECK(hand.lanes[0].first[1] == 1);
    CHECK(check_lanes_match(hand) == std::vector<int>{1, 1, 1});
}
