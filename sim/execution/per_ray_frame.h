// Running a workload through a tracer (one method's compiled ray path), one
// ray after another: every ray of every pixel (or of a ray file) traced on
// all cores, with per-ray event counts flushed into per-pixel and per-tile
// totals. Tiles write only their own slots and are merged in tile order, so
// counts, images and hit files are identical whatever the number of threads.
//
// Only the loop over a tile's rays is a template (compiled in every method's
// file, for each primitive kind); PerRayFrame's set-up and merge are compiled
// once (per_ray_frame.cpp).
#pragma once

#include "core/parallel.h"
#include "sim/execution/frame_result.h"
#include "sim/execution/interrupt.h"
#include "sim/hardware/leaf_programs.h"
#include "sim/util/progress.h"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace rtc {

// What the per-ray runner keeps beside its tracer: the result's arrays, the
// band's tiles (one per image row, or per kRaysPerTile rays of a ray list)
// and each thread's scratch.
class PerRayFrame {
public:
    static constexpr std::size_t kRaysPerTile = 4096;

    // Each tile is written by one task only, at its end (the task counts into
    // locals), on its own cache lines: no line is shared between threads'
    // tiles while they run.
    struct alignas(64) Tile {
        EventTotals totals;
        std::vector<Ray> rays;
        std::vector<TraceHit> hits;
        std::uint64_t rays_traced = 0;
    };

    // Sizes the result's per-pixel (or per-ray) arrays for the band of tiles
    // that fo selects (FrameOptions::band) and starts the clock.
    PerRayFrame(const RayWorkload& work, const FrameOptions& fo);

    [[nodiscard]] std::size_t tasks() const { return last_ - first_; }
    [[nodiscard]] unsigned threads() const { return threads_; }
    // The frame's tile that task `slot` traces.
    [[nodiscard]] std::size_t tile_of(std::size_t slot) const { return first_ + slot; }
    [[nodiscard]] Tile& tile(std::size_t slot) { return tiles_[slot]; }
    [[nodiscard]] TraceScratch& scratch(unsigned thread) { return scratch_[thread].s; }
    [[nodiscard]] FrameResult& result() { return out_; }
    [[nodiscard]] const CameraLanes& camera() const { return camera_; }
    void task_done() { progress_.advance(1); }

    // The tiles merged in order (tile 0, 1, 2, ...), the band and the time.
    [[nodiscard]] FrameResult finish();

private:
    struct alignas(64) Scratch {
        TraceScratch s;
    };
    const RayWorkload& work_;
    const FrameOptions& fo_;
    std::chrono::steady_clock::time_point start_;
    unsigned threads_;
    std::size_t tiles_total_, first_, last_;
    FrameResult out_;
    std::vector<Tile> tiles_;
    std::vector<Scratch> scratch_;
    CameraLanes camera_;
    Progress progress_;
};

// `tracer(CountingSink&, TraceScratch&, record_calls)` makes, once per task,
// the function `(const Ray&) -> TraceHit` that traces one ray counting into
// that sink: a method's template instantiation, called directly (no virtual
// call per ray). `record_calls` is std::false_type here: the per-ray model
// needs no program call's own events (the warp runner's is std::true_type).
template <class Tracer>
FrameResult run_frame_per_ray(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    PerRayFrame f(frame, fo);
    parallel_for(f.tasks(), f.threads(), [&](std::size_t slot, unsigned thread) {
        throw_if_interrupted();  // Ctrl-C: parallel_for stops handing out rows and rethrows
        const std::size_t tile = f.tile_of(slot);
        PerRayFrame::Tile& t = f.tile(slot);
        FrameResult& out = f.result();
        std::uint64_t rays_traced = 0;
        // Every ray of a pixel (or of a ray-list tile) counts into one sink:
        // the per-pixel sums without a per-ray flush.
        CountingSink sink;
        auto trace_ray = tracer(sink, f.scratch(thread), std::false_type{});
        const bool record_rays = fo.record_rays, record_hits = fo.record_hits;
        const bool record = record_rays || record_hits;  // one test per ray when neither
        const auto trace = [&](const Ray& ray) {
            const TraceHit hit = trace_ray(ray);
            ++rays_traced;
            if (record) {
                if (record_rays) t.rays.push_back(ray);
                if (record_hits) t.hits.push_back(hit);
            }
            return hit;
        };
        if (frame.from_camera) {
            const auto py = static_cast<std::uint32_t>(tile);
            // The row's arrays, width and sample count read once: the
            // pixel loop's stores may alias them, so they were reloaded per
            // pixel and per sample.
            const auto width = static_cast<std::uint32_t>(out.width);
            const std::uint32_t spp = frame.path.spp;
            // The path options copied into the task's frame: through the
            // workload's reference, every sample reloaded them via two pointers.
            const PathOptions path = frame.path;
            const CameraLanes& cam = f.camera();
            RayCounts* const row_counts = out.pixel_counts.data() + static_cast<std::size_t>(py) * width;
            Vec3* const row_radiance = out.radiance.data() + static_cast<std::size_t>(py) * width;
            const TileSample* const sample = fo.sample;
            for (std::uint32_t px = 0; px < width; ++px) {
                if (sample && !sample->traced_pixel(px, py)) {  // not in the sample: no work, zero pixels
                    row_counts[px].clear();
                    row_radiance[px] = Vec3{0.0f};
                    continue;
                }
                sink.ray.clear();
                // The samples summed in the pixel's own slot: a sum of the
                // loop's own lived in the stack frame anyway (the traces'
                // calls clobber every vector register) and was copied out.
                Vec3& sum = row_radiance[px];
                sum = Vec3{0.0f};
                for (std::uint32_t s = 0; s < spp; ++s)
                    sum += trace_path(cam, px, py, s, path,
                                      [&](const Ray& ray, std::uint32_t) { return trace(ray); })
                               .radiance;
                row_counts[px].copy_from(sink.ray);
                // x / 1 is x: one sample per pixel skips the division.
                if (spp != 1) sum /= static_cast<float>(spp);
            }
            // The row's sum, read back from its pixels: cheaper than a 64-bit
            // add per pixel (EventTotals::add_all says why it is exact).
            t.totals.add_all(row_counts, width);
        } else {
            const std::size_t begin = tile * PerRayFrame::kRaysPerTile;
            const std::size_t end = std::min(frame.rays.size(), begin + PerRayFrame::kRaysPerTile);
            for (std::size_t i = begin; i < end; ++i) {
                sink.ray.clear();
                trace(frame.rays[i]);
                out.ray_counts[i].copy_from(sink.ray);
            }
            t.totals.add_all(out.ray_counts.data() + begin, end - begin);
        }
        t.rays_traced = rays_traced;
        f.task_done();
    }, /*grain=*/1);  // one row per hand-out: rows through the scene cost far more than sky rows
    return f.finish();
}

}  // namespace rtc
