// The traversal kernel against brute force, for every mode and width.
#include "core/sinks.h"
#include "core/traverse.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <limits>
#include <set>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;
using rtc::test::Tri;

namespace {

struct Result {
    float t = kInfinity;
    std::uint32_t prim = UINT32_MAX;
};

// Closest hit over triangles with the order-independent tie rule (t, index).
template <TraversalMode Mode, class Sink>
Result trace_triangles(const Bvh& bvh, const std::vector<Tri>& tris, const Ray& ray, Sink& sink,
                       std::set<std::uint32_t>* visited = nullptr) {
    Result best;
    const auto leaf = [&](std::uint32_t first, std::uint32_t count, float tmax) {
        float nearest = kInfinity;
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t prim = bvh.prim_ids[first + k];
            if (visited) visited->insert(prim);
            Ray r = ray;
            r.tmax = tmax;
            const auto t = rtc::test::hit_triangle(tris[prim], r);
            if (!t) continue;
            if (*t < best.t || (*t == best.t && prim < best.prim)) best = {*t, prim};
            nearest = std::min(nearest, *t);
            if (Mode == TraversalMode::Closest) tmax = std::min(tmax, *t);
        }
        return nearest;
    };
    traverse<Mode, kBlasEvents>(bvh, ray.origin, safe_inverse(ray.direction), ray.tmin, ray.tmax,
                                sink, leaf);
    return best;
}

Result brute_force(const std::vector<Tri>& tris, const Ray& ray) {
    Result best;
    for (std::uint32_t i = 0; i < tris.size(); ++i) {
        const auto t = rtc::test::hit_triangle(tris[i], ray);
        if (t && (*t < best.t || (*t == best.t && i < best.prim))) best = {*t, i};
    }
    return best;
}

}  // namespace

TEST_CASE("traverse: closest, any-hit and all-candidates equal brute force") {
    for (int width : {2, 4, 8}) {
        for (int leaf_size : {1, 3}) {
            Rng rng(100 + width + leaf_size);
            const auto tris = rtc::test::random_triangles(rng, 1500);
            std::vector<Aabb> boxes;
            for (const Tri& t : tris) boxes.push_back(t.box());
            BuildOptions o;
            o.width = width;
            o.max_leaf_size = leaf_size;
            const Bvh bvh = build_bvh(boxes, o);
            CAPTURE(width);
            CAPTURE(leaf_size);
            int hits = 0;
            for (int i = 0; i < 400; ++i) {
                const Ray ray = rtc::test::random_ray(rng);
                NullSink sink;
                const Result ref = brute_force(tris, ray);
                const Result closest = trace_triangles<TraversalMode::Closest>(bvh, tris, ray, sink);
                CHECK(closest.prim == ref.prim);
                CHECK(closest.t == ref.t);
                hits += ref.prim != UINT32_MAX;

                const Result any = trace_triangles<TraversalMode::AnyHit>(bvh, tris, ray, sink);
                CHECK((any.prim != UINT32_MAX) == (ref.prim != UINT32_MAX));

                // All-candidates reaches exactly the leaves whose box the ray
                // pierces; with one primitive per leaf that is every
                // primitive box pierced.
                std::set<std::uint32_t> visited;
                const Result all =
                    trace_triangles<TraversalMode::AllCandidates>(bvh, tris, ray, sink, &visited);
                CHECK(all.prim == ref.prim);
                if (leaf_size == 1) {
                    std::set<std::uint32_t> pierced;
                    const Vec3 inv = safe_inverse(ray.direction);
                    for (std::uint32_t p = 0; p < boxes.size(); ++p)
                        if (intersect_box(boxes[p], ray.origin, inv, ray.tmin, ray.tmax) < kInfinity)
                            pierced.insert(p);
                    CHECK(visited == pierced);
                }
            }
            CHECK(hits > 50);  // the scene is not trivially empty
        }
    }
}

TEST_CASE("traverse: null and counting sinks give the same hits and counts repeat") {
    Rng rng(11);
    const auto tris = rtc::test::random_triangles(rng, 2000);
    std::vector<Aabb> boxes;
    for (const Tri& t : tris) boxes.push_back(t.box());
    const Bvh bvh = build_bvh(boxes);
    std::vector<Ray> rays;
    for (int i = 0; i < 300; ++i) rays.push_back(rtc::test::random_ray(rng));
    const auto run = [&](EventTotals& totals) {
        for (const Ray& ray : rays) {
            CountingSink counting;
            NullSink null;
            const Result a = trace_triangles<TraversalMode::Closest>(bvh, tris, ray, counting);
            const Result b = trace_triangles<TraversalMode::Closest>(bvh, tris, ray, null);
            CHECK(a.prim == b.prim);
            CHECK(a.t == b.t);
            CHECK(counting.ray[Event::BlasNodeVisit] >= 1);
            CHECK(counting.ray[Event::BlasBoxTest] >= counting.ray[Event::BlasNodeVisit] - 1);
            totals.add(counting.ray);
        }
    };
    EventTotals first, second;
    run(first);
    run(second);
    CHECK(first == second);
    CHECK(first[Event::BlasBoxTest] > first[Event::BlasNodeVisit]);
}

TEST_CASE("traverse: empty tree, degenerate rays and flat boxes") {
    const Bvh empty = build_bvh(std::vector<Aabb>{});
    CountingSink sink;
    int leaves = 0;
    const auto count_leaf = [&](std::uint32_t, std::uint32_t, float) {
        ++leaves;
        return kInfinity;
    };
    const Ray ray{Vec3(0, 0, -2), 0.0f, Vec3(0, 0, 1), kInfinity};
    CHECK(traverse<TraversalMode::Closest, kBlasEvents>(empty, ray.origin, safe_inverse(ray.direction),
                                                        0.0f, kInfinity, sink, count_leaf) == kInfinity);
    CHECK(leaves == 0);
    CHECK(sink.ray[Event::BlasNodeVisit] == 1);

    // A zero-thickness box (a flat triangle's box) is still hit head-on, and a
    // ray along a slab (zero direction component) does not produce NaN.
    const std::vector<Aabb> flat{{Vec3(-1, -1, 0), Vec3(1, 1, 0)}, {Vec3(2, 2, 2), Vec3(2, 2, 2)}};
    const Bvh bvh = build_bvh(flat);
    const auto t = traverse<TraversalMode::AllCandidates, kBlasEvents>(
        bvh, ray.origin, safe_inverse(ray.direction), 0.0f, kInfinity, sink,
        [](std::uint32_t, std::uint32_t, float) { return 1.0f; });
    CHECK(t == 1.0f);

    // NaN or zero directions terminate and report nothing.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const Vec3 d : {Vec3(nan, 0, 1), Vec3(0, 0, 0)}) {
        leaves = 0;
        const Ray bad{Vec3(5, 5, 5), 0.0f, d, kInfinity};
        traverse<TraversalMode::Closest, kBlasEvents>(bvh, bad.origin, safe_inverse(bad.direction),
                                                      0.0f, kInfinity, sink, count_leaf);
        CHECK(leaves == 0);
    }
}

}  // namespace RTCSIM_TEST_FILE
