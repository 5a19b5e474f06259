// Running one benchmark run: load the scene, build each method, trace the
// workload with run_frame (the counting sinks simulate uses) on one thread and
// on all threads, and collect the figures of issue 8; or time its per-ray and
// warp execution against each other (compare_warp_price).
#pragma once

#include "core/sinks.h"
#include "sim/bench/bench_cases.h"
#include "sim/config/run_config.h"
#include "sim/execution/frame.h"
#include "sim/methods/common/geometry.h"
#include "sim/methods/method.h"

#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

struct BenchOptions {
    // Thread counts timed, in order (0 stands for all cores); scaling is
    // reported against the first. Default: 1 and all cores.
    std::vector<unsigned> threads{1, 0};
    int repeat = 3;        // timings: best of this many traces (the machine is shared)
    // Trace in warps priced under this preset (the SIMT model); empty: per ray.
    std::string warp_preset;
};

// One thread count's timings: best and median of `repeat` traces.
struct ThreadRate {
    unsigned threads = 0;
    double best_rays_per_second = 0.0;
    double median_rays_per_second = 0.0;
    double best_seconds = 0.0;
};

struct MethodFigures {
    std::string method;
    double build_seconds = 0.0;
    std::uint64_t rays = 0;
    std::vector<ThreadRate> rates;    // per BenchOptions::threads entry
    double rays_per_second_1t = 0.0;  // best of `repeat` at 1 thread (0: not timed)
    double rays_per_second_nt = 0.0;  // best of `repeat` at the largest thread count
    unsigned threads = 0;             // that largest thread count
    double is_calls_per_ray = 0.0;
    double box_tests_per_ray = 0.0;   // TLAS + BLAS
    double bytes_per_primitive = 0.0; // TwoLevel (TLAS, instances, BLASes) / primitives
    EventTotals totals;
    bool counts_match = true;         // totals identical over every trace and thread count
};

struct RunFigures {
    std::string label;
    std::string kind;
    std::uint64_t primitives = 0;
    std::uint64_t triangles = 0;
    double load_seconds = 0.0;
    std::vector<MethodFigures> methods;
};

[[nodiscard]] RunFigures run_bench(const BenchRun& run, const BenchOptions& options);

// A run's typed plan, its geometry and its rays, made as simulate makes them.
struct LoadedRun {
    RunConfig config;
    Geometry geometry;
    RayWorkload frame;
    double load_seconds = 0.0;
};
[[nodiscard]] LoadedRun load_run(const BenchRun& run);

// One timed trace of `frame` with counting sinks, as run_bench times it
// (warp: the preset of --execution warp, or null).
[[nodiscard]] FrameResult bench_trace_frame(const BuiltMethod& method, const Geometry& g,
                                            const RayWorkload& frame, const TraceOptions& trace,
                                            unsigned threads, const CostModel* warp);

// `bench --warp-price` (issue 39): what the SIMT model costs the simulator,
// as a ratio measured side by side in one process. For each of a run's
// methods, per-ray and warp traces of the same frame are timed alternately
// (per-ray, warp, per-ray, ...), so that both see the same machine load, and
// warp's time over per-ray's is taken pair by pair. Both must count the same
// events and rays (the warp model only groups and prices what per-ray
// tracing counts). Times `run` so under options.warp_preset and prints it;
// returns false when the two executions' counts differ.
[[nodiscard]] bool compare_warp_price(const BenchRun& run, const BenchOptions& options);

// Median, smallest and largest of a non-empty list (alternated timings).
struct Spread {
    double median, lo, hi;
};
[[nodiscard]] Spread spread(std::vector<double> v);

// Peak resident set of the process so far (getrusage ru_maxrss), bytes.
[[nodiscard]] std::uint64_t peak_rss_bytes();

}  // namespace rtc
