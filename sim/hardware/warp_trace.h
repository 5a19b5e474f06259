// A compact record of every wave of a traced frame, so a frame traced once
// can be re-priced under the warp model with other costs (calibration, cost
// sweeps) without tracing again. Lanes keep the counts of their events that
// are not program events (the programs' are in their calls): 4 bytes per
// such event. Program calls are 2-byte indices into a table of distinct call
// profiles (most calls of a frame share a handful: a capsule miss, a capsule
// hit, a phantom call with k iterations, ...). About 32 B per ray + 2 B per
// call: a 3 M-ray frame with 30 M calls keeps about 160 MB.
#pragma once

#include "sim/hardware/warp_pricing.h"

#include <cstdint>
#include <vector>

namespace rtc {

class WarpTrace {
public:
    void append(const WaveWork& wave);
    // Appends `other` (its waves after ours), remapping its profiles.
    void append(const WarpTrace& other);

    [[nodiscard]] std::size_t waves() const { return wave_first_lane_.size(); }
    [[nodiscard]] std::size_t lanes() const { return lane_first_call_.size(); }
    [[nodiscard]] std::size_t calls() const { return call_profile_.size(); }
    [[nodiscard]] std::size_t profiles() const { return profiles_.size(); }
    [[nodiscard]] std::size_t memory_bytes() const;

    // Cycles of every wave under `model` (its execution parameters and
    // costs).
    [[nodiscard]] WarpTotals price(const CostModel& model) const;
    // The same, and the effective counts whose linear price is the frame's
    // cycles on the SM of `roof` (totals.cycles(roof)).
    [[nodiscard]] WarpTotals price(const CostModel& model, const Roofline& roof, EffectiveCounts& effective) const;
    // Every wave priced by price_wave_reference, the lane-by-lane
    // specification the fast pricers are tested against.
    [[nodiscard]] WarpTotals price_reference(const CostModel& model) const;

private:
    // Every wave priced; `eff` (if set) gets their effective counts, and
    // `rt_lanes` (if set) every lane's RT-unit counts.
    [[nodiscard]] WarpTotals price_waves(const CostModel& model, EffectiveCounts* eff, EffectiveCounts* rt_lanes,
                                         bool reference = false) const;
    [[nodiscard]] std::uint32_t calls_of(std::size_t lane) const {
        const std::size_t end = lane + 1 < lane_first_call_.size() ? lane_first_call_[lane + 1] : call_profile_.size();
        return static_cast<std::uint32_t>(end - lane_first_call_[lane]);
    }

    std::vector<std::uint32_t> wave_first_lane_;
    std::vector<std::uint32_t> lane_counts_;      // kLaneEvents per lane
    std::vector<std::uint32_t> lane_first_call_;
    std::vector<CallProfiles::Id> call_profile_;
    CallProfiles profiles_;
};

}  // namespace rtc
