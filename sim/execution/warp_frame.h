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
#pragma once

#include "sim/execution/frame.h"

#include <algorithm>

namespace rtc {

template <class Tracer>
FrameResult run_frame_warp(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    const auto start = std::chrono::steady_clock::now();
    const ExecutionModel& x = *fo.warp;
    const unsigned threads = fo.threads ? fo.threads : hardware_threads();
    const std::size_t presets = fo.warp_presets.size();
    std::size_t priced = presets;  // then the draws, which keep totals only
    for (const DrawSet& set : fo.warp_draws) priced += set.draws.size();
    FrameResult out;
    const auto tw = static_cast<std::uint32_t>(x.tile_width), th = static_cast<std::uint32_t>(x.tile_height);
    const std::size_t rays_per_task = static_cast<std::size_t>(x.warp_width) * 128;
    const std::size_t tasks = frame.from_camera
                                  ? (static_cast<std::size_t>(frame.camera.height) + th - 1) / th
                                  : (frame.rays.size() + rays_per_task - 1) / rays_per_task;
    // Cache-line aligned, here and per thread below: two threads' tasks, or
    // two threads' scratch, sharing a line would pass it back and forth per
    // ray (rays_traced, the calls' vector, the last call profile).
    struct alignas(64) Task {
        EventTotals totals;
        std::vector<WarpTotals> warp;
        WarpTrace trace;
        std::vector<Ray> rays;
        std::vector<TraceHit> hits;
        std::uint64_t rays_traced = 0;
    };
    const auto [first, last] = band_range(tasks, fo.band, fo.bands);
    std::vector<Task> task_out(last - first);
    struct alignas(64) PerThread {
        TraceScratch scratch;
        CallProfiles profiles;
        std::vector<ProgramPrices> prices;  // per preset
        std::vector<WaveWork> waves;        // per bounce
        std::vector<WaveDrawPricer> draws;  // per FrameOptions::warp_draws set
    };
    std::vector<PerThread> per_thread(threads);
    for (PerThread& p : per_thread) {
        p.scratch.profiles = &p.profiles;
        for (const DrawSet& set : fo.warp_draws) p.draws.emplace_back(set);
        p.prices.resize(presets);
    }
    if (frame.from_camera) {
        out.width = frame.camera.width;
        out.height = frame.camera.height;
        const std::size_t n = static_cast<std::size_t>(out.width) * out.height;
        const std::size_t pixels_per_task = static_cast<std::size_t>(th) * static_cast<std::size_t>(out.width);
        size_for_band(out.pixel_counts, n, first * pixels_per_task, last * pixels_per_task);
        size_for_band(out.radiance, n, first * pixels_per_task, last * pixels_per_task);
        out.pixel_warp_cycles.assign(n, 0.0f);
        out.pixel_simt_active.assign(n, 0.0f);
        out.pixel_simt_slots.assign(n, 0.0f);
        out.more_pixel_warp_cycles.assign(presets > 1 ? presets - 1 : 0, std::vector<float>(n, 0.0f));
    } else {
        size_for_band(out.ray_counts, frame.rays.size(), first * rays_per_task, last * rays_per_task);
    }
    const CameraFrame cam = frame.from_camera ? camera_frame(frame.camera) : CameraFrame{};
    const bool keep_rays = fo.record_rays || fo.record_hits;
    Progress progress(fo.label, last - first, fo.progress);

    parallel_for(last - first, threads, [&, first = first](std::size_t slot, unsigned thread) {
        throw_if_interrupted();  // Ctrl-C: parallel_for stops handing out tiles and rethrows
        const std::size_t task = first + slot;
        Task& t = task_out[slot];
        t.warp.resize(priced);
        PerThread& mine = per_thread[thread];
        TraceScratch& sc = mine.scratch;
        std::vector<WaveWork>& wv = mine.waves;
        CountingSink sink;
        auto trace_ray = tracer(sink, sc);
        const auto trace_lane = [&](const Ray& ray, std::size_t depth, std::uint32_t pixel, RayCounts& into) {
            sink.ray.clear();
            const TraceHit hit = trace_ray(ray);
            into += sink.ray;
            ++t.rays_traced;
            if (wv.size() <= depth) wv.resize(depth + 1);
            WaveWork& w = wv[depth];
            w.profiles = &mine.profiles;
            w.lanes.push_back({sink.ray, static_cast<std::uint32_t>(w.calls.size()),
                               static_cast<std::uint32_t>(sc.calls.size()), pixel});
            w.calls.insert(w.calls.end(), sc.calls.begin(), sc.calls.end());
            return hit;
        };
        const auto flush_waves = [&] {
            for (WaveWork& w : wv) {
                if (w.lanes.empty()) continue;
                for (std::size_t i = 0, slot = presets; i < mine.draws.size(); slot += fo.warp_draws[i++].draws.size())
                    mine.draws[i].add(w, &t.warp[slot]);
                for (std::size_t p = 0; p < presets; ++p) {
                    const WavePrice price = price_wave(w, *fo.warp_presets[p], mine.prices[p]);
                    t.warp[p].add(price, w.lanes.size());
                    if (!frame.from_camera) continue;
                    const float share = static_cast<float>(price.total() / static_cast<double>(w.lanes.size()));
                    if (p != 0) {
                        std::vector<float>& cycles = out.more_pixel_warp_cycles[p - 1];
                        for (const LaneWork& l : w.lanes) cycles[l.pixel] += share;
                        continue;
                    }
                    for (const LaneWork& l : w.lanes) {
                        out.pixel_warp_cycles[l.pixel] += share;
                        out.pixel_simt_active[l.pixel] += static_cast<float>(price.active_lane_rounds);
                        out.pixel_simt_slots[l.pixel] += static_cast<float>(price.rounds) * static_cast<float>(x.warp_width);
                    }
                }
                if (fo.record_warps) t.trace.append(w);
                w.clear();
            }
        };
        if (frame.from_camera) {
            const std::uint32_t y0 = static_cast<std::uint32_t>(task) * th;
            const std::uint32_t y1 = std::min<std::uint32_t>(y0 + th, static_cast<std::uint32_t>(out.height));
            const auto width = static_cast<std::uint32_t>(out.width);
            // Per-pixel rays and hits of this tile row, emitted row-major at the end.
            std::vector<std::vector<Ray>> pixel_rays(keep_rays ? static_cast<std::size_t>(width) * (y1 - y0) : 0);
            std::vector<std::vector<TraceHit>> pixel_hits(pixel_rays.size());
            for (std::uint32_t x0 = 0; x0 < width; x0 += tw) {
                const std::uint32_t x1 = std::min(x0 + tw, width);
                std::vector<RayCounts> counts((x1 - x0) * (y1 - y0));
                std::vector<Vec3> sums(counts.size(), Vec3{0.0f});
                for (std::uint32_t s = 0; s < frame.path.spp; ++s) {
                    for (std::uint32_t py = y0; py < y1; ++py)
                        for (std::uint32_t px = x0; px < x1; ++px) {
                            const std::size_t lane = (py - y0) * (x1 - x0) + (px - x0);
                            const auto pixel = static_cast<std::uint32_t>(py * width + px);
                            const std::size_t local = (py - y0) * width + px;
                            sums[lane] += trace_path(cam, px, py, s, frame.path,
                                                     [&](const Ray& ray, std::uint32_t depth) {
                                                         const TraceHit h = trace_lane(ray, depth, pixel, counts[lane]);
                                                         if (keep_rays) {
                                                             if (fo.record_rays) pixel_rays[local].push_back(ray);
                                                             if (fo.record_hits) pixel_hits[local].push_back(h);
                                                         }
                                                         return h;
                                                     })
                                              .radiance;
                        }
                    flush_waves();
                }
                for (std::uint32_t py = y0; py < y1; ++py)
                    for (std::uint32_t px = x0; px < x1; ++px) {
                        const std::size_t lane = (py - y0) * (x1 - x0) + (px - x0);
                        const std::size_t pixel = static_cast<std::size_t>(py) * width + px;
                        out.pixel_counts[pixel] = counts[lane];
                        out.radiance[pixel] = sums[lane] / static_cast<float>(frame.path.spp);
                        t.totals.add(counts[lane]);
                    }
            }
            for (std::size_t i = 0; i < pixel_rays.size(); ++i) {
                t.rays.insert(t.rays.end(), pixel_rays[i].begin(), pixel_rays[i].end());
                t.hits.insert(t.hits.end(), pixel_hits[i].begin(), pixel_hits[i].end());
            }
        } else {
            const std::size_t end = std::min(frame.rays.size(), (task + 1) * rays_per_task);
            for (std::size_t w0 = task * rays_per_task; w0 < end; w0 += static_cast<std::size_t>(x.warp_width)) {
                const std::size_t w1 = std::min(end, w0 + static_cast<std::size_t>(x.warp_width));
                for (std::size_t i = w0; i < w1; ++i) {
                    RayCounts counts;
                    const TraceHit h = trace_lane(frame.rays[i], 0, 0, counts);
                    out.ray_counts[i] = counts;
                    if (fo.record_rays) t.rays.push_back(frame.rays[i]);
                    if (fo.record_hits) t.hits.push_back(h);
                    t.totals.add(counts);
                }
                flush_waves();
            }
        }
        progress.advance(1);
    }, /*grain=*/1);
    progress.finish();
    out.warp.resize(priced);
    for (Task& t : task_out) {  // fixed order: task 0, 1, 2, ...
        out.totals += t.totals;
        out.rays_traced += t.rays_traced;
        for (std::size_t p = 0; p < priced; ++p) out.warp[p] += t.warp[p];
        if (fo.record_warps) out.warp_trace.append(t.trace);
        out.rays.insert(out.rays.end(), t.rays.begin(), t.rays.end());
        out.hits.insert(out.hits.end(), t.hits.begin(), t.hits.end());
        if (fo.bands) out.tasks.push_back({t.totals, t.rays_traced, std::move(t.warp)});
    }
    if (frame.from_camera)
        finish_band(out, tasks, first, last, static_cast<std::size_t>(th) * static_cast<std::size_t>(out.width),
                    static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height));
    else
        finish_band(out, tasks, first, last, rays_per_task, frame.rays.size());
    out.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace rtc
