// A sampled run's estimates over the whole frame (docs/sampling.md): the
// traced tiles' totals scaled by k = 1 / fraction, and a 95 % confidence
// interval for each from the tiles' spread (sim/execution/tile_sample.h).
#pragma once

#include "core/sinks.h"
#include "sim/execution/frame_result.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/warp_pricing.h"

#include <array>
#include <optional>
#include <vector>

namespace rtc {

struct SampledMethod {
    EventTotals totals;  // k x the traced tiles' counts
    std::uint64_t rays = 0;
    std::array<double, 2> rays_interval{};
    std::array<std::array<double, 2>, kEventCount> event_intervals{};
    // Per cost preset: each drawn tile's cycles (TileSample::slots order);
    // empty when the frame has no per-pixel cycles for the preset.
    std::vector<std::vector<double>> tile_cycles;
    std::vector<std::optional<SampledEstimate>> cycles;  // per cost preset, around the scaled total
};

// The estimates of one method's sampled frame. `costs` are the run's cost
// presets; `warp_pixels[p]` the frame's per-pixel cycles of preset p when it
// is a warp preset (its PresetWarp::pixel_cycles),
// null for per-ray presets (priced from the pixels' counts) or when the
// frame has none; `totals[p]` the preset's scaled total cycles.
[[nodiscard]] SampledMethod estimate_sampled(const FrameResult& frame, const TileSample& sample,
                                             const std::vector<CostModel>& costs,
                                             const std::vector<const std::vector<float>*>& warp_pixels,
                                             const std::vector<double>& totals);

// Scales what a sampled frame's pricing gives to the whole frame: k x
// cycles, counts and waves (ratios such as cycles per wave do not change).
void scale_priced(PricedRun& p, double k);
void scale_warp(WarpTotals& w, std::uint64_t k);

// `e` moved to be centred on `value` (the exact scaled figure, where the
// estimator summed per-tile values rounded otherwise).
[[nodiscard]] SampledEstimate centred(SampledEstimate e, double value);

// The fraction 1 / k a run needs for a relative half-width `target` on a
// speedup whose pilot at fraction 1 / k0 had relative half-width `pilot`:
// with two tiles per stratum the variance goes as (1 - f) / f at a fixed
// within-stratum spread, so (1 - f) / f = (1 - f0) / f0 (target / pilot)^2,
// rounded down to 1 / k (at least 1: every tile).
[[nodiscard]] std::uint32_t suggested_k(std::uint32_t k0, double pilot, double target);

}  // namespace rtc
