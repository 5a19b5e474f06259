#include "sim/hardware/warp_pricing.h"

#include <algorithm>

namespace rtc {

namespace {

// Price of the events of one unit in a count vector.
double unit_price(const RayCounts& c, const CostModel& m, EventUnit unit) {
    double s = 0.0;
    for (std::size_t e = 0; e < kEventCount; ++e)
        if (kEventUnits[e] == unit) s += static_cast<double>(c.n[e]) * m.cycles[e];
    return s;
}

void add_unit(EffectiveCounts& eff, const RayCounts& c, EventUnit unit, double scale) {
    for (std::size_t e = 0; e < kEventCount; ++e)
        if (kEventUnits[e] == unit) eff[e] += scale * static_cast<double>(c.n[e]);
}

}  // namespace

WavePrice price_wave(const WaveWork& wave, const CostModel& m, EffectiveCounts* eff) {
    WavePrice p;
    if (wave.lanes.empty()) return p;
    // Shader work in lockstep: the wave pays its most expensive lane once.
    std::size_t shader_lane = 0, rt_lane = 0;
    double rt_max = -1.0;
    for (std::size_t i = 0; i < wave.lanes.size(); ++i) {
        const double s = unit_price(wave.lanes[i].counts, m, EventUnit::Shader);
        if (s > p.shader) {
            p.shader = s;
            shader_lane = i;
        }
        const double r = unit_price(wave.lanes[i].counts, m, EventUnit::RtUnit);
        p.rt_lane_sum += r;
        if (r > rt_max) {
            rt_max = r;
            rt_lane = i;
        }
    }
    // RT unit: P lanes overlap; never faster than the slowest lane.
    const double parallel = std::max(1.0, m.execution.rt_parallel_lanes);
    const bool slowest_lane_bounds = rt_max >= p.rt_lane_sum / parallel;
    p.rt = slowest_lane_bounds ? rt_max : p.rt_lane_sum / parallel;
    // Program rounds.
    std::uint32_t max_calls = 0;
    for (const LaneWork& l : wave.lanes) max_calls = std::max(max_calls, l.calls);
    p.rounds = max_calls;
    double handoff_cost = 0.0;
    for (std::size_t e = 0; e < kEventCount; ++e)
        if (kEventUnits[e] == EventUnit::HandOff) handoff_cost += m.cycles[e];
    p.handoff = static_cast<double>(max_calls) * handoff_cost;
    for (std::uint32_t r = 0; r < max_calls; ++r) {
        double worst = -1.0;
        const RayCounts* worst_call = nullptr;
        for (const LaneWork& l : wave.lanes) {
            if (r >= l.calls) continue;
            ++p.active_lane_rounds;
            const RayCounts& call = wave.calls[l.first_call + r];
            const double c = unit_price(call, m, EventUnit::Program);
            if (c > worst) {
                worst = c;
                worst_call = &call;
            }
        }
        p.programs += worst;
        if (eff) add_unit(*eff, *worst_call, EventUnit::Program, 1.0);
    }
    if (eff) {
        add_unit(*eff, wave.lanes[shader_lane].counts, EventUnit::Shader, 1.0);
        if (slowest_lane_bounds) {
            add_unit(*eff, wave.lanes[rt_lane].counts, EventUnit::RtUnit, 1.0);
        } else {
            for (const LaneWork& l : wave.lanes) add_unit(*eff, l.counts, EventUnit::RtUnit, 1.0 / parallel);
        }
        for (std::size_t e = 0; e < kEventCount; ++e)
            if (kEventUnits[e] == EventUnit::HandOff) (*eff)[e] += max_calls;
    }
    return p;
}

void WarpTotals::add(const WavePrice& p, std::size_t active_lanes) {
    shader += p.shader;
    rt += p.rt;
    handoff += p.handoff;
    programs += p.programs;
    rt_lane_sum += p.rt_lane_sum;
    ++waves;
    lanes += active_lanes;
    rounds += p.rounds;
    active_lane_rounds += p.active_lane_rounds;
}

WarpTotals& WarpTotals::operator+=(const WarpTotals& o) {
    shader += o.shader;
    rt += o.rt;
    handoff += o.handoff;
    programs += o.programs;
    rt_lane_sum += o.rt_lane_sum;
    waves += o.waves;
    lanes += o.lanes;
    rounds += o.rounds;
    active_lane_rounds += o.active_lane_rounds;
    return *this;
}

double WarpTotals::simt_efficiency(int w) const {
    return rounds ? static_cast<double>(active_lane_rounds) / (static_cast<double>(rounds) * w) : 1.0;
}

double WarpTotals::rt_efficiency(int w) const {
    return rt > 0.0 ? rt_lane_sum / (rt * w) : 1.0;
}

double WarpTotals::occupancy(int w) const {
    return waves ? static_cast<double>(lanes) / (static_cast<double>(waves) * w) : 0.0;
}

}  // namespace rtc
