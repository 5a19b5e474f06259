// Running a workload through a tracer (one method's compiled ray path): every
// ray of every pixel (or of a ray file) traced on all cores, with per-ray event counts flushed into
// per-pixel and per-tile totals. Tiles write only their own slots and are
// merged in tile order, so counts, images and hit files are identical
// whatever the number of threads.
#pragma once

#include "core/parallel.h"
#include "core/uninitialized.h"
#include "sim/workload/camera.h"
#include "sim/workload/path_tracer.h"
#include "sim/execution/interrupt.h"
#include "sim/util/progress.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/leaf_programs.h"
#include "sim/hardware/uncertainty/draw_pricing.h"
#include "sim/hardware/warp_trace.h"

#include <algorithm>
#include <chrono>
#include <span>
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

// One task's totals, kept in sharded runs (FrameOptions::bands) so that a
// merge adds the bands' tasks in the single run's order.
struct FrameTask {
    EventTotals totals;
    std::uint64_t rays_traced = 0;
    std::vector<WarpTotals> warp;  // per warp preset
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
    std::vector<WarpTotals> warp;           // per FrameOptions::warp_presets entry, then per draw of warp_draws
    std::vector<float> pixel_warp_cycles;   // first warp preset: per pixel, its share of its waves
    std::vector<std::vector<float>> more_pixel_warp_cycles;  // warp presets 1, 2, ...: the same
    std::vector<float> pixel_simt_active;   // per pixel: active lane-rounds of its waves
    std::vector<float> pixel_simt_slots;    // per pixel: rounds x W of its waves
    WarpTrace warp_trace;                   // every wave, when FrameOptions::record_warps
    // The frame's tasks (image rows, tile rows, blocks of rays) and those this
    // result traced, [task_begin, task_end); the pixels (camera) or rays (ray
    // lists) they cover, [item_begin, item_end). A banded run traces part of
    // the frame: its per-pixel arrays are zero elsewhere, and `tasks` holds
    // each task's totals.
    std::size_t task_count = 0, task_begin = 0, task_end = 0;
    std::size_t item_begin = 0, item_end = 0;
    std::vector<FrameTask> tasks;
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
    // priced per wave like the presets, but only their totals are kept.
    std::vector<DrawSet> warp_draws;
    bool record_warps = false;
    // Sharded runs (sim/shard): trace only band `band` of `bands` contiguous
    // bands of the frame's tasks and keep each task's totals; 0 bands: the
    // whole frame, no task records.
    std::uint32_t band = 0, bands = 0;
};

// Band `band` of `bands` over `tasks` tasks: [first, second), contiguous; the
// bands together cover every task once (some are empty when tasks < bands).
[[nodiscard]] inline std::pair<std::size_t, std::size_t> band_range(std::size_t tasks, std::uint32_t band,
                                                                    std::uint32_t bands) {
    if (bands == 0) return {0, tasks};
    if (band >= bands) return {tasks, tasks};
    return {tasks * band / bands, tasks * (band + 1) / bands};  // tasks < 2^40, bands <= 10^5: no overflow
}

// Sizes a per-item array that the band's tasks fill, items [first, last):
// only the items outside the band are zeroed here.
template <class T>
void size_for_band(UninitializedVector<T>& v, std::size_t items, std::size_t first, std::size_t last) {
    v.resize(items);
    std::fill(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(first, items)), T{});
    std::fill(v.begin() + static_cast<std::ptrdiff_t>(std::min(last, items)), v.end(), T{});
}

// Records the band's range of tasks and items.
inline void finish_band(FrameResult& out, std::size_t tasks, std::size_t first,
                        std::size_t last, std::size_t items_per_task, std::size_t items) {
    out.task_count = tasks;
    out.task_begin = first;
    out.task_end = last;
    out.item_begin = std::min(items, first * items_per_task);
    out.item_end = std::min(items, last * items_per_task);
}

