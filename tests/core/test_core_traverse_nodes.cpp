// The traversal kernel's node styles and box tests (core/traverse.h): the
// scalar box test (the fallback of a target without SSE2) against the SIMD
// one, child by child and through the kernel; the oriented styles with no
// rotation against the axis-aligned one (same leaves, same order, same
// counts); and oriented trees of both styles against brute force.
#include "core/obb_build.h"
#include "core/obb_nodes.h"
#include "core/sinks.h"
#include "core/traverse.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <bit>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;
using rtc::test::Tri;

namespace {

// What a traversal did: the leaves in the order it reached them, its counts
// and its closest hit (t, primitive).
struct Walk {
    std::vector<std::uint32_t> leaves;
    RayCounts counts;
    float t = kInfinity;
    std::uint32_t prim = UINT32_MAX;
};

// A leaf function over triangles: closest hit with the tie rule (t, index).
template <TraversalMode Mode>
auto triangle_leaf(const Bvh& bvh, const std::vector<Tri>& tris, const Ray& ray, Walk& w) {
    return [&bvh, &tris, &ray, &w](std::uint32_t first, std::uint32_t count, float tmax) {
        w.leaves.push_back(first);
        float nearest = kInfinity;
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t prim = bvh.prim_ids[first + k];
            Ray r = ray;
            r.tmax = tmax;
            const auto t = rtc::test::hit_triangle(tris[prim], r);
            if (!t) continue;
            if (*t < w.t || (*t == w.t && prim < w.prim)) w.t = *t, w.prim = prim;
            nearest = std::min(nearest, *t);
            if (Mode == TraversalMode::Closest) tmax = std::min(tmax, *t);
        }
        return nearest;
    };
}

template <TraversalMode Mode, class Nodes>
Walk walk_nodes(Nodes nodes, const Bvh& bvh, const std::vector<Tri>& tris, const Ray& ray) {
    Walk w;
    CountingSink sink;
    traverse_nodes<Mode, kBlasEvents>(nodes, ray.tmin, ray.tmax, sink, triangle_leaf<Mode>(bvh, tris, ray, w));
    w.counts = sink.ray;
    return w;
}

template <TraversalMode Mode>
Walk walk_obb(const ObbBvh& tree, const std::vector<Tri>& tris, const Ray& ray) {
    Walk w;
    CountingSink sink;
    traverse_obb<Mode>(tree.bvh, tree.frames, ray, ray.tmax, sink, triangle_leaf<Mode>(tree.bvh, tris, ray, w));
    w.counts = sink.ray;
    return w;
}

bool same(const Walk& a, const Walk& b) {
    return a.leaves == b.leaves && a.counts.n == b.counts.n && a.prim == b.prim &&
           std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
}

std::vector<Aabb> boxes_of(const std::vector<Tri>& tris) {
    std::vector<Aabb> boxes;
    for (const Tri& t : tris) boxes.push_back(t.box());
    return boxes;
}

// Rays of test::random_ray, some with tmax cut short, and rays along the
// axes (zero direction components: safe_inverse's +-1e30).
std::vector<Ray> test_rays(Rng& rng, int n) {
    std::vector<Ray> rays;
    for (int i = 0; i < n; ++i) {
        Ray r = rtc::test::random_ray(rng);
        if (i % 3 == 1) r.tmax = rng.uniform(0.5f, 2.0f);
        if (i % 7 == 2) r.direction.x = 0.0f;
        if (i % 11 == 3) r.direction.y = -0.0f, r.direction.z = 0.0f;
        rays.push_back(r);
    }
    return rays;
}

}  // namespace

TEST_CASE("box test: the scalar child test and the SIMD one agree bit for bit") {
    Rng rng(4301);
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    int compared = 0, hit = 0;
    for (int round = 0; round < 3000; ++round) {
        // Two blocks (up to 8 children); every tenth box flat, empty or with
        // an infinite or NaN corner.
        BvhLaneBlock blocks[2];
        for (std::uint32_t i = 0; i < 8; ++i) {
            Aabb box = rtc::test::random_boxes(rng, 1, 0.5f)[0];
            switch (rng.gen() % 30) {
                case 0: box.hi.z = box.lo.z; break;
                case 1: std::swap(box.lo.x, box.hi.x); break;
                case 2: box.hi.y = inf; break;
                case 3: box.lo.x = nan; break;
                default: break;
            }
            blocks[i / 4].set(i % 4, BvhEntry{box, i, 1}, true);
        }
        Ray ray = rtc::test::random_ray(rng);
        if (round % 5 == 1) ray.direction.x = round % 2 ? 0.0f : -0.0f;
        if (round % 13 == 2) ray.origin.y = blocks[0].lo_y[0];  // on a slab
        const Vec3 inv = safe_inverse(ray.direction);
        const float tmax = round % 4 == 0 ? inf : rng.uniform(0.0f, 4.0f);
        const float tmin = round % 9 == 0 ? rng.uniform(0.0f, 2.0f) : 0.0f;
        for (std::uint32_t n = 0; n <= 8; ++n) {
            float want[8], got[8];
            const unsigned want_mask = ScalarBoxTest::children(blocks, n, ScalarBoxTest::Ray(ray.origin, inv, tmin),
                                                               ScalarBoxTest::tmax(tmax), want);
            const unsigned got_mask = BlockBoxTest::children(blocks, n, BlockBoxTest::Ray(ray.origin, inv, tmin),
                                                             BlockBoxTest::tmax(tmax), got);
            ++compared;
            CHECK(got_mask == want_mask);
            for (std::uint32_t i = 0; i < n; ++i) {
                if (!(want_mask >> i & 1u)) continue;
                ++hit;
                if (std::bit_cast<std::uint32_t>(got[i]) != std::bit_cast<std::uint32_t>(want[i])) {
                    CAPTURE(round);
                    CAPTURE(i);
                    CHECK(std::bit_cast<std::uint32_t>(got[i]) == std::bit_cast<std::uint32_t>(want[i]));
                }
            }
        }
    }
    CHECK(compared == 3000 * 9);
    CHECK(hit > 1000);  // not all misses
}

