// parallel_for, and the builder's independence from the thread count.
#include "core/bvh.h"
#include "core/parallel.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

TEST_CASE("parallel_for: every index exactly once, for any thread count") {
    CHECK(hardware_threads() >= 1);
    for (unsigned threads : {0u, 1u, 2u, 3u, 8u}) {
        for (std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{5}, std::size_t{1000}}) {
            std::vector<std::atomic<int>> hits(count);
            std::atomic<unsigned> max_thread{0};
            parallel_for(count, threads, [&](std::size_t i, unsigned thread) {
                ++hits[i];
                unsigned seen = max_thread.load();
                while (thread > seen && !max_thread.compare_exchange_weak(seen, thread)) {}
            });
            CAPTURE(threads);
            CAPTURE(count);
            for (std::size_t i = 0; i < count; ++i) CHECK(hits[i] == 1);
            // thread ids index per-thread scratch: never past the thread count.
            CHECK(max_thread.load() < (threads == 0 ? hardware_threads() : threads));
        }
    }
}

TEST_CASE("parallel_for: threads = 1 runs inline, more threads than items is fine") {
    const auto caller = std::this_thread::get_id();
    bool all_inline = true;
    parallel_for(100, 1, [&](std::size_t, unsigned thread) {
        all_inline = all_inline && std::this_thread::get_id() == caller && thread == 0;
    });
    CHECK(all_inline);
    std::vector<int> out(3, 0);
    parallel_for(3, 16, [&](std::size_t i, unsigned) { out[i] = static_cast<int>(i) + 1; });
    CHECK(out == std::vector<int>{1, 2, 3});
}

TEST_CASE("parallel_for: an exception in a worker reaches the caller and stops the rest") {
    for (unsigned threads : {1u, 2u, 4u}) {
        std::atomic<int> done{0};
        CHECK_THROWS_WITH_AS(parallel_for(100000, threads,
                                          [&](std::size_t i, unsigned) {
                                              if (i == 10) throw std::runtime_error("item 10");
                                              // Slow items: without them another thread can finish
                                              // all 10^5 while item 10 unwinds (seen under ASan on a
                                              // loaded machine); 20 us each makes that take >= 1 s.
                                              if (i > 10) std::this_thread::sleep_for(std::chrono::microseconds(20));
                                              ++done;
                                          }, 1),
                             "item 10", std::runtime_error);
        CAPTURE(threads);
        CHECK(done.load() < 100000 - 1);  // stopped early
    }
}

TEST_CASE("parallel_for: calls inside a call, and callers on two threads at once, each run every index once") {
    // The pool serves one call at a time; a call from inside another's work
    // (which would wait for the pool it is part of) or from a second thread
    // while the pool is busy runs on fresh threads instead.
    constexpr std::size_t kOuter = 16, kInner = 200;
    std::vector<std::atomic<int>> hits(kOuter * kInner);
    std::atomic<unsigned> max_inner_thread{0};
    parallel_for(kOuter, 3, [&](std::size_t i, unsigned) {
        parallel_for(kInner, 2, [&](std::size_t j, unsigned thread) {
            if (thread > max_inner_thread.load()) max_inner_thread.store(thread);
            ++hits[i * kInner + j];
        }, 1);
    }, 1);
    for (std::size_t k = 0; k < hits.size(); ++k) REQUIRE(hits[k] == 1);
    CHECK(max_inner_thread.load() < 2u);

    constexpr std::size_t kCount = 20000;
    std::vector<std::atomic<int>> a(kCount), b(kCount);
    const auto many_calls = [](std::vector<std::atomic<int>>& out, unsigned threads) {
        for (std::size_t round = 0; round < 50; ++round)
            parallel_for(kCount / 50, threads,
                         [&](std::size_t i, unsigned) { ++out[round * (kCount / 50) + i]; }, 7);
    };
    std::thread other([&] { many_calls(b, 4); });
    many_calls(a, 2);
    other.join();
    for (std::size_t k = 0; k < kCount; ++k) {
        REQUIRE(a[k] == 1);
        REQUIRE(b[k] == 1);
    }
    // Fewer threads after more, then more again: the pool's workers are
    // reused and the thread ids stay below the count asked for.
    for (unsigned threads : {8u, 2u, 5u}) {
        std::atomic<unsigned> max_thread{0};
        parallel_for(1000, threads, [&](std::size_t, unsigned thread) {
            unsigned seen = max_thread.load();
            while (thread > seen && !max_thread.compare_exchange_weak(seen, thread)) {}
        }, 1);
        CHECK(max_thread.load() < threads);
    }
}

