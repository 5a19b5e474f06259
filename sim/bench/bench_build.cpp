// build/bench_build: times the BVH builder alone (core/build/) on a few
// scenes and prints, per scene, a hash of the tree (root, entries, prim ids),
// its node count and SAH cost, so that a faster builder can be checked to
// give the same trees. Usage:
//   build/bench_build [--scale S] [--repeat R] [--threads T[,T2...]] [--cases a,b] [--fresh-memory 1]
//                     [--control 1] [--cluster-size K]
// The case `fur` times the cluster method's orientation grouping instead
// (sim/methods/common/cluster_groups.cpp, clusters of K, default 256) on the
// straight fur of configs/runs/cluster_fur20m.json at S x 1 M segments (the
// 20 M fur is --scale 20) and prints a hash of the groups: the same hash is
// the same clusters, members in the same order.
// S multiplies every scene's primitive count (default 1: about 1 M each);
// wall time is the best of R builds, M prims/s per thread from it; the
// CPU-time rate (all threads' CPU time over R builds) drifts less with load.
// --threads takes a list (1,2): the counts' builds alternate within each of
// the R rounds (1, 2, 1, 2, ...), so that every count meets the same
// machine, and each count after the first prints its scaling against the
// first, as the ratio of the best times and as the median and range of the
// rounds' ratios (each round's builds run back to back: on a VM whose speed
// drifts between minutes, those compare). Every count must give the same
// tree (same hash), else bench_build exits 1. --control 1 adds, per count T
// after a first count of 1, T independent 1-thread builds at once in every
// round: T times one build's work in their time, against one build's in its
// own, is what T threads give this job on this machine with nothing shared,
// the ceiling for the builder's scaling.
// Freed memory stays in the heap as in simulate (sim/util/process_memory.h),
// so builds after the first reuse its pages; --fresh-memory 1 leaves glibc's
// default, where every build takes fresh pages (on a VM with slow page faults
// that is most of the difference, see docs/benchmark.md).
// For callgrind: valgrind --tool=callgrind --toggle-collect='*build_bvh*'
//   build/bench_build --scale 0.2 --repeat 1 --threads 1
#include "core/bvh.h"
#include "intersectors/capsule.h"
#include "intersectors/triangle.h"
#include "scenes/convert.h"
#include "scenes/generators/bundle.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/generators/random.h"
#include "scenes/generators/sphere_mesh.h"
#include "sim/methods/common/cluster_groups.h"
#include "sim/util/process_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <chrono>
#include <ctime>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace rtc;

