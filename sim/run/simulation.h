// One simulated run: load the scene, convert it into primitives, build each
// method, trace the workload through it, price the counts under every cost
// preset and the structures under the memory preset.
#pragma once

#include "scenes/stats.h"
#include "sim/config/config_json.h"
#include "sim/config/run_config.h"
#include "sim/execution/frame.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/memory_model.h"
#include "sim/run/area_stats.h"
#include "sim/run/hit_agreement.h"
#include "sim/run/sampled_run.h"
#include "sim/config/work_estimate.h"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rtc {

struct MethodRun {
    std::string method;
    bool runnable = true;
    std::string reason;                // why not runnable
    std::uint64_t instances = 0;
    double build_seconds = 0.0;
    StructureCounts structures;
    std::size_t simulator_bytes = 0;   // the simulator's own structures (not the model)
    FrameResult frame;
    std::vector<PricedRun> priced;     // one per cost preset, in config order
    std::vector<WarpTotals> warp;      // per cost preset: the warp model's figures (warp presets only)
    std::vector<Roofline> roof;        // per cost preset: the SM its waves are priced on (sm_model.h)
    // Per cost preset: total cycles under each cost model drawn from its
    // uncertainty block (empty: the preset has none, or draws are off).
    std::vector<std::vector<double>> draw_cycles;
    MemoryBreakdown memory;
    // Approximate methods (MethodInfo::approximate): their hits against the
    // baseline's on a sample of the baseline's rays (hit_agreement.h); unset
    // for exact methods, without the baseline in the run, and in sharded runs.
    std::optional<HitAgreement> agreement;
    // Sampled runs (RunResult::sample): the estimates over the whole frame.
    // `priced`, `warp` and `draw_cycles` are already scaled to it; `frame`
    // holds what was traced (the sampled tiles only).
    std::optional<SampledMethod> sampled;

    // The event totals and rays over the whole frame: traced, or estimated.
    [[nodiscard]] const EventTotals& totals() const { return sampled ? sampled->totals : frame.totals; }
    [[nodiscard]] std::uint64_t rays() const { return sampled ? sampled->rays : frame.rays_traced; }
};

// The SM roofline of `method`'s pipeline under `cost` in run `r` (disabled
// for presets without an SM block).
[[nodiscard]] Roofline method_roofline(const CostModel& cost, const RunConfig& r, const std::vector<std::string>& needs);

// One method's frame priced under one cost preset. This is the one
// per-preset step of pricing: a run's own (every preset of its config) and a
// later re-pricing under another preset (Python's MethodRun.price) both take
// it, so the second gives what report.json would have.
struct PresetPrice {
    PricedRun run;    // totals priced per ray; total_cycles the warp model's under a warp preset
    WarpTotals warp;  // the waves' figures (all zero under a per-ray preset)
    Roofline roof;    // the SM the waves are priced on
};

// `totals`: the traced event totals. `warp`: the frame's waves priced under
// `cost` (a warp preset), or nullptr (a per-ray preset). `needs`: the
// method's hardware features. `sample_k`: a sampled run traced 1 / k of its
// tiles, and every figure is scaled to the whole frame (1: traced in full).
[[nodiscard]] PresetPrice price_preset(const EventTotals& totals, const CostModel& cost, const WarpTotals* warp,
                                       const RunConfig& config, const std::vector<std::string>& needs,
                                       std::uint32_t sample_k);

struct RunResult {
    RunConfig config;
    PointJson point;                   // set by the app for the reports; never read here
    std::string sweep_label;
    SceneStats scene;
    std::vector<std::string> scene_notes;  // what the scene's files held and it drops (Scene::notes)
    AreaStats areas;
    std::uint64_t primitives = 0;
    std::vector<CostModel> costs;
    std::optional<ExecutionModel> warp_grouping;  // the warp presets' grouping, if any
    MemoryModel memory;
    Camera camera;                     // resolved camera (camera workloads)
    std::vector<MethodRun> methods;
    std::size_t mesh_vertices = 0, mesh_triangles = 0;  // for memory pricing without the scene
    std::optional<TileSample> sample;  // the traced tiles of a sampled run (config.sampling)
    bool repriced = false;             // priced from another point's trace (reprice_run)
    double load_seconds = 0.0, convert_seconds = 0.0, total_seconds = 0.0;

    [[nodiscard]] const MethodRun* find(std::string_view method) const;
    [[nodiscard]] MethodRun* find(std::string_view method) {
        return const_cast<MethodRun*>(std::as_const(*this).find(method));
    }
    // The baseline's run (config.baseline), or nullptr when it was not run.
    [[nodiscard]] const MethodRun* baseline() const { return find(config.baseline); }
    [[nodiscard]] MethodRun* baseline() { return find(config.baseline); }
    // cycles(baseline) / cycles(method) under preset `preset`; 0 when not available.
    [[nodiscard]] double speedup(std::string_view method, std::size_t preset = 0) const;
    // The 90 % interval [low, high] of speedup(method, preset) over the
    // preset's cost draws (cost_uncertainty.h); nullopt without draws or speedup.
    [[nodiscard]] std::optional<std::array<double, 2>> speedup_interval(std::string_view method,
                                                                        std::size_t preset = 0) const;
    // Sampled runs: speedup(method, preset) with its 95 % sampling interval
    // (the ratio estimator over the same tiles); nullopt when not sampled.
    [[nodiscard]] std::optional<SampledEstimate> sampled_speedup(std::string_view method,
                                                                 std::size_t preset = 0) const;
    // Why preset `preset` gives no intervals ("" when it does).
    [[nodiscard]] std::string no_interval_reason(std::size_t preset) const;
    // Total memory of `method` over the baseline's, in percent; NaN when not available.
    [[nodiscard]] double memory_overhead_percent(std::string_view method) const;
};

struct RunContext {
    unsigned threads = 0;
    bool quiet = false;
    bool record_warps = false;  // keep every wave (calibration re-prices them)
    bool keep_rays = false;     // keep the recorded rays and hits in the result (the Python module's arrays)
    std::string out_dir;  // rays/hits files are streamed here when requested
    WorkLimits limits;    // checked again once the scene is loaded
    // Sharded runs (sim/shard, docs/scale-out.md): trace only band `band` of
    // `bands` of each frame (0 bands: the whole frame), or, when merging,
    // take each method's frame from `frame_source` instead of tracing it.
    std::uint32_t band = 0, bands = 0;
    std::function<FrameResult(const std::string& method)> frame_source;
};

// `config` is all a run reads: its scene description, resolved paths and
// loaded presets (parse_run_config); no JSON, no file it does not name.
[[nodiscard]] RunResult run_simulation(const RunConfig& config, const RunContext& context);

// `config` priced from `traced`, a run of a config with the same trace
// (same_trace), without tracing again: the counts are re-priced under
// config's cost presets and the structures under its memory preset. nullopt
// when that is not possible (a warp preset the trace did not record waves
// for, or a method the other memory preset's instance limit now lets run).
[[nodiscard]] std::optional<RunResult> reprice_run(const RunResult& traced, const RunConfig& config);

}  // namespace rtc
