// Running a workload in warps (the SIMT execution model, see
// sim/hardware/execution_model.h). Camera workloads: a warp is a tile of
// tile_width x tile_height pixels at one sample index; every lane's path is
// traced in full and its k-th ray joins the tile's k-th wave (lanes whose
// paths ended are idle). Ray lists: W consecutive rays make one wave. Each
// wave is priced under every warp preset as soon as it is complete, so the
// frame's memory does not grow with its rays (unless record_warps keeps them
// for calibration). Tasks are rows of tiles, merged in order: results are
// identical whatever the number of threads, and the rays and hits files keep
// the per-ray model's order (row-major pixels, then samples, then bounces).
//
// Only the loops over a task's rays are a template (compiled in every
// method's file, for each primitive kind); WarpFrame's set-up, the pricing
// of waves, the tiles' results and the merge are compiled once
// (warp_frame.cpp).
#pragma once

#include "core/parallel.h"
#include "sim/execution/frame_result.h"
#include "sim/execution/interrupt.h"
#include "sim/hardware/call_profiles.h"
#include "sim/hardware/leaf_programs.h"
#include "sim/hardware/warp_pricing.h"
#include "sim/util/progress.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace rtc {

class WarpFrame {
public:
    // Cache-line aligned, here and per thread below: two threads' tasks, or
    // two threads' scratch, sharing a line would pass it back and forth per
    // ray (rays_traced, the calls' vector, the last call profile).
    struct alignas(64) Task {
        EventTotals totals;
        std::vector<PresetWarpTotals> warp;  // per preset
        WarpTrace trace;
        std::vector<Ray> rays;
        std::vector<TraceHit> hits;
        std::uint64_t rays_traced = 0;
    };
    struct alignas(64) Thread {
        TraceScratch scratch;
        CallProfiles profiles;
        std::vector<ProgramPrices> prices;  // per preset
        std::vector<WaveWork> waves;        // per bounce
        std::vector<WaveDrawPricer> draws;  // per FrameOptions::warp_draws set
        // The task's rays and hits per pixel of its row of tiles, emitted
        // row-major at the end (when recorded).
        std::vector<std::vector<Ray>> pixel_rays;
        std::vector<std::vector<TraceHit>> pixel_hits;
    };

    // Sizes the result's arrays for the band of tasks that fo selects, and
    // each thread's scratch; starts the clock.
    WarpFrame(const RayWorkload& work, const FrameOptions& fo);

    [[nodiscard]] std::size_t tasks() const { return last_ - first_; }
    [[nodiscard]] unsigned threads() const { return static_cast<unsigned>(threads_.size()); }
    [[nodiscard]] std::size_t task_of(std::size_t slot) const { return first_ + slot; }
    [[nodiscard]] Task& task(std::size_t slot) { return tasks_[slot]; }
    [[nodiscard]] Thread& thread(unsigned t) { return threads_[t]; }
    [[nodiscard]] FrameResult& result() { return out_; }
    [[nodiscard]] const CameraLanes& camera() const { return camera_; }
    [[nodiscard]] const ExecutionModel& model() const { return *fo_.warp; }
    [[nodiscard]] std::size_t rays_per_task() const { return rays_per_task_; }

    // The ray just traced, as a lane of the wave of its bounce `depth`: its
    // counts and the program calls it made (th.scratch.calls, as profile
    // ids). Inline, once per ray: as a call it cost 68 instructions per ray
    // (case 2 ref).
    [[gnu::always_inline]] static void add_lane(Thread& th, std::size_t depth, std::uint32_t pixel,
                                                const RayCounts& counts) {
        WaveWork& w = th.waves[depth];  // sized for every bounce (the constructor)
        const CallCounts& calls = th.scratch.calls;
        LaneWork& l = w.lanes.emplace_back();  // unconstructed: every field is written here
        l.counts.copy_from(counts);
        l.first_call = static_cast<std::uint32_t>(w.calls.size());
        l.calls = static_cast<std::uint32_t>(calls.size());
        l.pixel = pixel;
        for (const ProgramCounts& c : calls) w.calls.push_back(th.profiles.id(c));
    }

    // Prices every wave with lanes under each preset and draw, adds the
    // prices to the task and (camera workloads) to the lanes' pixels, and
    // empties the waves.
    void flush_waves(Thread& th, Task& t);

    // Camera workloads: a task's row of tiles [y0, y1), and in it the tile
    // of columns [x0, x1): before and after its samples. Each pixel's counts
    // and radiance are summed in the result's own slots (started by its
    // first ray); finish_tile divides the radiance by the sample count and
    // finish_row adds the rows' counts to the task's totals.
    void start_row(Thread& th, std::uint32_t y0, std::uint32_t y1);
    void finish_tile(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1);
    // A tile a sampled run does not trace: its pixels' counts and radiance zeroed.
    void skip_tile(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1);
    void finish_row(Thread& th, Task& t, std::uint32_t y0, std::uint32_t y1);

    void task_done() { progress_.advance(1); }

