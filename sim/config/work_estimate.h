// What a run will cost before it starts: rays traced, primitives built and
// the simulator's peak memory, checked against ceilings (`--max-rays`,
// `--max-memory`, `--force` to go past) so that a typo such as spp =
// 2147483647 or a 2^32-cylinder bundle fails in a second with the key that
// caused it, instead of running for days or dying in the allocator.
//
// Two checks: from the config alone (camera and ray-file workloads,
// procedural scenes, sweep size) before anything is loaded, and from the
// loaded scene (file scenes, follow hairs) before any primitive is built.
// Estimates are upper bounds (every path runs all its bounces); the memory
// figures come from measured runs (see work_estimate.cpp).
#pragma once

#include "scenes/scene.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rtc {

struct RunConfig;

struct WorkLimits {
    double max_rays = 1e10;         // rays traced over every method and sweep point (--max-rays)
    double max_memory = 0.0;        // bytes (--max-memory); 0: 3/4 of physical memory, else 16 GiB
    double max_sweep_points = 1e4;  // sweep points (a sweep larger than this is a typo)
    // Break-even map cells priced after tracing (--max-break-even): cells x
    // cost models (the preset and its draws) x methods, over every map and
    // point. About 5 million a second on one core: 2e8 is about 40 s.
    double max_break_even = 2e8;
    bool force = false;             // --force: report and go on
};

// The memory ceiling in bytes that `limits` means on this machine.
[[nodiscard]] double memory_ceiling(const WorkLimits& limits);

struct WorkEstimate {
    double rays = 0.0;          // over every method
    double primitives = 0.0;    // after conversion (phantom subdivision included)
    double memory_bytes = 0.0;  // simulator peak (one method's structures + every method's pixels)
    std::string rays_key;       // JSON path that sets the ray count, e.g. "/workload/spp"
    std::string rays_detail;    // "800 x 800 pixels x 4 spp x 4 rays per path x 2 methods"
    std::string memory_key;     // JSON path behind the largest memory term
    std::string memory_detail;
    double break_even = 0.0;    // cell prices of the break-even maps (WorkLimits::max_break_even)
    std::string break_even_key;  // the largest map's /break_even/<i>/cells
    std::string break_even_detail;
};

// From the config alone; primitives of file scenes count 0 here.
[[nodiscard]] WorkEstimate estimate_config_work(const RunConfig& config);
// With the scene loaded (everything but the rays is exact).
[[nodiscard]] WorkEstimate estimate_scene_work(const RunConfig& config, const Scene& scene);

// Throws InputError "<file>: <key>: ... exceed --max-... (...; --force to run
// anyway)" unless the limits allow it; with `force`, returns quietly.
void check_work(const WorkEstimate& estimate, const WorkLimits& limits, const std::string& file);
// Several sweep points: rays add up, memory is the largest point's.
[[nodiscard]] WorkEstimate combine_work(const std::vector<WorkEstimate>& points);

// "123456", or "1.23e+07" from a million on.
[[nodiscard]] std::string count_text(double x);
// "1.5 GiB", "512 MiB", "12 KiB", "100 B": an estimate's size in at most two
// figures (sim/util/table.h's format_bytes prints measured sizes with two
// decimals; one name for both was ambiguous for an int argument).
[[nodiscard]] std::string format_estimate_bytes(double bytes);
// Parses a size for --max-memory: bytes, or a number with K, M, G, T
// (powers of 1024, optionally followed by "iB" or "B"); nullopt if invalid.
[[nodiscard]] std::optional<double> parse_byte_size(const std::string& text);

}  // namespace rtc
