#include "sim/execution/per_ray_frame.h"

namespace rtc {

namespace {

std::size_t tile_count(const RayWorkload& work) {
    return work.from_camera ? static_cast<std::size_t>(work.camera.height)
                            : (work.rays.size() + PerRayFrame::kRaysPerTile - 1) / PerRayFrame::kRaysPerTile;
}

}  // namespace

PerRayFrame::PerRayFrame(const RayWorkload& work, const FrameOptions& fo)
    : work_(work),
      fo_(fo),
      start_(std::chrono::steady_clock::now()),
      threads_(fo.threads ? fo.threads : hardware_threads()),
      tiles_total_(tile_count(work)),
      first_(band_range(tiles_total_, fo.band, fo.bands).first),
      last_(band_range(tiles_total_, fo.band, fo.bands).second),
      tiles_(last_ - first_),
      scratch_(threads_),
      camera_(work.from_camera ? camera_frame(work.camera) : CameraFrame{}),
      progress_(fo.label, last_ - first_, fo.progress) {
    if (work.from_camera) {
        out_.width = work.camera.width;
        out_.height = work.camera.height;
        const std::size_t pixels = static_cast<std::size_t>(out_.width) * out_.height;
        const std::size_t row = static_cast<std::size_t>(out_.width);
        size_for_band(out_.pixel_counts, pixels, first_ * row, last_ * row);
        size_for_band(out_.radiance, pixels, first_ * row, last_ * row);
    } else {
        size_for_band(out_.ray_counts, work.rays.size(), first_ * kRaysPerTile, last_ * kRaysPerTile);
    }
}

FrameResult PerRayFrame::finish() {
    progress_.finish();
    for (Tile& t : tiles_) {  // fixed order: tile 0, 1, 2, ...
        out_.totals += t.totals;
        out_.rays_traced += t.rays_traced;
        out_.rays.insert(out_.rays.end(), t.rays.begin(), t.rays.end());
        out_.hits.insert(out_.hits.end(), t.hits.begin(), t.hits.end());
        if (fo_.bands) out_.tasks.push_back({t.totals, t.rays_traced, {}});
    }
    if (work_.from_camera)
        finish_band(out_, tiles_total_, first_, last_, static_cast<std::size_t>(out_.width), out_.pixel_counts.size());
    else
        finish_band(out_, tiles_total_, first_, last_, kRaysPerTile, work_.rays.size());
    out_.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return std::move(out_);
}

}  // namespace rtc
