#include "sim/hardware/warp_trace.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace rtc {

namespace {

// The events a lane record keeps: every event outside intersection programs.
constexpr auto kLaneEventIndex = events_of_unit<EventUnit::Program, /*Others=*/true>();
constexpr std::size_t kLaneEvents = kLaneEventIndex.size();

}  // namespace

void WarpTrace::append(const WaveWork& wave) {
    wave_first_lane_.push_back(static_cast<std::uint32_t>(lanes()));
    for (const LaneWork& l : wave.lanes) {
        for (const std::uint8_t e : kLaneEventIndex) lane_counts_.push_back(l.counts.n[e]);
        lane_first_call_.push_back(static_cast<std::uint32_t>(call_profile_.size()));
        for (std::uint32_t k = 0; k < l.calls; ++k)
            call_profile_.push_back(profiles_.id((*wave.profiles)[wave.calls[l.first_call + k]]));
    }
}

void WarpTrace::append(const WarpTrace& o) {
    const auto lane_base = static_cast<std::uint32_t>(lanes());
    const auto call_base = static_cast<std::uint32_t>(call_profile_.size());
    std::vector<CallProfiles::Id> remap(o.profiles_.size());
    for (std::size_t p = 0; p < o.profiles_.size(); ++p)
        remap[p] = profiles_.id(o.profiles_[static_cast<CallProfiles::Id>(p)]);
    for (const std::uint32_t w : o.wave_first_lane_) wave_first_lane_.push_back(lane_base + w);
    lane_counts_.insert(lane_counts_.end(), o.lane_counts_.begin(), o.lane_counts_.end());
    for (const std::uint32_t c : o.lane_first_call_) lane_first_call_.push_back(call_base + c);
    for (const std::uint32_t p : o.call_profile_) call_profile_.push_back(remap[p]);
}

std::size_t WarpTrace::memory_bytes() const {
    return wave_first_lane_.size() * 4 + lane_counts_.size() * 4 + lane_first_call_.size() * 4 +
           call_profile_.size() * 2 + profiles_.size() * (sizeof(RayCounts) + 24);
}

// Rebuilds each wave from the compact arrays and prices it with price_wave,
// the function frames use while tracing, so both agree by construction.
WarpTotals WarpTrace::price(const CostModel& m) const { return price_waves(m, nullptr, nullptr); }

WarpTotals WarpTrace::price(const CostModel& m, const Roofline& roof, EffectiveCounts& eff) const {
    EffectiveCounts rt_lanes{};
    const WarpTotals totals = price_waves(m, &eff, roof.enabled ? &rt_lanes : nullptr);
    roofline_counts(totals, roof, eff, rt_lanes, m.execution);
    return totals;
}

WarpTotals WarpTrace::price_reference(const CostModel& m) const { return price_waves(m, nullptr, nullptr, true); }

WarpTotals WarpTrace::price_waves(const CostModel& m, EffectiveCounts* eff, EffectiveCounts* rt_lanes,
                                  bool reference) const {
    WarpTotals totals;
    ProgramPrices prices;
    WaveWork wave;
    wave.profiles = &profiles_;
    const std::size_t nw = wave_first_lane_.size(), nl = lanes();
    for (std::size_t w = 0; w < nw; ++w) {
        wave.clear();
        const std::size_t l0 = wave_first_lane_[w], l1 = w + 1 < nw ? wave_first_lane_[w + 1] : nl;
        const std::size_t c0 = lane_first_call_.empty() || l0 >= nl ? call_profile_.size() : lane_first_call_[l0];
        for (std::size_t l = l0; l < l1; ++l) {
            RayCounts counts;  // the lane's own events; its calls' are in the profiles
            for (std::size_t k = 0; k < kLaneEvents; ++k) counts.n[kLaneEventIndex[k]] = lane_counts_[l * kLaneEvents + k];
            wave.lanes.push_back({counts, static_cast<std::uint32_t>(lane_first_call_[l] - c0), calls_of(l), 0});
        }
        const std::size_t c1 = l1 < nl ? lane_first_call_[l1] : call_profile_.size();
        wave.calls.assign(call_profile_.begin() + static_cast<std::ptrdiff_t>(c0),
                          call_profile_.begin() + static_cast<std::ptrdiff_t>(c1));
        totals.add(reference ? price_wave_reference(wave, m, prices, eff) : price_wave(wave, m, prices, eff),
                   wave.lanes.size());
        if (rt_lanes) add_rt_lane_counts(*rt_lanes, wave, m);
    }
    return totals;
}

}  // namespace rtc