TEST_CASE("traverse: the kernel with the scalar box test walks as with the SIMD one") {
    for (const int width : {2, 4, 8}) {
        CAPTURE(width);
        Rng rng(4400 + width);
        const auto tris = rtc::test::random_triangles(rng, 1200);
        BuildOptions o;
        o.width = width;
        const Bvh bvh = build_bvh(boxes_of(tris), o);
        for (const Ray& ray : test_rays(rng, 300)) {
            const Vec3 inv = safe_inverse(ray.direction);
            const auto both = [&](auto mode) {
                constexpr TraversalMode kMode = decltype(mode)::value;
                const Walk simd =
                    walk_nodes<kMode>(AabbNodes<>(bvh, ray.origin, inv, ray.tmin), bvh, tris, ray);
                const Walk scalar = walk_nodes<kMode>(
                    AabbNodes<ScalarBoxTest>(bvh, ray.origin, inv, ray.tmin), bvh, tris, ray);
                CHECK(same(simd, scalar));
            };
            both(std::integral_constant<TraversalMode, TraversalMode::Closest>{});
            both(std::integral_constant<TraversalMode, TraversalMode::AnyHit>{});
            both(std::integral_constant<TraversalMode, TraversalMode::AllCandidates>{});
        }
    }
}

TEST_CASE("traverse: oriented nodes without rotations walk as axis-aligned ones") {
    for (const int width : {2, 4, 8}) {
        CAPTURE(width);
        Rng rng(4500 + width);
        const auto tris = rtc::test::random_triangles(rng, 1200);
        BuildOptions o;
        o.width = width;
        o.max_leaf_size = 2;
        ObbBvh tree{build_bvh(boxes_of(tris), o), {}};
        for (const ObbStyle style : {ObbStyle::PerChild, ObbStyle::PerNode}) {
            tree.frames.style = style;
            tree.frames.frame_of.assign(tree.bvh.entries.size(), kWorldFrame);
            for (const Ray& ray : test_rays(rng, 200)) {
                const Vec3 inv = safe_inverse(ray.direction);
                Walk aabb;
                CountingSink sink;
                traverse<TraversalMode::Closest, kBlasEvents>(
                    tree.bvh, ray.origin, inv, ray.tmin, ray.tmax, sink,
                    triangle_leaf<TraversalMode::Closest>(tree.bvh, tris, ray, aabb));
                aabb.counts = sink.ray;
                // The leaves' prim_ids ranges are the same in both (`first`
                // indexes prim_ids), only inner nodes are read differently.
                CHECK(same(walk_obb<TraversalMode::Closest>(tree, tris, ray), aabb));
            }
        }
    }
}

TEST_CASE("traverse: oriented trees of both styles give brute force's closest hit") {
    Rng rng(4601);
    // Thin triangles (slivers along random directions), which oriented boxes fit.
    std::vector<Tri> tris;
    std::vector<BoundProxy> proxies;
    for (int i = 0; i < 800; ++i) {
        const Vec3 c = rng.point(-1.0f, 1.0f), d = 0.3f * rng.direction(), e = 0.01f * rng.direction();
        tris.push_back({c - d, c + d, c + e});
        proxies.push_back({{tris.back().a, tris.back().c, tris.back().c, tris.back().b}, 0.0f});
    }
    const std::vector<Aabb> boxes = boxes_of(tris);
    for (const int width : {2, 4, 8}) {
        CAPTURE(width);
        BuildOptions b;
        b.width = width;
        ObbBuildOptions per_child;
        per_child.width = width;
        per_child.intersection = 2.0;
        const ObbBvh trees[] = {build_obb_bvh(boxes, proxies, per_child),
                                quantize_obb_bvh(build_bvh(boxes, b), proxies, QuantizeOptions{})};
        for (const ObbBvh& tree : trees) {
            const bool per_node = tree.frames.style == ObbStyle::PerNode;
            CAPTURE(per_node);
            REQUIRE(tree.frames.rotated_entries() > 0);
            EventTotals totals;
            for (const Ray& ray : test_rays(rng, 300)) {
                std::uint32_t want = UINT32_MAX;
                float want_t = kInfinity;
                for (std::uint32_t p = 0; p < tris.size(); ++p) {
                    const auto t = rtc::test::hit_triangle(tris[p], ray);
                    if (t && (*t < want_t || (*t == want_t && p < want))) want_t = *t, want = p;
                }
                const Walk closest = walk_obb<TraversalMode::Closest>(tree, tris, ray);
                CHECK(closest.prim == want);
                const Walk any = walk_obb<TraversalMode::AnyHit>(tree, tris, ray);
                CHECK((any.prim == UINT32_MAX) == (want == UINT32_MAX));
                CHECK(walk_obb<TraversalMode::AllCandidates>(tree, tris, ray).prim == want);
                totals.add(closest.counts);
            }
            // Each style's rotated children counted its own way.
            CHECK((totals[Event::ObbBoxTest] > 0) == !per_node);
            CHECK((totals[Event::NodeRotate] > 0) == per_node);
        }
    }
}

}  // namespace RTCSIM_TEST_FILE
