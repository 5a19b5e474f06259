#include "sim/execution/warp_frame.h"

#include <stdexcept>

namespace rtc {

namespace {

// Per draw set, the index of the warp preset it was drawn from.
std::vector<std::size_t> draw_presets(const FrameOptions& fo) {
    std::vector<std::size_t> out;
    for (const DrawSet& set : fo.warp_draws) {
        const auto p = std::find(fo.warp_presets.begin(), fo.warp_presets.end(), set.base);
        if (p == fo.warp_presets.end()) throw std::logic_error("a warp draw set's base is not a warp preset");
        out.push_back(static_cast<std::size_t>(p - fo.warp_presets.begin()));
    }
    return out;
}

std::size_t task_count(const RayWorkload& work, const ExecutionModel& x, std::size_t rays_per_task) {
    const auto th = static_cast<std::size_t>(x.tile_height);
    return work.from_camera ? (static_cast<std::size_t>(work.camera.height) + th - 1) / th
                            : (work.rays.size() + rays_per_task - 1) / rays_per_task;
}

}  // namespace

WarpFrame::WarpFrame(const RayWorkload& work, const FrameOptions& fo)
    : work_(work),
      fo_(fo),
      start_(std::chrono::steady_clock::now()),
      presets_(fo.warp_presets.size()),
      draw_preset_(draw_presets(fo)),
      rays_per_task_(static_cast<std::size_t>(fo.warp->warp_width) * 128),
      tasks_total_(task_count(work, *fo.warp, rays_per_task_)),
      first_(band_range(tasks_total_, fo.band, fo.bands).first),
      last_(band_range(tasks_total_, fo.band, fo.bands).second),
      tasks_(last_ - first_),
      threads_(fo.threads ? fo.threads : hardware_threads()),
      camera_(work.from_camera ? camera_frame(work.camera) : CameraFrame{}),
      progress_(fo.label, last_ - first_, fo.progress) {
    for (Task& t : tasks_) {
        t.warp.resize(presets_);
        for (std::size_t i = 0; i < draw_preset_.size(); ++i)
            t.warp[draw_preset_[i]].draws.resize(fo.warp_draws[i].draws.size());
    }
    // Every bounce's wave from the start (a path has at most bounces + 1
    // rays; a ray list's rays are all depth 0), each with room for a tile's
    // lanes or a ray list's warp: no size check and no reallocation per ray.
    const std::size_t depths = work.from_camera ? static_cast<std::size_t>(work.path.bounces) + 1 : 1;
    const std::size_t lanes = std::max(static_cast<std::size_t>(fo.warp->tile_width) * fo.warp->tile_height,
                                       static_cast<std::size_t>(fo.warp->warp_width));
    for (Thread& th : threads_) {
        for (const DrawSet& set : fo.warp_draws) th.draws.emplace_back(set);
        th.prices.resize(presets_);
        th.waves.resize(depths);
        for (WaveWork& w : th.waves) {
            w.profiles = &th.profiles;
            w.lanes.reserve(lanes);
        }
    }
    if (work.from_camera) {
        out_.width = work.camera.width;
        out_.height = work.camera.height;
        const std::size_t n = static_cast<std::size_t>(out_.width) * out_.height;
        const std::size_t pixels_per_task =
            static_cast<std::size_t>(fo.warp->tile_height) * static_cast<std::size_t>(out_.width);
        size_for_band(out_.pixel_counts, n, first_ * pixels_per_task, last_ * pixels_per_task);
        size_for_band(out_.radiance, n, first_ * pixels_per_task, last_ * pixels_per_task);
        out_.pixel_simt_active.assign(n, 0.0f);
        out_.pixel_simt_slots.assign(n, 0.0f);
    } else {
        size_for_band(out_.ray_counts, work.rays.size(), first_ * rays_per_task_, last_ * rays_per_task_);
    }
    out_.warp.resize(presets_);
    for (std::size_t p = 0; p < presets_; ++p) {
        out_.warp[p].preset = fo.warp_presets[p]->name;
        if (work.from_camera) out_.warp[p].pixel_cycles.assign(static_cast<std::size_t>(out_.width) * out_.height, 0.0f);
    }
}

void WarpFrame::flush_waves(Thread& th, Task& t) {
    const bool camera = work_.from_camera;
    const auto warp_width = static_cast<float>(fo_.warp->warp_width);
    for (WaveWork& w : th.waves) {
        if (w.lanes.empty()) continue;
        for (std::size_t i = 0; i < th.draws.size(); ++i) th.draws[i].add(w, t.warp[draw_preset_[i]].draws.data());
        for (std::size_t p = 0; p < presets_; ++p) {
            const WavePrice price = price_wave(w, *fo_.warp_presets[p], th.prices[p]);
            t.warp[p].totals.add(price, w.lanes.size());
            if (!camera) continue;
            const float share = static_cast<float>(price.total() / static_cast<double>(w.lanes.size()));
            std::vector<float>& cycles = out_.warp[p].pixel_cycles;
            if (p != 0) {
                for (const LaneWork& l : w.lanes) cycles[l.pixel] += share;
                continue;
            }
            const auto active = static_cast<float>(price.active_lane_rounds);
            const float slots = static_cast<float>(price.rounds) * warp_width;
            for (const LaneWork& l : w.lanes) {
                cycles[l.pixel] += share;
                out_.pixel_simt_active[l.pixel] += active;
                out_.pixel_simt_slots[l.pixel] += slots;
            }
        }
        if (fo_.record_warps) t.trace.append(w);
        w.clear();
    }
}

void WarpFrame::start_row(Thread& th, std::uint32_t y0, std::uint32_t y1) {
    const std::size_t pixels = fo_.record_rays || fo_.record_hits ? static_cast<std::size_t>(out_.width) * (y1 - y0) : 0;
    th.pixel_rays.assign(pixels, {});
    th.pixel_hits.assign(pixels, {});
}

void WarpFrame::finish_tile(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) {
    const std::uint32_t spp = work_.path.spp;
    if (spp == 1) return;  // x / 1 is x
    const auto width = static_cast<std::size_t>(out_.width);
    for (std::uint32_t py = y0; py < y1; ++py)
        for (std::uint32_t px = x0; px < x1; ++px) out_.radiance[py * width + px] /= static_cast<float>(spp);
}

void WarpFrame::skip_tile(std::uint32_t x0, std::uint32_t x1, std::uint32_t y0, std::uint32_t y1) {
    const auto width = static_cast<std::size_t>(out_.width);
    for (std::uint32_t py = y0; py < y1; ++py)
        for (std::uint32_t px = x0; px < x1; ++px) {
            out_.pixel_counts[py * width + px].clear();
            out_.radiance[py * width + px] = Vec3{0.0f};
        }
}

void WarpFrame::finish_row(Thread& th, Task& t, std::uint32_t y0, std::uint32_t y1) {
    // The rows' counts, read back from their pixels (as the per-ray runner
    // sums its row): cheaper than a 64-bit add per pixel.
    const auto width = static_cast<std::size_t>(out_.width);
    t.totals.add_all(out_.pixel_counts.data() + y0 * width, (y1 - y0) * width);
    for (std::size_t i = 0; i < th.pixel_rays.size(); ++i) {
        t.rays.insert(t.rays.end(), th.pixel_rays[i].begin(), th.pixel_rays[i].end());
        t.hits.insert(t.hits.end(), th.pixel_hits[i].begin(), th.pixel_hits[i].end());
    }
}

FrameResult WarpFrame::finish() {
    progress_.finish();
    for (std::size_t i = 0; i < draw_preset_.size(); ++i)
        out_.warp[draw_preset_[i]].draws.resize(fo_.warp_draws[i].draws.size());
    for (Task& t : tasks_) {  // fixed order: task 0, 1, 2, ...
        out_.totals += t.totals;
        out_.rays_traced += t.rays_traced;
        for (std::size_t p = 0; p < presets_; ++p) out_.warp[p] += t.warp[p];
        if (fo_.record_warps) out_.warp_trace.append(t.trace);
        out_.rays.insert(out_.rays.end(), t.rays.begin(), t.rays.end());
        out_.hits.insert(out_.hits.end(), t.hits.begin(), t.hits.end());
        if (fo_.bands) out_.tasks.push_back({t.totals, t.rays_traced, std::move(t.warp)});
    }
    const std::size_t pixels = static_cast<std::size_t>(out_.width) * static_cast<std::size_t>(out_.height);
    if (work_.from_camera)
        finish_band(out_, tasks_total_, first_, last_,
                    static_cast<std::size_t>(fo_.warp->tile_height) * static_cast<std::size_t>(out_.width), pixels);
    else
        finish_band(out_, tasks_total_, first_, last_, rays_per_task_, work_.rays.size());
    out_.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return std::move(out_);
}

}  // namespace rtc
