#include "sim/hardware/warp_trace.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace rtc {

namespace {

// The events a lane record keeps: every event outside intersection programs.
constexpr std::size_t count_lane_events() {
    std::size_t n = 0;
    for (const EventUnit u : kEventUnits) n += u != EventUnit::Program;
    return n;
}
constexpr std::size_t kLaneEvents = count_lane_events();

constexpr std::array<std::uint8_t, kLaneEvents> lane_event_index() {
    std::array<std::uint8_t, kLaneEvents> idx{};
    std::size_t k = 0;
    for (std::size_t e = 0; e < kEventCount; ++e)
        if (kEventUnits[e] != EventUnit::Program) idx[k++] = static_cast<std::uint8_t>(e);
    return idx;
}
constexpr auto kLaneEventIndex = lane_event_index();

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

// The same arithmetic as price_wave (warp_pricing.cpp), straight from the
// compact arrays: each profile is priced once per model, each lane from its
// packed counts. Tests check that both agree.
WarpTotals WarpTrace::price(const CostModel& m, EffectiveCounts* eff) const {
    std::vector<double> profile_price(profiles_.size());
    for (std::size_t p = 0; p < profiles_.size(); ++p)
        profile_price[p] = program_price(profiles_[static_cast<CallProfiles::Id>(p)], m);
    double handoff_cost = 0.0;
    for (std::size_t e = 0; e < kEventCount; ++e)
        if (kEventUnits[e] == EventUnit::HandOff) handoff_cost += m.cycles[e];
    const double parallel = std::max(1.0, m.execution.rt_parallel_lanes);
    WarpTotals totals;
    const std::size_t nw = wave_first_lane_.size(), nl = lanes();
    for (std::size_t w = 0; w < nw; ++w) {
        const std::size_t l0 = wave_first_lane_[w], l1 = w + 1 < nw ? wave_first_lane_[w + 1] : nl;
        WavePrice p;
        std::size_t shader_lane = l0, rt_lane = l0;
        double rt_max = -1.0;
        std::uint32_t rounds = 0;
        for (std::size_t l = l0; l < l1; ++l) {
            double shader = 0.0, rt = 0.0;
            for (std::size_t k = 0; k < kLaneEvents; ++k) {
                const std::size_t e = kLaneEventIndex[k];
                const double c = lane_counts_[l * kLaneEvents + k] * m.cycles[e];
                if (kEventUnits[e] == EventUnit::Shader) shader += c;
                else if (kEventUnits[e] == EventUnit::RtUnit) rt += c;
            }
            if (shader > p.shader) p.shader = shader, shader_lane = l;
            p.rt_lane_sum += rt;
            if (rt > rt_max) rt_max = rt, rt_lane = l;
            rounds = std::max(rounds, calls_of(l));
        }
        const bool slowest_lane_bounds = rt_max >= p.rt_lane_sum / parallel;
        p.rt = slowest_lane_bounds ? rt_max : p.rt_lane_sum / parallel;
        p.rounds = rounds;
        p.handoff = rounds * handoff_cost;
        for (std::uint32_t r = 0; r < rounds; ++r) {
            double worst = -1.0;
            CallProfiles::Id worst_profile = 0;
            for (std::size_t l = l0; l < l1; ++l) {
                if (r >= calls_of(l)) continue;
                ++p.active_lane_rounds;
                const CallProfiles::Id prof = call_profile_[lane_first_call_[l] + r];
                if (profile_price[prof] > worst) worst = profile_price[prof], worst_profile = prof;
            }
            p.programs += worst;
            if (eff) add_program_counts(*eff, profiles_[worst_profile]);
        }
        if (eff) {
            for (std::size_t k = 0; k < kLaneEvents; ++k) {
                const std::size_t e = kLaneEventIndex[k];
                if (kEventUnits[e] == EventUnit::Shader) (*eff)[e] += lane_counts_[shader_lane * kLaneEvents + k];
                if (kEventUnits[e] == EventUnit::HandOff) (*eff)[e] += rounds;
                if (kEventUnits[e] != EventUnit::RtUnit) continue;
                if (slowest_lane_bounds) {
                    (*eff)[e] += lane_counts_[rt_lane * kLaneEvents + k];
                } else {
                    for (std::size_t l = l0; l < l1; ++l) (*eff)[e] += lane_counts_[l * kLaneEvents + k] / parallel;
                }
            }
        }
        totals.add(p, l1 - l0);
    }
    return totals;
}

}  // namespace rtc
