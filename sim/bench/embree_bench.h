// `bench --embree` (issue 39): the simulator's trace rate beside Embree 3's
// on the same rays through the same method, so that anyone can check the
// speed claim on their own machine. For each of a run's methods that Embree
// can mirror (ref and obb on capsule scenes without a mesh;
// sim/bench/embree_scene.h says how), one recorded trace gives the rays and
// rtcsim's hits, Embree traces those rays and the hits are compared, then the
// two are timed alternately (rtcsim, Embree, rtcsim, ...) so that both see the
// same machine load, and the ratio is taken pair by pair.
//
// rtcsim's rate is bench's (run_frame with counting sinks: camera rays, miss
// shading and event records included); Embree's is rtcIntersect1 over the
// recorded rays with the same threads (core/parallel.h).
#pragma once

#include "sim/bench/bench_run.h"

namespace rtc {

// Whether this bench was built with Embree (CMake found it).
[[nodiscard]] bool embree_built();

// Compares `run` as above and prints it; returns false when rtcsim and Embree
// disagree on the hits (see check_hits in the .cpp for the tolerance).
// Without Embree it prints nothing and returns true.
[[nodiscard]] bool compare_with_embree(const BenchRun& run, const BenchOptions& options);

}  // namespace rtc
