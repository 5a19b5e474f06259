#include "sim/hardware/warp_trace.h"

#include <algorithm>

namespace rtc {

namespace {

std::uint64_t hash_counts(const RayCounts& c) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the counts
    for (const std::uint32_t v : c.n) h = (h ^ v) * 1099511628211ull;
    return h;
}

}  // namespace

std::uint32_t WarpTrace::profile_id(const RayCounts& c) {
    const std::uint64_t h = hash_counts(c);
    const auto [lo, hi] = profile_index_.equal_range(h);
    for (auto it = lo; it != hi; ++it)
        if (profiles_[it->second].n == c.n) return it->second;
    const auto id = static_cast<std::uint32_t>(profiles_.size());
    profiles_.push_back(c);
    profile_index_.emplace(h, id);
    return id;
}

void WarpTrace::append(const WaveWork& wave) {
    wave_first_lane_.push_back(static_cast<std::uint32_t>(lane_counts_.size()));
    for (const LaneWork& l : wave.lanes) {
        lane_counts_.push_back(l.counts);
        lane_first_call_.push_back(static_cast<std::uint32_t>(call_profile_.size()));
        for (std::uint32_t k = 0; k < l.calls; ++k) call_profile_.push_back(profile_id(wave.calls[l.first_call + k]));
    }
}

void WarpTrace::append(const WarpTrace& o) {
    const auto lane_base = static_cast<std::uint32_t>(lane_counts_.size());
    const auto call_base = static_cast<std::uint32_t>(call_profile_.size());
    std::vector<std::uint32_t> remap(o.profiles_.size());
    for (std::size_t p = 0; p < o.profiles_.size(); ++p) remap[p] = profile_id(o.profiles_[p]);
    for (const std::uint32_t w : o.wave_first_lane_) wave_first_lane_.push_back(lane_base + w);
    lane_counts_.insert(lane_counts_.end(), o.lane_counts_.begin(), o.lane_counts_.end());
    for (const std::uint32_t c : o.lane_first_call_) lane_first_call_.push_back(call_base + c);
    for (const std::uint32_t p : o.call_profile_) call_profile_.push_back(remap[p]);
}

std::size_t WarpTrace::memory_bytes() const {
    return wave_first_lane_.size() * 4 + lane_counts_.size() * sizeof(RayCounts) + lane_first_call_.size() * 4 +
           call_profile_.size() * 4 + profiles_.size() * (sizeof(RayCounts) + 24);
}

WarpTotals WarpTrace::price(const CostModel& model, EffectiveCounts* effective) const {
    WarpTotals totals;
    WaveWork wave;
    const std::size_t nw = wave_first_lane_.size();
    for (std::size_t w = 0; w < nw; ++w) {
        wave.clear();
        const std::size_t l0 = wave_first_lane_[w];
        const std::size_t l1 = w + 1 < nw ? wave_first_lane_[w + 1] : lane_counts_.size();
        for (std::size_t l = l0; l < l1; ++l) {
            const std::size_t c0 = lane_first_call_[l];
            const std::size_t c1 = l + 1 < lane_first_call_.size() ? lane_first_call_[l + 1] : call_profile_.size();
            wave.lanes.push_back({lane_counts_[l], static_cast<std::uint32_t>(wave.calls.size()),
                                  static_cast<std::uint32_t>(c1 - c0), 0});
            for (std::size_t c = c0; c < c1; ++c) wave.calls.push_back(profiles_[call_profile_[c]]);
        }
        totals.add(price_wave(wave, model, effective), wave.lanes.size());
    }
    return totals;
}

}  // namespace rtc
