#include "sim/run/sampled_run.h"

#include <algorithm>
#include <cmath>

namespace rtc {

SampledEstimate centred(SampledEstimate e, double value) {
    const double low = value - e.value + e.interval[0], high = value - e.value + e.interval[1];
    e.value = value;
    e.interval = {low, high};
    return e;
}

SampledMethod estimate_sampled(const FrameResult& frame, const TileSample& sample, const std::vector<CostModel>& costs,
                               const std::vector<const std::vector<float>*>& warp_pixels,
                               const std::vector<double>& totals) {
    SampledMethod s;
    const std::uint32_t k = sample.k();
    for (std::size_t i = 0; i < kEventCount; ++i) s.totals.n[i] = frame.totals.n[i] * k;
    s.rays = frame.rays_traced * k;
    const int w = frame.width, h = frame.height;
    const bool pixels = frame.pixel_counts.size() == static_cast<std::size_t>(w) * static_cast<std::size_t>(h) && w > 0;
    if (pixels) {
        // Every event's per-tile sums in one pass over the drawn tiles' pixels.
        std::vector<std::array<double, kEventCount>> tiles(sample.slots().size());
        for (std::size_t e = 0; e < kEventCount; ++e) {
            const std::vector<double> y =
                sample.tile_values(w, h, [&](std::size_t p) { return static_cast<double>(frame.pixel_counts[p].n[e]); });
            const SampledEstimate est = centred(estimate_total(y, k), static_cast<double>(s.totals.n[e]));
            s.event_intervals[e] = est.interval;
            if (static_cast<Event>(e) == Event::Ray) s.rays_interval = centred(est, static_cast<double>(s.rays)).interval;
        }
    }
    s.tile_cycles.resize(costs.size());
    s.cycles.resize(costs.size());
    for (std::size_t p = 0; p < costs.size(); ++p) {
        const std::vector<float>* warp = p < warp_pixels.size() ? warp_pixels[p] : nullptr;
        if (costs[p].execution.warp()) {
            if (!warp || warp->size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) continue;
            s.tile_cycles[p] = sample.tile_values(w, h, [&](std::size_t i) { return static_cast<double>((*warp)[i]); });
        } else {
            if (!pixels) continue;
            s.tile_cycles[p] =
                sample.tile_values(w, h, [&](std::size_t i) { return price_cycles(frame.pixel_counts[i], costs[p]); });
        }
        s.cycles[p] = centred(estimate_total(s.tile_cycles[p], k), p < totals.size() ? totals[p] : 0.0);
    }
    return s;
}

void scale_priced(PricedRun& p, double k) {
    p.total_cycles *= k;
    p.per_ray_cycles *= k;
    for (double& c : p.by_event) c *= k;
}

void scale_warp(WarpTotals& w, std::uint64_t k) {
    const auto kd = static_cast<double>(k);
    w.shader *= kd;
    w.rt *= kd;
    w.handoff *= kd;
    w.programs *= kd;
    w.rt_lane_sum *= kd;
    w.waves *= k;
    w.lanes *= k;
    w.rounds *= k;
    w.active_lane_rounds *= k;
}

std::uint32_t suggested_k(std::uint32_t k0, double pilot, double target) {
    if (k0 <= 1 || !(target > 0.0)) return 1;
    if (!(pilot > 0.0)) return k0;  // no spread seen: no evidence for a smaller sample than the pilot's
    const double f0 = 1.0 / k0;
    const double odds = (1.0 - f0) / f0 * (target / pilot) * (target / pilot);  // (1 - f) / f
    const double k = std::floor(1.0 + odds);                                       // 1 / f = 1 + odds
    return k >= 1e9 ? 1000000000u : static_cast<std::uint32_t>(std::max(1.0, k));
}

}  // namespace rtc
