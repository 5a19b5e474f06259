#include "sim/hardware/uncertainty/draw_pricing.h"

#include <algorithm>
#include <array>
#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace rtc {

namespace {

template <class InUnit>
void split_unit(InUnit in_unit, const DrawSet& set, std::vector<std::uint8_t>& fixed,
                std::vector<std::uint8_t>& changed, std::vector<double>& cost) {
    const std::size_t n = set.draws.size();
    for (std::size_t e = 0; e < kEventCount; ++e) {
        if (!in_unit(static_cast<Event>(e))) continue;
        const bool differs = std::any_of(set.draws.begin(), set.draws.end(),
                                         [&](const CostModel* m) { return m->cycles[e] != set.base->cycles[e]; });
        (differs ? changed : fixed).push_back(static_cast<std::uint8_t>(e));
        if (!differs) continue;
        for (std::size_t d = 0; d < n; ++d) cost.push_back(set.draws[d]->cycles[e]);
    }
}

}  // namespace

WaveDrawPricer::WaveDrawPricer(const DrawSet& set, bool lane_by_lane)
    : set_(&set), n_(set.draws.size()), lane_by_lane_(lane_by_lane) {
    // As price_wave: a machine's lockstep events (its shader traversal loop)
    // leave the RT unit and are priced at the wave's slowest lane.
    const ExecutionModel& machine = set.base->execution;
    const auto in = [&](EventUnit u) { return [&machine, u](Event e) { return machine.unit(e) == u; }; };
    split_unit(in(EventUnit::Shader), set, shader_.fixed, shader_.changed, shader_.cost);
    split_unit(in(EventUnit::RtUnit), set, rt_.fixed, rt_.changed, rt_.cost);
    split_unit(in(EventUnit::Lockstep), set, loop_.fixed, loop_.changed, loop_.cost);
    // undominated_rows_8's gather: changed event k into lane k + 1; lane 0
    // (the fixed sum) and lanes past the changed events gather nothing.
    for (Unit* u : {&shader_, &rt_, &loop_})
        for (std::size_t k = 0; k < u->changed.size() && k + 1 < u->gather_index.size(); ++k) {
            u->gather_index[k + 1] = u->changed[k];
            u->gather_use[k + 1] = -1;
        }
    for (const CostModel* m : set.draws) {
        double h = 0.0;
        for (std::size_t e = 0; e < kEventCount; ++e)
            if (kEventUnits[e] == EventUnit::HandOff) h += m->cycles[e];
        handoff_.push_back(h);
        for (std::size_t k = 0; k < kProgramEventCount; ++k)
            programs_change_ = programs_change_ || m->cycles[kProgramEvents[k]] != set.base->cycles[kProgramEvents[k]];
    }
    for (std::vector<double>* v : {&shader_max_, &loop_max_, &rt_max_, &rt_sum_, &lane_}) v->assign(n_, 0.0);
}

// Each lane's row (fixed sum, then its counts of the changed events) and the
// undominated rows among them, in cand_ (stride doubles per row), and the
// rows' sum over the wave in counts_.
void WaveDrawPricer::undominated_rows(const WaveWork& wave, const Unit& u) {
    const CostModel& base = *set_->base;
    const std::size_t k_count = u.changed.size(), stride = k_count + 1;
    cand_.clear();
    counts_.assign(stride, 0.0);  // the wave's sums: fixed, then each changed event
    double row[kEventCount + 1];  // one lane: fixed sum, then its changed counts
    for (const LaneWork& l : wave.lanes) {
        row[0] = 0.0;
        for (const std::uint8_t e : u.fixed) row[0] += static_cast<double>(l.counts.n[e]) * base.cycles[e];
        for (std::size_t k = 0; k < k_count; ++k) row[k + 1] = static_cast<double>(l.counts.n[u.changed[k]]);
        for (std::size_t k = 0; k < stride; ++k) counts_[k] += row[k];
        const auto covers = [&](const double* a, const double* b) {  // a >= b everywhere
            for (std::size_t k = 0; k < stride; ++k)
                if (a[k] < b[k]) return false;
            return true;
        };
        bool dominated = false;
        for (std::size_t c = 0; c < cand_.size() && !dominated; c += stride) dominated = covers(&cand_[c], row);
        if (dominated) continue;
        for (std::size_t c = 0; c < cand_.size();)  // drop the candidates this lane covers
            if (covers(row, &cand_[c])) cand_.erase(cand_.begin() + static_cast<std::ptrdiff_t>(c),
                                                     cand_.begin() + static_cast<std::ptrdiff_t>(c + stride));
            else c += stride;
        cand_.insert(cand_.end(), row, row + stride);
    }
}

