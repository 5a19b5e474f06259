// A compact record of every wave of a traced frame, so a frame traced once
// can be re-priced under the warp model with other costs (calibration, cost
// sweeps) without tracing again. Lanes keep their full event counts; program
// calls are stored as indices into a table of distinct call profiles (most
// calls of a frame share a handful of profiles: a capsule miss, a capsule
// hit, a phantom call with k iterations, ...).
#pragma once

#include "sim/hardware/warp_pricing.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rtc {

class WarpTrace {
public:
    void append(const WaveWork& wave);
    // Appends `other` (its waves after ours), remapping its profiles.
    void append(const WarpTrace& other);

    [[nodiscard]] std::size_t waves() const { return wave_first_lane_.size(); }
    [[nodiscard]] std::size_t lanes() const { return lane_counts_.size(); }
    [[nodiscard]] std::size_t calls() const { return call_profile_.size(); }
    [[nodiscard]] std::size_t profiles() const { return profiles_.size(); }
    [[nodiscard]] std::size_t memory_bytes() const;

    // Cycles of every wave under `model` (its execution parameters and
    // costs), and the effective counts that reproduce them linearly.
    [[nodiscard]] WarpTotals price(const CostModel& model, EffectiveCounts* effective = nullptr) const;

private:
    std::uint32_t profile_id(const RayCounts& c);

    std::vector<std::uint32_t> wave_first_lane_;
    std::vector<RayCounts> lane_counts_;
    std::vector<std::uint32_t> lane_first_call_;
    std::vector<std::uint32_t> call_profile_;
    std::vector<RayCounts> profiles_;
    std::unordered_multimap<std::uint64_t, std::uint32_t> profile_index_;  // hash -> id
};

}  // namespace rtc