std::uint64_t fnv(std::uint64_t h, const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

std::uint64_t tree_hash(const Bvh& b) {
    std::uint64_t h = 1469598103934665603ull;
    h = fnv(h, &b.root, sizeof b.root);
    h = fnv(h, b.entries.data(), b.entries.size() * sizeof(BvhEntry));
    return fnv(h, b.prim_ids.data(), b.prim_ids.size() * sizeof(std::uint32_t));
}

std::vector<Aabb> capsule_boxes(const Strands& s) {
    const auto prims = std::get<std::vector<Capsule>>(to_primitives(s, PrimitiveKind::Capsule));
    std::vector<Aabb> boxes;
    boxes.reserve(prims.size());
    for (const Capsule& c : prims) boxes.push_back(bounds(c));
    return boxes;
}

// The fur of configs/runs/cluster_fur20m.json (20 M segments at scale 20):
// straight strands of 4 segments on a unit sphere.
std::vector<Capsule> fur_capsules(double scale) {
    HairDesc d;
    d.style = HairStyle::Straight;
    d.strands = static_cast<std::uint32_t>(std::max(1.0, 250000.0 * scale));
    d.points_per_strand = 5;
    d.length = 0.15f;
    d.radius = 0.0008f;
    d.tip_radius = 0.0002f;
    d.seed = 3;
    return std::get<std::vector<Capsule>>(to_primitives(make_hair(d).strands, PrimitiveKind::Capsule));
}

std::uint64_t groups_hash(const Clusters& c) {
    const std::uint64_t h = fnv(1469598103934665603ull, c.first.data(), c.first.size() * sizeof(std::uint32_t));
    return fnv(h, c.members.data(), c.members.size() * sizeof(std::uint32_t));
}

// The orientation grouping alone: best wall time of `repeat`, CPU time of all.
void time_grouping(double scale, int repeat, int threads, int size) {
    const std::vector<Capsule> caps = fur_capsules(scale);
    double best = 1e30, cpu = 0.0;
    Clusters c;
    for (int r = 0; r < repeat; ++r) {
        const std::clock_t c0 = std::clock();
        const auto t0 = std::chrono::steady_clock::now();
        c = group_orientation(std::span<const Capsule>(caps), size, static_cast<unsigned>(threads));
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    }
    std::printf("%-10s %9zu %9zu %12s %016llx %9.4f %12.3f %12.3f  %d thread%s (orientation groups of %d; "
                "clusters in the nodes column; CPU s per grouping %.3f)\n",
                "fur", caps.size(), c.count(), "-", static_cast<unsigned long long>(groups_hash(c)), best,
                static_cast<double>(caps.size()) / best / 1e6 / threads,
                static_cast<double>(caps.size()) * repeat / cpu / 1e6, threads, threads == 1 ? "" : "s", size,
                cpu / repeat);
    std::fflush(stdout);
}

std::vector<Aabb> make_case(const std::string& name, double scale) {
    const auto n = static_cast<std::uint32_t>(std::max(1.0, 1e6 * scale));
    if (name == "bundle") {
        BundleDesc d;
        d.count = n;
        d.radius = 0.0005f;
        d.tilt_deg = 45.0f;
        return capsule_boxes(make_bundle(d).strands);
    }
    if (name == "hair") {
        HairDesc d;
        d.style = HairStyle::Curly;
        d.points_per_strand = 17;
        d.strands = std::max(1u, n / 16);
        return capsule_boxes(make_hair(d).strands);
    }
    if (name == "random") {  // n short capsules at random in a unit cube
        Strands s;
        SceneRng rng{7};
        const auto u = [&] { return static_cast<float>(rng.uniform()); };
        for (std::uint32_t i = 0; i < n; ++i) {
            const Vec3 p{u(), u(), u()};
            const Vec3 q = p + 0.02f * Vec3{u() - 0.5f, u() - 0.5f, u() - 0.5f};
            s.points.push_back(p);
            s.points.push_back(q);
            s.radii.insert(s.radii.end(), {0.001f, 0.001f});
            s.offsets.push_back(static_cast<std::uint32_t>(s.points.size()));
        }
        return capsule_boxes(s);
    }
    if (name == "triangles") {
        const int rings = std::max(3, static_cast<int>(std::sqrt(n / 2.0)));
        const TriangleMesh m = make_sphere_mesh(Vec3{0.0f}, 1.0f, rings, rings);
        std::vector<Aabb> boxes;
        for (const auto& t : m.triangles)
            boxes.push_back(bounds(Triangle{m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]}));
        return boxes;
    }
    std::fprintf(stderr, "bench_build: unknown case '%s' (bundle, hair, random, triangles, fur)\n", name.c_str());
    std::exit(2);
}

// "1,2,4": thread counts, each in [1, 1024].
bool parse_threads(const std::string& text, std::vector<int>& out) {
    out.clear();
    std::size_t pos = 0;
    while (pos <= text.size()) {
        const std::size_t comma = std::min(text.find(',', pos), text.size());
        const std::string item = text.substr(pos, comma - pos);
        char* end = nullptr;
        const long v = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || v < 1 || v > 1024) return false;
        out.push_back(static_cast<int>(v));
        pos = comma + 1;
    }
    return !out.empty();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// `repeat` rounds, each building the tree once per thread count in turn.