#if defined(__AVX2__)
// undominated_rows() for rows of at most 8 doubles, two AVX registers each:
// the counts gathered in one instruction and rows compared whole. The same
// rows (the fixed sum added in the same order), sums and candidates in the
// same order: only the instructions differ (the head frame's traces at 200 x
// 200 x 1: 38.8 M -> 24.4 M instructions for the rows and their prices, 3.4 %
// of all).
void WaveDrawPricer::undominated_rows_8(const WaveWork& wave, const Unit& u) {
    const CostModel& base = *set_->base;
    const std::size_t k_count = u.changed.size(), stride = k_count + 1;
    const __m256i idx = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(u.gather_index.data()));
    const __m256i mask = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(u.gather_use.data()));
    rows_.clear();
    __m256d sum_lo = _mm256_setzero_pd(), sum_hi = _mm256_setzero_pd();
    const auto covers = [](__m256d a_lo, __m256d a_hi, __m256d b_lo, __m256d b_hi) {  // a >= b everywhere
        const __m256d lt = _mm256_or_pd(_mm256_cmp_pd(a_lo, b_lo, _CMP_LT_OQ), _mm256_cmp_pd(a_hi, b_hi, _CMP_LT_OQ));
        return _mm256_movemask_pd(lt) == 0;
    };
    const auto lo_of = [](const Row8& r) { return _mm256_load_pd(r.v); };
    const auto hi_of = [](const Row8& r) { return _mm256_load_pd(r.v + 4); };
    for (const LaneWork& l : wave.lanes) {
        double fixed = 0.0;
        for (const std::uint8_t e : u.fixed) fixed += static_cast<double>(l.counts.n[e]) * base.cycles[e];
        const __m256i counts = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(),
                                                           reinterpret_cast<const int*>(l.counts.n.data()), idx,
                                                           mask, 4);
        // [fixed sum, changed 0..2] and [changed 3..6]. Unsigned counts
        // converted exactly: as signed after flipping the top bit, plus 2^31.
        const __m256i flipped = _mm256_xor_si256(counts, _mm256_set1_epi32(INT32_MIN));
        const __m256d top = _mm256_set1_pd(2147483648.0);
        const __m256d lo = _mm256_blend_pd(
            _mm256_add_pd(_mm256_cvtepi32_pd(_mm256_castsi256_si128(flipped)), top), _mm256_set1_pd(fixed), 1);
        const __m256d hi = _mm256_add_pd(_mm256_cvtepi32_pd(_mm256_extracti128_si256(flipped, 1)), top);
        sum_lo = _mm256_add_pd(sum_lo, lo);
        sum_hi = _mm256_add_pd(sum_hi, hi);
        bool dominated = false;
        for (std::size_t c = 0; c < rows_.size() && !dominated; ++c)
            dominated = covers(lo_of(rows_[c]), hi_of(rows_[c]), lo, hi);
        if (dominated) continue;
        std::size_t kept = 0;  // drop the candidates this lane covers, keeping the others' order
        for (std::size_t c = 0; c < rows_.size(); ++c)
            if (!covers(lo, hi, lo_of(rows_[c]), hi_of(rows_[c]))) rows_[kept++] = rows_[c];
        rows_.resize(kept);
        Row8& row = rows_.emplace_back();
        _mm256_store_pd(row.v, lo);
        _mm256_store_pd(row.v + 4, hi);
    }
    alignas(32) double sums[8];
    _mm256_store_pd(sums, sum_lo);
    _mm256_store_pd(sums + 4, sum_hi);
    counts_.assign(sums, sums + stride);
    cand_.resize(rows_.size() * stride);
    for (std::size_t c = 0; c < rows_.size(); ++c)
        std::copy(rows_[c].v, rows_[c].v + stride, cand_.begin() + static_cast<std::ptrdiff_t>(c * stride));
}
#endif