// `tracer(CountingSink&, TraceScratch&)` makes, once per task, the function
// `(const Ray&) -> TraceHit` that traces one ray counting into that sink: a
// method's template instantiation, called directly (no virtual call per ray).
template <class Tracer>
FrameResult run_frame_per_ray(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    const auto start = std::chrono::steady_clock::now();
    const unsigned threads = fo.threads ? fo.threads : hardware_threads();
    FrameResult out;
    // One tile per image row (or per 4096 rays of a ray list).
    constexpr std::size_t kRaysPerTile = 4096;
    const std::size_t tiles = frame.from_camera
                                  ? static_cast<std::size_t>(frame.camera.height)
                                  : (frame.rays.size() + kRaysPerTile - 1) / kRaysPerTile;
    // Each tile is written by one task only, at its end (the task counts into
    // locals), on its own cache lines: no line is shared between threads'
    // tiles while they run.
    struct alignas(64) Tile {
        EventTotals totals;
        std::vector<Ray> rays;
        std::vector<TraceHit> hits;
        std::uint64_t rays_traced = 0;
    };
    const auto [first, last] = band_range(tiles, fo.band, fo.bands);
    struct alignas(64) Scratch {
        TraceScratch s;
    };
    std::vector<Tile> tile_out(last - first);
    std::vector<Scratch> scratch(threads);
    if (frame.from_camera) {
        out.width = frame.camera.width;
        out.height = frame.camera.height;
        const std::size_t pixels = static_cast<std::size_t>(out.width) * out.height;
        size_for_band(out.pixel_counts, pixels, first * out.width, last * out.width);
        size_for_band(out.radiance, pixels, first * out.width, last * out.width);
    } else {
        size_for_band(out.ray_counts, frame.rays.size(), first * kRaysPerTile, last * kRaysPerTile);
    }
    const CameraFrame cam = frame.from_camera ? camera_frame(frame.camera) : CameraFrame{};
    Progress progress(fo.label, last - first, fo.progress);

    parallel_for(last - first, threads, [&, first = first](std::size_t slot, unsigned thread) {
        throw_if_interrupted();  // Ctrl-C: parallel_for stops handing out rows and rethrows
        const std::size_t tile = first + slot;
        Tile& t = tile_out[slot];
        TraceScratch& sc = scratch[thread].s;
        EventTotals totals;
        std::uint64_t rays_traced = 0;
        // Every ray of a pixel (or of a ray-list tile) counts into one sink:
        // the per-pixel sums without a per-ray flush.
        CountingSink sink;
        auto trace_ray = tracer(sink, sc);
        const bool record_rays = fo.record_rays, record_hits = fo.record_hits;
        const auto trace = [&](const Ray& ray) {
            const TraceHit hit = trace_ray(ray);
            ++rays_traced;
            if (record_rays) t.rays.push_back(ray);
            if (record_hits) t.hits.push_back(hit);
            return hit;
        };
        if (frame.from_camera) {
            const auto py = static_cast<std::uint32_t>(tile);
            // The row's arrays, width and sample count read once: the
            // pixel loop's stores may alias them, so they were reloaded per
            // pixel and per sample.
            const auto width = static_cast<std::uint32_t>(out.width);
            const std::uint32_t spp = frame.path.spp;
            RayCounts* const row_counts = out.pixel_counts.data() + static_cast<std::size_t>(py) * width;
            Vec3* const row_radiance = out.radiance.data() + static_cast<std::size_t>(py) * width;
            for (std::uint32_t px = 0; px < width; ++px) {
                sink.ray.clear();
                Vec3 sum{0.0f};
                for (std::uint32_t s = 0; s < spp; ++s)
                    sum += trace_path(cam, px, py, s, frame.path,
                                      [&](const Ray& ray, std::uint32_t) { return trace(ray); })
                               .radiance;
                row_counts[px] = sink.ray;
                row_radiance[px] = sum / static_cast<float>(spp);
            }
            // The row's sum, read back from its pixels: cheaper than a 64-bit
            // add per pixel (EventTotals::add_all says why it is exact).
            totals.add_all(row_counts, width);
        } else {
            const std::size_t begin = tile * kRaysPerTile;
            const std::size_t end = std::min(frame.rays.size(), begin + kRaysPerTile);
            for (std::size_t i = begin; i < end; ++i) {
                sink.ray.clear();
                trace(frame.rays[i]);
                out.ray_counts[i] = sink.ray;
            }
            totals.add_all(out.ray_counts.data() + begin, end - begin);
        }
        t.totals = totals;
        t.rays_traced = rays_traced;
        progress.advance(1);
    }, /*grain=*/1);  // one row per hand-out: rows through the scene cost far more than sky rows
    progress.finish();
    for (Tile& t : tile_out) {  // fixed order: tile 0, 1, 2, ...
        out.totals += t.totals;
        out.rays_traced += t.rays_traced;
        out.rays.insert(out.rays.end(), t.rays.begin(), t.rays.end());
        out.hits.insert(out.hits.end(), t.hits.begin(), t.hits.end());
        if (fo.bands) out.tasks.push_back({t.totals, t.rays_traced, {}});
    }
    if (frame.from_camera)
        finish_band(out, tiles, first, last, static_cast<std::size_t>(out.width), out.pixel_counts.size());
    else
        finish_band(out, tiles, first, last, kRaysPerTile, frame.rays.size());
    out.trace_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace rtc

#include "sim/execution/warp_frame.h"

namespace rtc {

// Traces the workload per ray, or in warps when fo.warp is set.
template <class Tracer>
FrameResult run_frame(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    return fo.warp ? run_frame_warp(frame, fo, tracer) : run_frame_per_ray(frame, fo, tracer);
}

}  // namespace rtc