// Prints a line per count and, for each count after the first, its scaling.
// Returns false (after saying so) when the counts' trees differ.
bool time_builds(const std::string& name, const std::vector<Aabb>& boxes, int repeat,
                 const std::vector<int>& thread_counts, bool control) {
    const std::size_t k = thread_counts.size();
    std::vector<double> best(k, 1e30), cpu(k, 0.0);
    std::vector<std::vector<double>> seconds(k);
    // The control, per count T > 1 after the first: T independent 1-thread
    // builds at once, one per thread, timed together.
    std::vector<std::vector<double>> together(k);
    std::vector<std::uint64_t> hash(k);
    std::vector<std::size_t> nodes(k);
    std::vector<double> sah(k);
    Bvh bvh;
    for (int r = 0; r < repeat; ++r) {
        for (std::size_t t = 0; t < k; ++t) {
            BuildOptions o;
            o.threads = thread_counts[t];
            const std::clock_t c0 = std::clock();
            const auto t0 = std::chrono::steady_clock::now();
            bvh = build_bvh(boxes, o);
            const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            cpu[t] += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
            seconds[t].push_back(s);
            best[t] = std::min(best[t], s);
            if (r == 0) hash[t] = tree_hash(bvh), nodes[t] = bvh.node_count(), sah[t] = sah_cost(bvh);
        }
        for (std::size_t t = 1; control && t < k; ++t) {
            BuildOptions one;
            one.threads = 1;
            std::vector<std::thread> builders;
            const auto t0 = std::chrono::steady_clock::now();
            for (int b = 0; b < thread_counts[t]; ++b) builders.emplace_back([&] { (void)build_bvh(boxes, one); });
            for (std::thread& b : builders) b.join();
            together[t].push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
    }
    const auto prims = static_cast<double>(boxes.size());
    bool same = true;
    for (std::size_t t = 0; t < k; ++t) {
        std::printf("%-10s %9zu %9zu %12.6f %016llx %9.4f %12.3f %12.3f  %d thread%s\n", name.c_str(), boxes.size(),
                    nodes[t], sah[t], static_cast<unsigned long long>(hash[t]), best[t],
                    prims / best[t] / 1e6 / thread_counts[t], prims * repeat / cpu[t] / 1e6, thread_counts[t],
                    thread_counts[t] == 1 ? "" : "s");
        same = same && hash[t] == hash[0];
    }
    for (std::size_t t = 1; t < k; ++t) {
        std::vector<double> ratio;
        for (int r = 0; r < repeat; ++r) ratio.push_back(seconds[0][r] / seconds[t][r]);
        std::printf("%-10s scaling %d -> %d threads: %.2fx (best times), rounds %.2fx median [%.2f-%.2f] of %d\n",
                    name.c_str(), thread_counts[0], thread_counts[t], best[0] / best[t], median(ratio),
                    *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()),
                    repeat);
        if (!control || thread_counts[0] != 1) continue;
        // T builds' work in the time `together` took, against one build's
        // in its 1-thread time: what T threads give this job with nothing
        // shared but the machine.
        std::vector<double> ceiling;
        for (int r = 0; r < repeat; ++r) ceiling.push_back(thread_counts[t] * seconds[0][r] / together[t][r]);
        const double best_together = *std::min_element(together[t].begin(), together[t].end());
        std::printf("%-10s control: %d 1-thread builds at once: %.2fx (best times), rounds %.2fx median [%.2f-%.2f]\n",
                    name.c_str(), thread_counts[t], thread_counts[t] * best[0] / best_together, median(ceiling),
                    *std::min_element(ceiling.begin(), ceiling.end()),
                    *std::max_element(ceiling.begin(), ceiling.end()));
    }
    std::fflush(stdout);
    if (!same) std::fprintf(stderr, "bench_build: %s: the thread counts built different trees (hashes above)\n", name.c_str());
    return same;
}

