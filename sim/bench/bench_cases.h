// The benchmark's standard cases (issue 8), each written as the same JSON a
// `simulate` config holds, so the benchmark builds and traces exactly what a
// simulation of that config would: same defaults, same builders, same
// counting sinks, same frame runner.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

// One scene + primitive kind + workload, traced by one or more methods.
struct BenchRun {
    std::string label;       // e.g. "capsules", "phantom"
    nlohmann::json config;   // a run config (scene, primitives, methods, workload)
};

struct BenchCase {
    int id = 0;
    std::string title;
    std::string note;            // what was chosen and why (radius, resolution, ...)
    std::vector<BenchRun> runs;
    std::string missing_data;    // non-empty: the case is skipped, this says why
};

// The standard cases 1..5. `data_dir` is where hair/sintel_* are looked for
// (case 4 is marked skipped when they are missing).
[[nodiscard]] std::vector<BenchCase> standard_cases(const std::string& data_dir);

// The opt-in scale case: 2^24 masquerade instances.
[[nodiscard]] BenchCase scale_case();

}  // namespace rtc
