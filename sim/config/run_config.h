// A `simulate` config, typed. Every field has its default here; parsing
// (run_config.cpp) rejects unknown keys and bad values with the JSON path.
// Key reference: configs/README.md.
#pragma once

#include "sim/methods/method.h"
#include "sim/config/workload_config.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace rtc {

struct OutputOptions {
    bool images = true;       // render, heat maps, ratio map (PNG)
    bool arrays = true;       // per-pixel (or per-ray) counts and cycles as .npy (docs/outputs.md)
    bool write_rays = false;  // rays.bin: every traced ray (32 B each)
    bool write_hits = false;  // hits_<method>.bin: each method's hit per ray (12 B each)
};

// Intervals on speedups (docs/calibration.md): every cost preset with an
// "uncertainty" block is also priced under `draws` cost models drawn from it.
struct UncertaintyOptions {
    int draws = 64;           // 0: no intervals
    std::uint64_t seed = 1;   // the same seed gives the same draws
};

// A break-even map (sim/report): sweep the cost of two event groups of one
// cost preset on log axes and show, per cell, which method is cheapest.
struct BreakEvenAxis {
    std::vector<Event> events;  // all set to the swept value
    double min = 1.0, max = 100.0;
};
struct BreakEvenSpec {
    std::string name;    // file name: break_even_<name>.png
    std::string preset;  // a cost preset's name, one of the run's
    BreakEvenAxis x, y;
    int cells = 48;      // per axis
};

struct RunConfig {
    std::string file;                 // where the config came from (for messages)
    std::string name;                 // default: the config file's stem
    std::string description;
    nlohmann::json scene;             // the `scene` block, read by load_scene
    PrimitiveKind kind = PrimitiveKind::Capsule;
    int subdivision = 1;              // phantom pre-subdivision: 1, 2, 4 or 8
    std::vector<std::string> methods{"ref", "obb"};  // registered names (sim/methods/registry.cpp)
    std::string baseline = "ref";     // speedups, ratio maps and memory overheads are against it
    MethodOptions build;              // widths, bins, leaf sizes, OBB variant
    TraceOptions trace;               // IS schedule, phantom early-out
    // Preset names or paths as given; parse_run_config resolves them into files
    // (sim/util/paths.h: names are searched in the preset directories).
    std::vector<std::string> cost_presets{"turing-calibrated"};  // first = primary; the best evidence by default
    std::string memory_preset = "memory-optix7";
    WorkloadDesc workload;
    OutputOptions output;
    UncertaintyOptions uncertainty;
    nlohmann::json calibrate;         // optional `calibrate` block (null when absent)
    std::vector<BreakEvenSpec> break_even;  // optional `break_even` list
};

// Parses one (sweep-expanded) config. Throws InputError "<file>: <path>: ...".
[[nodiscard]] RunConfig parse_run_config(const nlohmann::json& config, const std::string& file);

}  // namespace rtc