void WaveDrawPricer::unit_prices(const WaveWork& wave, const Unit& u, double* max, double* sum) {
    const std::size_t n = n_, k_count = u.changed.size(), stride = k_count + 1;
#if defined(__AVX2__)
    if (stride <= 8 && !lane_by_lane_) undominated_rows_8(wave, u);
    else undominated_rows(wave, u);
#else
    undominated_rows(wave, u);
#endif
    if (sum) {  // over all lanes: linear in the summed counts
        for (std::size_t d = 0; d < n; ++d) sum[d] = counts_[0];
        for (std::size_t k = 0; k < k_count; ++k) {
            const double* cost = u.cost.data() + k * n;
            for (std::size_t d = 0; d < n; ++d) sum[d] += counts_[k + 1] * cost[d];
        }
    }
    for (std::size_t c = 0; c < cand_.size(); c += stride) {
        const double* lane_c = &cand_[c];
        double* const w = lane_.data();  // this lane under every draw
        for (std::size_t d = 0; d < n; ++d) w[d] = lane_c[0];
        for (std::size_t k = 0; k < k_count; ++k) {
            const double* cost = u.cost.data() + k * n;
            for (std::size_t d = 0; d < n; ++d) w[d] += lane_c[k + 1] * cost[d];
        }
        for (std::size_t d = 0; d < n; ++d) max[d] = std::max(max[d], w[d]);
    }
}

void WaveDrawPricer::prepare_profiles(const CallProfiles& table) {
    for (std::size_t id = profile_price_.size() / std::max<std::size_t>(n_, 1); id < table.size(); ++id)
        for (std::size_t d = 0; d < n_; ++d)
            profile_price_.push_back(program_price(table[static_cast<CallProfiles::Id>(id)], *set_->draws[d]));
}

void WaveDrawPricer::add(const WaveWork& wave, WarpTotals* totals) {
    if (wave.lanes.empty() || n_ == 0) return;
    const CostModel& base = *set_->base;
    const std::size_t n = n_;
    std::fill(shader_max_.begin(), shader_max_.end(), 0.0);  // price_wave: max(0, lanes)
    std::fill(rt_max_.begin(), rt_max_.end(), -1.0);
    unit_prices(wave, shader_, shader_max_.data(), nullptr);
    if (!loop_.fixed.empty() || !loop_.changed.empty()) {
        std::fill(loop_max_.begin(), loop_max_.end(), 0.0);
        unit_prices(wave, loop_, loop_max_.data(), nullptr);
        for (std::size_t d = 0; d < n; ++d) shader_max_[d] += loop_max_[d];
    }
    unit_prices(wave, rt_, rt_max_.data(), rt_sum_.data());
    std::uint32_t max_calls = 0;
    for (const LaneWork& l : wave.lanes) max_calls = std::max(max_calls, l.calls);
    // Program rounds: the most expensive active call of each round.
    double programs = 0.0;
    if (!programs_change_) {
        worst_.assign(max_calls, -1.0);
        const double* price = base_prices_.all(*wave.profiles, base);
        for (const LaneWork& l : wave.lanes)
            for (std::uint32_t r = 0; r < l.calls; ++r)
                worst_[r] = std::max(worst_[r], price[wave.calls[l.first_call + r]]);
        for (double w : worst_) programs += w;
    } else {
        // Per draw; a round's lanes mostly call a few distinct profiles (a
        // capsule miss, a hit), so the max over draws is taken per distinct one.
        prepare_profiles(*wave.profiles);
        worst_.assign(n, 0.0);
        std::array<CallProfiles::Id, 64> ids{};  // warp_width <= 64 lanes
        for (std::uint32_t r = 0; r < max_calls; ++r) {
            std::size_t distinct = 0;
            for (const LaneWork& l : wave.lanes) {
                if (l.calls <= r) continue;
                const CallProfiles::Id id = wave.calls[l.first_call + r];
                if (std::find(ids.begin(), ids.begin() + static_cast<std::ptrdiff_t>(distinct), id) ==
                    ids.begin() + static_cast<std::ptrdiff_t>(distinct) && distinct < ids.size())
                    ids[distinct++] = id;
            }
            double* const round = lane_.data();
            std::fill(round, round + n, -1.0);
            for (std::size_t i = 0; i < distinct; ++i) {
                const double* price = profile_price_.data() + static_cast<std::size_t>(ids[i]) * n;
                for (std::size_t d = 0; d < n; ++d) round[d] = std::max(round[d], price[d]);
            }
            for (std::size_t d = 0; d < n; ++d) worst_[d] += round[d];
        }
    }
    // Only the cycles: a draw's waves, lanes and rounds are its preset's.
    const double parallel = std::max(1.0, base.execution.rt_parallel_lanes);
    for (std::size_t d = 0; d < n; ++d) {
        WarpTotals& t = totals[d];
        t.shader += shader_max_[d];
        t.rt += std::max(rt_max_[d], rt_sum_[d] / parallel);
        t.rt_lane_sum += rt_sum_[d];
        t.handoff += static_cast<double>(max_calls) * handoff_[d];
        t.programs += programs_change_ ? worst_[d] : programs;
    }
}

}  // namespace rtc
