// Pricing each warp wave under the N cost models drawn from one preset's
// uncertainty (cost_uncertainty.h) at once. Calling price_wave N times per
// wave made the quickstart 45 % slower with 64 draws. Here, per unit (shader,
// RT), the events no draw changes are summed once per lane; a lane whose
// counts of the changed events and fixed sum are all <= another lane's can
// never be the slowest under any draw (costs are >= 0), so only the few
// undominated lanes are priced per draw, and the lanes' sum comes from the
// summed counts. Program rounds are priced once when no draw changes a
// program cost, else per distinct call profile of each round. (Pruning lanes
// by bounds over the draws instead of dominance priced more lanes: the
// draws' spread is wider than the lanes'.) Same formulas as price_wave (execution_model.h); only the
// summation order differs (unchanged events first).
#pragma once

#include "sim/hardware/warp_pricing.h"

#include <array>
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
    // lane_by_lane: the rows compared one double at a time, as the reference
    // the AVX2 path is tested against (it is used anyway past 7 changed events).
    explicit WaveDrawPricer(const DrawSet& set, bool lane_by_lane = false);
    // Adds the wave's price under draw d to totals[d], d < set.draws.size().
    void add(const WaveWork& wave, WarpTotals* totals);

private:
    struct Unit {
        std::vector<std::uint8_t> fixed;    // events no draw changes: priced with the base
        std::vector<std::uint8_t> changed;  // events some draw changes
        std::vector<double> cost;           // [k * D + d]: changed event k under draw d
        std::array<std::int32_t, 8> gather_index{}, gather_use{};  // undominated_rows_8's gather
    };
    void prepare_profiles(const CallProfiles& table);

    const DrawSet* set_;
    std::size_t n_ = 0;  // draws
    bool lane_by_lane_ = false;
    Unit shader_, rt_, loop_;  // loop_: the preset's lockstep events (ExecutionModel)
    std::vector<double> handoff_;       // per draw: the cost of one hand-off
    bool programs_change_ = false;
    ProgramPrices base_prices_;         // programs priced once when no draw changes them
    std::vector<double> profile_price_; // [id * D + d] when programs change
    // max (slowest lane) and, unless null, sum over the wave's lanes of unit u, per draw.
    void unit_prices(const WaveWork& wave, const Unit& u, double* max, double* sum);
    // Into cand_: the rows (fixed sum, then the changed counts) of the lanes
    // no other lane covers, in lane order; into counts_: the rows' sum.
    void undominated_rows(const WaveWork& wave, const Unit& u);
    void undominated_rows_8(const WaveWork& wave, const Unit& u);  // the same, rows of <= 8 (AVX2)
    struct alignas(32) Row8 {
        double v[8];
    };
    std::vector<Row8> rows_;
    // Scratch: per draw; the undominated lanes (fixed sum, then the changed counts).
    std::vector<double> shader_max_, loop_max_, rt_max_, rt_sum_, lane_, worst_, cand_, counts_;
};

}  // namespace rtc
