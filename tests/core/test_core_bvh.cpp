// BVH builder invariants and bad input.
#include "core/bvh.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

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

    const std::vector<Aabb> one{{Vec3(0), Vec3(1)}};
    const Bvh single = build_bvh(one);
    REQUIRE(single.root.size() == 1);  // a lone leaf still hangs below the root node
    CHECK(!single.entries[0].is_inner());
    check_invariants(single, one);

    // 1000 copies of the same box: no SAH plane separates them, yet leaves
    // must still hold one primitive each and the tree stay shallow.
    const std::vector<Aabb> same(1000, Aabb{Vec3(0), Vec3(0)});
    const Bvh deg = build_bvh(same);
    check_invariants(deg, same);
    CHECK(deg.leaf_count() == 1000);
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