namespace {

bool identical(const Bvh& a, const Bvh& b) {
    return a.prim_ids == b.prim_ids && a.entries.size() == b.entries.size() &&
           std::memcmp(&a.root, &b.root, sizeof(BvhEntry)) == 0 &&
           std::memcmp(a.entries.data(), b.entries.data(), a.entries.size() * sizeof(BvhEntry)) == 0 &&
           a.memory_bytes() == b.memory_bytes();
}

// Builds with 1 thread (twice), 2 and 4 threads and checks all trees are equal.
void check_thread_independent(const std::vector<Aabb>& boxes, BuildOptions o) {
    o.threads = 1;
    const Bvh reference = build_bvh(boxes, o);
    CHECK(reference.primitive_count() == boxes.size());
    for (int threads : {1, 2, 4}) {
        o.threads = threads;
        CAPTURE(threads);
        CHECK(identical(build_bvh(boxes, o), reference));
    }
}

}  // namespace

// Big enough (a root over 2 x 16384 references, nodes over 4096) that the parallel
// top splits and the subtree tasks both run.
TEST_CASE("bvh build: the same tree for 1, 2 and 4 threads, random input") {
    Rng rng(11);
    const auto boxes = rtc::test::random_boxes(rng, 60000, 0.01f);
    for (int width : {2, 8}) {
        for (int leaf : {1, 4}) {
            BuildOptions o;
            o.width = width;
            o.max_leaf_size = leaf;
            CAPTURE(width);
            CAPTURE(leaf);
            check_thread_independent(boxes, o);
        }
    }
    BuildOptions median;
    median.strategy = SplitStrategy::Median;
    check_thread_independent(boxes, median);
}

TEST_CASE("bvh build: the same tree for 1, 2 and 4 threads, degenerate input") {
    // All boxes identical: every split is an object median.
    check_thread_independent(std::vector<Aabb>(40000, Aabb{Vec3(1), Vec3(2)}), {});
    // Many duplicates of a few boxes, including signed zeros.
    Rng rng(5);
    const std::vector<Aabb> few{{Vec3(-0.0f), Vec3(0.0f)}, {Vec3(0.0f), Vec3(1.0f)},
                                {Vec3(-1.0f), Vec3(-0.0f)}, {Vec3(0.5f), Vec3(0.5f)}};
    std::vector<Aabb> dups;
    for (int i = 0; i < 40000; ++i) dups.push_back(few[rng.gen() % few.size()]);
    check_thread_independent(dups, {});
    BuildOptions big_leaves;
    big_leaves.max_leaf_size = 8;
    check_thread_independent(dups, big_leaves);
}

TEST_CASE("bvh build: the first invalid primitive is named whatever the thread count") {
    Rng rng(2);
    auto boxes = rtc::test::random_boxes(rng, 50000);
    boxes[40000] = {Vec3(1), Vec3(0)};
    boxes[45000].lo.x = std::numeric_limits<float>::quiet_NaN();
    for (int threads : {1, 2, 4}) {
        BuildOptions o;
        o.threads = threads;
        CHECK_THROWS_WITH_AS(static_cast<void>(build_bvh(boxes, o)), doctest::Contains("primitive 40000 has an inverted"),
                             std::invalid_argument);
    }
}

// Nodes of up to 32 references bin only into their occupied bins; clusters of
// a few boxes whose centroids differ by less than a float's smallest normal
// (where a bin scale overflows to infinity) or not at all exercise that path,
// its ties and its fall-back to the object median, below parallel top splits.
TEST_CASE("bvh build: the same tree for 1, 2 and 4 threads, clusters of tiny nodes") {
    Rng rng(17);
    std::vector<Aabb> boxes;
    const float tiny = std::numeric_limits<float>::denorm_min();
    while (boxes.size() < 40000) {
        const Vec3 c = rng.point(0.0f, 1.0f);
        const int size = 1 + static_cast<int>(rng.gen() % 40);
        const int kind = static_cast<int>(rng.gen() % 3);
        for (int i = 0; i < size; ++i) {
            Vec3 p = c;
            if (kind == 0) p.x = static_cast<float>(rng.gen() % 4) * tiny;  // denormal spreads
            if (kind == 1) p += rng.point(0.0f, 1e-3f);                     // ordinary small cluster
            boxes.push_back({p - Vec3(static_cast<float>(i % 3) * 1e-4f), p + Vec3(1e-4f)});
        }
    }
    for (int leaf : {1, 2}) {
        BuildOptions o;
        o.max_leaf_size = leaf;
        CAPTURE(leaf);
        check_thread_independent(boxes, o);
    }
}

}  // namespace RTCSIM_TEST_FILE