    // The tasks merged in order (task 0, 1, 2, ...), the band and the time.
    [[nodiscard]] FrameResult finish();

private:
    const RayWorkload& work_;
    const FrameOptions& fo_;
    std::chrono::steady_clock::time_point start_;
    std::size_t presets_;
    std::vector<std::size_t> draw_preset_;  // per FrameOptions::warp_draws set: the preset it draws from
    std::size_t rays_per_task_, tasks_total_, first_, last_;
    FrameResult out_;
    std::vector<Task> tasks_;
    std::vector<Thread> threads_;
    CameraLanes camera_;
    Progress progress_;
};

template <class Tracer>
FrameResult run_frame_warp(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    WarpFrame f(frame, fo);
    const ExecutionModel& x = f.model();
    parallel_for(f.tasks(), f.threads(), [&](std::size_t slot, unsigned thread) {
        throw_if_interrupted();  // Ctrl-C: parallel_for stops handing out tiles and rethrows
        const std::size_t task = f.task_of(slot);
        WarpFrame::Task& t = f.task(slot);
        WarpFrame::Thread& th = f.thread(thread);
        FrameResult& out = f.result();
        CountingSink sink;
        // The tracer records each program call's counts (th.scratch.calls):
        // an instantiation of its own, the per-ray model's has no recording.
        auto trace_ray = tracer(sink, th.scratch, std::true_type{});
        // One ray of a lane: its own counts (the sink is cleared per ray),
        // added to the lane's (`first`: copied, so the slot needs no
        // clearing) and recorded in the wave of its bounce.
        const auto trace_lane = [&](const Ray& ray, std::size_t depth, std::uint32_t pixel, RayCounts& into,
                                    bool first) {
            sink.ray.clear();
            const TraceHit hit = trace_ray(ray);
            if (first)
                into.copy_from(sink.ray);
            else
                into += sink.ray;
            ++t.rays_traced;
            WarpFrame::add_lane(th, depth, pixel, sink.ray);
            return hit;
        };
        if (frame.from_camera) {
            const auto tw = static_cast<std::uint32_t>(x.tile_width), tile_h = static_cast<std::uint32_t>(x.tile_height);
            const std::uint32_t y0 = static_cast<std::uint32_t>(task) * tile_h;
            const std::uint32_t y1 = std::min<std::uint32_t>(y0 + tile_h, static_cast<std::uint32_t>(out.height));
            const auto width = static_cast<std::uint32_t>(out.width);
            const CameraLanes& cam = f.camera();
            f.start_row(th, y0, y1);
            for (std::uint32_t x0 = 0; x0 < width; x0 += tw) {
                const std::uint32_t x1 = std::min(x0 + tw, width);
                if (fo.sample && !fo.sample->traced(x0 / tw, static_cast<std::uint32_t>(task))) {
                    f.skip_tile(x0, x1, y0, y1);  // not in the sample: no work, zero pixels
                    continue;
                }
                for (std::uint32_t s = 0; s < frame.path.spp; ++s) {
                    for (std::uint32_t py = y0; py < y1; ++py)
                        for (std::uint32_t px = x0; px < x1; ++px) {
                            const auto pixel = static_cast<std::uint32_t>(py * width + px);
                            const std::size_t local = (py - y0) * width + px;
                            // Sample 0's camera ray (every path's first) starts the
                            // pixel's sums: its slots are not cleared first.
                            const Vec3 r =
                                trace_path(cam, px, py, s, frame.path, [&](const Ray& ray, std::uint32_t depth) {
                                    const TraceHit h =
                                        trace_lane(ray, depth, pixel, out.pixel_counts[pixel], s == 0 && depth == 0);
                                    if (fo.record_rays) th.pixel_rays[local].push_back(ray);
                                    if (fo.record_hits) th.pixel_hits[local].push_back(h);
                                    return h;
                                }).radiance;
                            out.radiance[pixel] = (s == 0 ? Vec3{0.0f} : out.radiance[pixel]) + r;
                        }
                    f.flush_waves(th, t);
                }
                f.finish_tile(x0, x1, y0, y1);
            }
            f.finish_row(th, t, y0, y1);
        } else {
            const std::size_t end = std::min(frame.rays.size(), (task + 1) * f.rays_per_task());
            const auto w = static_cast<std::size_t>(x.warp_width);
            for (std::size_t w0 = task * f.rays_per_task(); w0 < end; w0 += w) {
                for (std::size_t i = w0; i < std::min(end, w0 + w); ++i) {
                    const TraceHit h = trace_lane(frame.rays[i], 0, 0, out.ray_counts[i], /*first=*/true);
                    if (fo.record_rays) t.rays.push_back(frame.rays[i]);
                    if (fo.record_hits) t.hits.push_back(h);
                }
                t.totals.add_all(out.ray_counts.data() + w0, std::min(end, w0 + w) - w0);
                f.flush_waves(th, t);
            }
        }
        f.task_done();
    }, /*grain=*/1);
    return f.finish();
}

}  // namespace rtc
