// Pricing one warp wave under the SIMT execution model (execution_model.h):
// what each lane's ray did (its events, and each intersection-program call's
// own events in call order), and the cycles the warp spends on it.
#pragma once

#include "core/sinks.h"
#include "core/uninitialized.h"
#include "sim/hardware/call_profiles.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/sm_model.h"

#include <array>
#include <cstdint>
#include <vector>

namespace rtc {

// One active lane of a wave.
struct LaneWork {
    RayCounts counts;                          // every event of the lane's ray
    std::uint32_t first_call = 0, calls = 0;   // its program calls in WaveWork::calls
    std::uint32_t pixel = 0;                   // where its cost is shown (camera workloads)
};

// The lanes of one wave (idle lanes are simply absent).
struct WaveWork {
    // Unconstructed on emplace_back(): the frame writes every field of a new lane.
    UninitializedVector<LaneWork> lanes;
    std::vector<CallProfiles::Id> calls;  // each call's profile (its own events)
    const CallProfiles* profiles = nullptr;

    void clear() {
        lanes.clear();
        calls.clear();
    }
};

// The program price of each profile of a table under one model, filled as
// the table grows (one per thread and preset while tracing).
class ProgramPrices {
public:
    double of(const CallProfiles& table, CallProfiles::Id id, const CostModel& model) {
        if (id >= price_.size()) extend(table, id, model);
        return price_[id];
    }
    // The prices of every profile of `table`, indexed by id.
    const double* all(const CallProfiles& table, const CostModel& model) {
        if (table.size() > price_.size()) extend(table, static_cast<CallProfiles::Id>(table.size() - 1), model);
        return price_.data();
    }

private:
    void extend(const CallProfiles& table, CallProfiles::Id id, const CostModel& model);
    std::vector<double> price_;
};

struct WavePrice {
    // shader: the wave's own shader work in lockstep, including a traversal
    // loop the machine runs as shader code (ExecutionModel::lockstep_events).
    double shader = 0.0, rt = 0.0, handoff = 0.0, programs = 0.0;
    std::uint32_t rounds = 0;              // IS rounds: the most calls of any lane
    std::uint32_t active_lane_rounds = 0;  // sum over rounds of the lanes with a call
    double rt_lane_sum = 0.0;              // sum over lanes of their own RT cycles

    [[nodiscard]] double total() const { return shader + rt + handoff + programs; }
};

// Effective event counts: with the argmax lanes and calls the prices chose,
// the wave's cycles are exactly sum_e counts[e] * cost[e] (every term is a
// max or sum of linear functions of the costs). Calibration fits with them.
using EffectiveCounts = std::array<double, kEventCount>;

[[nodiscard]] WavePrice price_wave(const WaveWork& wave, const CostModel& model, ProgramPrices& prices,
                                   EffectiveCounts* effective = nullptr);
// The same, lane by lane: the reference the tests hold price_wave to.
[[nodiscard]] WavePrice price_wave_reference(const WaveWork& wave, const CostModel& model, ProgramPrices& prices,
                                             EffectiveCounts* effective = nullptr);

// Adds every lane's RT-unit event counts (without the preset's lockstep
// events, which the wave runs as shader code) to `counts`: the effective
// counts of the waves' rt_lane_sum.
void add_rt_lane_counts(EffectiveCounts& counts, const WaveWork& wave, const CostModel& model);

// The price of one call profile's program events, and its counts added to
// effective counts.
[[nodiscard]] double program_price(const ProgramCounts& call, const CostModel& model);
void add_program_counts(EffectiveCounts& effective, const ProgramCounts& call);

// A frame's waves on one SM's resources (sm_model.h): the three roofline
// terms, the cycles (the largest, or the lone-wave sum when the roofline is
// disabled) and which term bound them.
struct FrameTerms {
    enum class Bound : std::uint8_t { Sum, Latency, Issue, RtUnit };
    double latency = 0.0, issue = 0.0, rt_unit = 0.0, cycles = 0.0;
    Bound bound = Bound::Sum;
};
[[nodiscard]] const char* bound_name(FrameTerms::Bound b);

// Sums over many waves, for one preset.
struct WarpTotals {
    double shader = 0.0, rt = 0.0, handoff = 0.0, programs = 0.0;
    double rt_lane_sum = 0.0;
    std::uint64_t waves = 0, lanes = 0, rounds = 0, active_lane_rounds = 0;

    void add(const WavePrice& p, std::size_t active_lanes);
    WarpTotals& operator+=(const WarpTotals& o);
    // Every wave priced alone and added up (the model without an SM).
    [[nodiscard]] double lone_wave_cycles() const { return shader + rt + handoff + programs; }
    // The frame's cycles on the SM of `roof` (its pipeline's resident warps).
    [[nodiscard]] FrameTerms terms(const Roofline& roof) const;
    [[nodiscard]] double cycles(const Roofline& roof) const { return terms(roof).cycles; }
    // Active lanes per IS round over the warp width (Nsight's "active threads
    // per warp" for the program phase); 1 when no round ran.
    [[nodiscard]] double simt_efficiency(int warp_width) const;
    // Vulkan-Sim's RT SIMT efficiency: lanes' own RT time over W x the warp's.
    [[nodiscard]] double rt_efficiency(int warp_width) const;
    // Active lanes per wave over W (idle lanes: ended paths, partial tiles).
    [[nodiscard]] double occupancy(int warp_width) const;
};

// Effective counts of a whole frame under `roof`: `waves` are the waves'
// own (price_wave's, summed), `rt_lanes` every lane's RT-unit event counts
// (without the machine's lockstep events), summed. Turns `waves` into the
// counts whose linear price is the binding term of totals.terms(roof).
// `machine`: whose lockstep events (ExecutionModel::unit, AMD's traversal
// loop) the waves priced as shader work: SM code, issue cycles like the
// shader's own.
void roofline_counts(const WarpTotals& totals, const Roofline& roof, EffectiveCounts& waves,
                     const EffectiveCounts& rt_lanes, const ExecutionModel& machine);

}  // namespace rtc
