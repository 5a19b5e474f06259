// `bench --embree-hair CONFIG` (issue 54 item 4): Embree 3's oriented hair
// BVH against its axis-aligned BVH over the same segments, built and traced
// on the same rays, beside what the simulator counts for `ref` and
// `obb-nodes` on those rays (sim/bench/embree_hair.h says how each Embree
// side is made and what Embree does not expose).
//
// For every scene of the config (its sweep's scenes, else its scene): the
// simulator's `ref` traces the config's workload once with its rays and hits
// recorded; `obb-nodes` traces it once for its counts; then the two Embree
// scenes are built alternately `repeat` times (build time: the median), their
// hits are compared with each other and with ref's, and they trace the
// recorded rays alternately (aligned, oriented, aligned, ...) `repeat` times
// per thread count: rates, and oriented over aligned pair by pair.
#pragma once

#include "sim/bench/bench_run.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

// One bench run per scene of the run config at `path` (its sweep's `scene`
// list, else its own scene), each labelled by the scene's name. Throws
// InputError when the file cannot be read or sweeps anything but scenes.
[[nodiscard]] std::vector<BenchRun> hair_runs_of_config(const std::string& path);

// Times and prints one run as above and appends its figures to `out` (an
// array). Returns false when the two Embree BVHs disagree on the hits beyond
// float tolerance. Throws std::runtime_error when bench was built without Embree.
[[nodiscard]] bool compare_hair_bvhs(const BenchRun& run, const BenchOptions& options, nlohmann::json& out);

}  // namespace rtc
