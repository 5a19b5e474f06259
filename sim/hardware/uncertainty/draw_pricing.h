// Pricing each warp wave under the N cost models drawn from one preset's
// uncertainty (cost_uncertainty.h) at once. Calling price_wave N times per
// wave made the quickstart 45 % slower with 64 draws; here the events whose
// cost no draw changes are summed once per lane, the changed ones (a few)
// are applied to all draws in loops over draws the compiler vectorizes, and
// the program rounds are priced once when no draw changes a program cost.
// Same formulas as price_wave (execution_model.h); only the summation order
// of a lane's events differs (unchanged events first).
#pragma once

#include "sim/hardware/warp_pricing.h"

#include <cstdint>
#include <vector>

namespace rtc {

// A preset and the models drawn from it (same execution model, other costs).
struct DrawSet {
    const CostModel* base = nullptr;
    std::vector<const CostModel*> draws;
};

// One per thread and draw set while tracing (it caches per-profile prices).
class WaveDrawPricer {
public:
    explicit WaveDrawPricer(const DrawSet& set);
    // Adds the wave's price under draw d to totals[d], d < set.draws.size().
    void add(const WaveWork& wave, WarpTotals* totals);

private:
    struct Unit {
        std::vector<std::uint8_t> fixed;    // events no draw changes: priced with the base
        std::vector<std::uint8_t> changed;  // events some draw changes
        std::vector<double> cost;           // [k * D + d]: changed event k under draw d
    };
    void prepare_profiles(const CallProfiles& table);

    const DrawSet* set_;
    std::size_t n_ = 0;  // draws
    Unit shader_, rt_;
    std::vector<double> handoff_;       // per draw: the cost of one hand-off
    bool programs_change_ = false;
    ProgramPrices base_prices_;         // programs priced once when no draw changes them
    std::vector<double> profile_price_; // [id * D + d] when programs change
    // Scratch, per draw.
    std::vector<double> lane_, shader_max_, rt_max_, rt_sum_, worst_;
};

}  // namespace rtc
