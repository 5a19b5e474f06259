// A `simulate` config, typed: one sweep point's plan. Every field has its
// default here; parsing (run_config.cpp) rejects unknown keys and bad values
// with the JSON path, resolves every path (absolute), loads and checks the
// presets, so a run needs nothing but this. Key reference: configs/README.md.
#pragma once

#include "sim/config/scene_config.h"
#include "sim/config/workload_config.h"
#include "sim/execution/tile_sample.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/memory_model.h"
#include "sim/methods/method.h"

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
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
    // The swept value multiplies each event's preset cost instead (a factor:
    // the operation classes of a program keep their ratios).
    bool scale = false;
};
struct BreakEvenSpec {
    std::string name;    // file name: break_even_<name>.png
    std::string preset;  // a cost preset's name, one of the run's
    BreakEvenAxis x, y;
    int cells = 48;      // per axis
    std::vector<std::string> methods;  // the methods compared (empty: all the run's)
};

struct RunConfig {
    std::string file;                 // where the config came from (for messages)
    std::string name;                 // default: the config file's stem
    std::string description;
    SceneDesc scene;                  // the `scene` block, checked (load_scene makes the Scene)
    PrimitiveKind kind = PrimitiveKind::Capsule;
    int subdivision = 1;              // phantom pre-subdivision: 1, 2, 4 or 8
    std::vector<std::string> methods{"ref", "obb"};  // registered names (sim/methods/registry.cpp)
    std::string baseline = "ref";     // speedups, ratio maps and memory overheads are against it
    MethodOptions build;              // widths, bins, leaf sizes, OBB variant
    TraceOptions trace;               // IS schedule, phantom early-out
    // Preset names or paths as given; parse_run_config resolves them into files
    // (sim/util/paths.h: names are searched in the preset directories) and
    // loads them into `costs` and `memory`.
    std::vector<std::string> cost_presets{"turing-calibrated"};  // first = primary; the best evidence by default
    std::string memory_preset = "memory-optix7";
    std::vector<std::shared_ptr<const CostModel>> costs;  // per cost preset, loaded and checked
    std::shared_ptr<const MemoryModel> memory;
    WorkloadDesc workload;
    OutputOptions output;
    UncertaintyOptions uncertainty;
    std::vector<BreakEvenSpec> break_even;  // optional `break_even` list
    // Sampled simulation (docs/sampling.md): trace 1 / round(1 / fraction)
    // of the warp tiles, stratified, and scale; 1: every tile.
    SamplingOptions sampling;
};

// Presets loaded once per file, shared by the points of a plan.
struct PresetCache {
    std::map<std::string, std::shared_ptr<const CostModel>> costs;
    std::map<std::string, std::shared_ptr<const MemoryModel>> memory;
};

// Parses one (sweep-expanded) config and loads its presets (from `presets`
// when already loaded there). Throws InputError "<file>: <path>: ...".
[[nodiscard]] RunConfig parse_run_config(const nlohmann::json& config, const std::string& file,
                                         PresetCache* presets = nullptr);

// One map of a config's `break_even` list (`map`, at JSON path `path` of
// `file`): every key checked, its methods among the run's `methods`. Python's
// rtcsim.plot.break_even asks for its maps through it, so a map means the
// same there as in a config. (Names unique in the list: the caller's check.)
[[nodiscard]] BreakEvenSpec parse_break_even_spec(const nlohmann::json& map, const std::string& file,
                                                  const std::string& path, const std::vector<std::string>& methods);
// A map's preset is one of `costs` (by name) and prices every event its axes
// set; else an InputError naming `file`.
void check_break_even_preset(const BreakEvenSpec& spec, const std::vector<const CostModel*>& costs,
                             const std::string& file);

}  // namespace rtc