constexpr const char* kUsage =
    "bench_build: times the BVH builder alone (core/build/) and prints each tree's hash\n"
    "  --cases a,b          bundle, hair, random, triangles (capsule boxes but triangles), and fur:\n"
    "                       the cluster method's orientation grouping of the fur of\n"
    "                       configs/runs/cluster_fur20m.json (default: the four builder cases)\n"
    "  --scale S            primitives x S million (default 1; the 20 M fur is fur at --scale 20)\n"
    "  --repeat R           builds per case; wall time is the best, CPU time over all (default 5)\n"
    "  --threads T[,T2...]  threads per build (default 1); with a list the counts' builds\n"
    "                       alternate in every round and each count after the first prints\n"
    "                       its scaling against the first (best times, and the rounds' ratios)\n"
    "  --cluster-size K     fur: primitives per cluster (default 256)\n"
    "  --fresh-memory 1     glibc's default heap: fresh pages for every build\n"
    "  --control 1          with --threads 1,T: each round also times T independent 1-thread\n"
    "                       builds at once, and prints what T threads give this job with\n"
    "                       nothing shared but the machine (the ceiling for the scaling)\n";

}  // namespace

int main(int argc, char** argv) {
    double scale = 1.0;
    int repeat = 5, cluster_size = 256;
    std::vector<int> thread_counts{1};
    bool fresh_memory = false, control = false;
    std::string cases = "bundle,hair,random,triangles";
    for (int i = 1; i < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::printf("%s", kUsage);
            return 0;
        }
        if (i + 1 == argc) { std::fprintf(stderr, "bench_build: %s needs a value\n", a.c_str()); return 2; }
        if (a == "--scale") scale = std::atof(argv[i + 1]);
        else if (a == "--repeat") repeat = std::max(1, std::atoi(argv[i + 1]));
        else if (a == "--threads") {
            if (!parse_threads(argv[i + 1], thread_counts)) {
                std::fprintf(stderr, "bench_build: --threads takes thread counts from 1 to 1024, e.g. 1,2; got '%s'\n",
                             argv[i + 1]);
                return 2;
            }
        }
        else if (a == "--cases") cases = argv[i + 1];
        else if (a == "--cluster-size") cluster_size = std::max(1, std::atoi(argv[i + 1]));
        else if (a == "--fresh-memory") fresh_memory = std::atoi(argv[i + 1]) != 0;
        else if (a == "--control") control = std::atoi(argv[i + 1]) != 0;
        else { std::fprintf(stderr, "bench_build: unknown option %s\n", a.c_str()); return 2; }
    }
    const bool kept = !fresh_memory && keep_freed_memory();
#if defined(__GLIBC__)
    // The control's builds run on threads of their own, which glibc would
    // give arenas of their own, where a block above 64 MB is always fresh
    // pages: with one arena they reuse the heap's pages as the timed builds
    // do, and the control times the work rather than the page faults.
    if (control && kept) mallopt(M_ARENA_MAX, 1);
#endif
    if (!set_huge_pages_from_environment("bench_build")) return 2;
    std::printf("memory: %s\n", kept ? "freed memory kept in the heap (as simulate does)"
                                      : "glibc's default (fresh pages for every large array)");
    std::printf("%-10s %9s %9s %12s %18s %9s %12s %12s  %s\n", "case", "prims", "nodes", "SAH", "tree hash",
                "best s", "Mprims/s/thr", "Mprims/cpu-s", "threads");
    std::size_t pos = 0;
    while (pos <= cases.size()) {
        const std::size_t comma = std::min(cases.find(',', pos), cases.size());
        const std::string name = cases.substr(pos, comma - pos);
        pos = comma + 1;
        if (name == "fur") {
            for (const int threads : thread_counts) time_grouping(scale, repeat, threads, cluster_size);
            continue;
        }
        const std::vector<Aabb> boxes = make_case(name, scale);
        if (!time_builds(name, boxes, repeat, thread_counts, control)) return 1;
    }
    std::printf("huge pages (RTCSIM_HUGE_PAGES): %s\n", huge_pages_summary().c_str());
}
