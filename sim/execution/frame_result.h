// What running a workload through a method takes and gives: the workload
// (camera paths or a ray list), the options (threads, records, the SIMT model,
// bands of a sharded run) and the result (event totals, per-pixel or per-ray
// counts and images, warp totals). The runners are in per_ray_frame.h and
// warp_frame.h; run_frame (frame.h) picks one.
#pragma once

#include "core/uninitialized.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/trace_hit.h"
#include "sim/hardware/uncertainty/draw_pricing.h"
#include "sim/hardware/warp_trace.h"
#include "sim/execution/tile_sample.h"
#include "sim/workload/camera.h"
#include "sim/workload/path_tracer.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace rtc {

// A workload resolved against a scene: a camera with its path options, or an
// explicit list of rays.
struct RayWorkload {
    bool from_camera = true;
    Camera camera;
    PathOptions path;
    std::vector<Ray> rays;  // when !from_camera
};

// One warp preset's totals over a task or a frame: its own and, when the
// run draws from its uncertainty block (run intervals), each draw's.
struct PresetWarpTotals {
    WarpTotals totals;
    std::vector<WarpTotals> draws;  // per draw, in the order of FrameOptions::warp_draws' set

    PresetWarpTotals& operator+=(const PresetWarpTotals& o) {
        totals += o.totals;
        for (std::size_t d = 0; d < draws.size() && d < o.draws.size(); ++d) draws[d] += o.draws[d];
        return *this;
    }
};

// A warp preset's results in a frame, found by the preset's name.
struct PresetWarp : PresetWarpTotals {
    std::string preset;               // CostModel::name (unique in a run: run_config.cpp)
    std::vector<float> pixel_cycles;  // camera frames: per pixel, its share of its waves' cycles
};

// One task's totals, kept in sharded runs (FrameOptions::bands) so that a
// merge adds the bands' tasks in the single run's order.
struct FrameTask {
    EventTotals totals;
    std::uint64_t rays_traced = 0;
    std::vector<PresetWarpTotals> warp;  // per warp preset, as FrameResult::warp
};

struct FrameResult {
    int width = 0, height = 0;            // 0 x 0 for ray lists
    EventTotals totals;
    // Filled by the frame's tasks, not zeroed first (see core/uninitialized.h).
    UninitializedVector<RayCounts> pixel_counts;  // per pixel, summed over samples and bounces
    UninitializedVector<RayCounts> ray_counts;    // ray lists: per ray, in the list's order
    UninitializedVector<Vec3> radiance;           // per pixel, mean over samples
    std::vector<Ray> rays;                // every traced ray, when recorded
    std::vector<TraceHit> hits;           // every traced ray's hit, when recorded
    std::uint64_t rays_traced = 0;
    double trace_seconds = 0.0;
    // SIMT execution (when FrameOptions::warp is set):
    std::vector<PresetWarp> warp;           // per FrameOptions::warp_presets entry, in its order
    std::vector<float> pixel_simt_active;   // per pixel: active lane-rounds of its waves (first warp preset)
    std::vector<float> pixel_simt_slots;    // per pixel: rounds x W of its waves (first warp preset)
    WarpTrace warp_trace;                   // every wave, when FrameOptions::record_warps
    // The frame's tasks (image rows, tile rows, blocks of rays) and those this
    // result traced, [task_begin, task_end); the pixels (camera) or rays (ray
    // lists) they cover, [item_begin, item_end). A banded run traces part of
    // the frame: its per-pixel arrays are zero elsewhere, and `tasks` holds
    // each task's totals.
    std::size_t task_count = 0, task_begin = 0, task_end = 0;
    std::size_t item_begin = 0, item_end = 0;
    std::vector<FrameTask> tasks;

    // The warp results of the preset named `preset`, or null (not a warp
    // preset of this frame).
    [[nodiscard]] const PresetWarp* warp_of(std::string_view preset) const {
        for (const PresetWarp& w : warp)
            if (w.preset == preset) return &w;
        return nullptr;
    }
};

struct FrameOptions {
    unsigned threads = 0;       // 0: all cores
    bool record_rays = false;
    bool record_hits = false;
    bool progress = true;
    std::string label = "trace";
    // SIMT execution: the warp grouping (null: per-ray model only), the
    // presets priced per wave as the frame runs, and whether to keep every
    // wave for re-pricing (calibration).
    const ExecutionModel* warp = nullptr;
    std::vector<const CostModel*> warp_presets;
    // Cost models drawn from the warp presets' uncertainty (run intervals):
    // priced per wave like the presets, but only their totals are kept, with
    // the preset each set's `base` is (FrameResult::warp[p].draws).
    std::vector<DrawSet> warp_draws;
    bool record_warps = false;
    // Sharded runs (sim/shard): trace only band `band` of `bands` contiguous
    // bands of the frame's tasks and keep each task's totals; 0 bands: the
    // whole frame, no task records.
    std::uint32_t band = 0, bands = 0;
    // Sampled runs (camera workloads, docs/sampling.md): trace only the
    // sample's tiles; the others' pixels are zero. Null: every tile.
    const TileSample* sample = nullptr;
};

// Band `band` of `bands` over `tasks` tasks: [first, second), contiguous; the
// bands together cover every task once (some are empty when tasks < bands).
[[nodiscard]] inline std::pair<std::size_t, std::size_t> band_range(std::size_t tasks, std::uint32_t band,
                                                                    std::uint32_t bands) {
    if (bands == 0) return {0, tasks};
    if (band >= bands) return {tasks, tasks};
    return {tasks * band / bands, tasks * (band + 1) / bands};  // tasks < 2^40, bands <= 10^5: no overflow
}

// For the runners (frame_result.cpp). Sizes a per-item array that the
// band's tasks fill, items [first, last): only the items outside the band
// are zeroed here.
void size_for_band(UninitializedVector<RayCounts>& v, std::size_t items, std::size_t first, std::size_t last);
void size_for_band(UninitializedVector<Vec3>& v, std::size_t items, std::size_t first, std::size_t last);

// Records the band's range of tasks and items.
void finish_band(FrameResult& out, std::size_t tasks, std::size_t first, std::size_t last,
                 std::size_t items_per_task, std::size_t items);

}  // namespace rtc
