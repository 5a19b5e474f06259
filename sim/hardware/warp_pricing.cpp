#include "sim/hardware/warp_pricing.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace rtc {

namespace {

// The events of each unit, as index lists (no per-event branch when pricing).
constexpr auto kShaderEvents = events_of_unit<EventUnit::Shader>();
constexpr auto kRtEvents = events_of_unit<EventUnit::RtUnit>();
constexpr auto kHandOffEvents = events_of_unit<EventUnit::HandOff>();

template <class List>
double price_of(const RayCounts& c, const CostModel& m, const List& events) {
    double s = 0.0;
    for (const std::uint8_t e : events) s += static_cast<double>(c.n[e]) * m.cycles[e];
    return s;
}

template <class List>
void add_counts(EffectiveCounts& eff, const RayCounts& c, const List& events, double scale) {
    for (const std::uint8_t e : events) eff[e] += scale * static_cast<double>(c.n[e]);
}

// price_of(lane counts, events) of lanes [i, i + 4), each lane's sum in the
// same order (mul, then add: the same doubles), four lanes per instruction;
// the counts are gathered from the lanes' records.
#if defined(__AVX2__)
template <class List>
__m256d price_of_4(const LaneWork* lanes, const CostModel& m, const List& events) {
    static_assert(sizeof(LaneWork) % sizeof(std::uint32_t) == 0);
    constexpr int kStride = sizeof(LaneWork) / sizeof(std::uint32_t);
    const __m128i index = _mm_setr_epi32(0, kStride, 2 * kStride, 3 * kStride);
    const __m128i sign = _mm_set1_epi32(static_cast<int>(0x80000000u));
    const __m256d two31 = _mm256_set1_pd(2147483648.0);
    __m256d s = _mm256_setzero_pd();
    for (const std::uint8_t e : events) {
        const __m128i c = _mm_i32gather_epi32(reinterpret_cast<const int*>(lanes->counts.n.data() + e), index, 4);
        // Unsigned to double, exactly: (c - 2^31) as a signed int, + 2^31.
        const __m256d d = _mm256_add_pd(_mm256_cvtepi32_pd(_mm_xor_si128(c, sign)), two31);
        s = _mm256_add_pd(s, _mm256_mul_pd(d, _mm256_set1_pd(m.cycles[e])));
    }
    return s;
}
#endif

// The shader and RT-unit price (without lockstep events) of every lane from
// `i` on.
void lane_prices(const WaveWork& wave, const CostModel& m, double* shader, double* rt, std::size_t i) {
    const std::size_t n = wave.lanes.size();
#if defined(__AVX2__)
    for (; i + 4 <= n; i += 4) {
        _mm256_storeu_pd(shader + i, price_of_4(&wave.lanes[i], m, kShaderEvents));
        _mm256_storeu_pd(rt + i, price_of_4(&wave.lanes[i], m, kRtEvents));
    }
#endif
    for (; i < n; ++i) {
        shader[i] = price_of(wave.lanes[i].counts, m, kShaderEvents);
        rt[i] = price_of(wave.lanes[i].counts, m, kRtEvents);
    }
}

// For lanes [0, i), four at a time, with i returned (a multiple of 4): the
// most expensive lane's shader price and RT price (into `shader_max` and
// `rt_max`, which start at 0 and -1), the sum of their RT prices in lane
// order (the same doubles as the lane-by-lane loop: a max of the same values,
// and the same additions in the same order), and the most calls of a lane.
std::size_t lane_maxima(const WaveWork& wave, const CostModel& m, double& shader_max, double& rt_max,
                        double& rt_sum, std::uint32_t& max_calls) {
    std::size_t i = 0;
#if defined(__AVX2__)
    const std::size_t n = wave.lanes.size();
    if (n < 4) return 0;
    static_assert(sizeof(LaneWork) % sizeof(std::uint32_t) == 0 && offsetof(LaneWork, calls) % 4 == 0);
    constexpr int kStride = sizeof(LaneWork) / sizeof(std::uint32_t);
    const __m128i index = _mm_setr_epi32(0, kStride, 2 * kStride, 3 * kStride);
    __m256d s_max = _mm256_set1_pd(shader_max), r_max = _mm256_set1_pd(rt_max);
    __m128i calls_max = _mm_setzero_si128();
    double sum = rt_sum;
    for (; i + 4 <= n; i += 4) {
        const LaneWork* l = &wave.lanes[i];
        s_max = _mm256_max_pd(s_max, price_of_4(l, m, kShaderEvents));
        const __m256d r = price_of_4(l, m, kRtEvents);
        r_max = _mm256_max_pd(r_max, r);
        alignas(32) double lane_rt[4];
        _mm256_store_pd(lane_rt, r);
        sum = (((sum + lane_rt[0]) + lane_rt[1]) + lane_rt[2]) + lane_rt[3];
        calls_max = _mm_max_epu32(calls_max, _mm_i32gather_epi32(reinterpret_cast<const int*>(&l->calls), index, 4));
    }
    alignas(32) double s4[4], r4[4];
    _mm256_store_pd(s4, s_max);
    _mm256_store_pd(r4, r_max);
    alignas(16) std::uint32_t c4[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(c4), calls_max);
    for (int k = 0; k < 4; ++k) {
        shader_max = std::max(shader_max, s4[k]);
        rt_max = std::max(rt_max, r4[k]);
        max_calls = std::max(max_calls, c4[k]);
    }
    rt_sum = sum;
#else
    (void)wave, (void)m, (void)shader_max, (void)rt_max, (void)rt_sum, (void)max_calls;
#endif
    return i;
}

// w[r] = max(w[r], price[call[r]]) for rounds r = `r`, r + 1, ... while four
// fit in `calls`, four rounds per instruction; leaves `r` at the first round
// not done. Only the maxima: without effective counts nobody asks which call
// was the most expensive. The same doubles as the scalar loop (a max of the
// same values; prices are finite).
void round_maxima(const CallProfiles::Id* call, std::uint32_t calls, const double* price, double* w,
                  std::uint32_t& r) {
#if defined(__AVX2__)
    static_assert(sizeof(CallProfiles::Id) == 2);
    for (; r + 4 <= calls; r += 4) {
        const __m128i ids = _mm_cvtepu16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(call + r)));
        // The masked form: the plain one leaves its pass-through operand
        // undefined, which GCC 12 reports as maybe-uninitialized.
        const __m256d c = _mm256_mask_i32gather_pd(_mm256_setzero_pd(), price, ids,
                                                   _mm256_castsi256_pd(_mm256_set1_epi64x(-1)), 8);
        _mm256_storeu_pd(w + r, _mm256_max_pd(_mm256_loadu_pd(w + r), c));
    }
#else
    (void)call, (void)calls, (void)price, (void)w, (void)r;
#endif
}

}  // namespace

double program_price(const ProgramCounts& call, const CostModel& m) {
    double s = 0.0;
    for (std::size_t k = 0; k < kProgramEventCount; ++k) s += static_cast<double>(call.n[k]) * m.cycles[kProgramEvents[k]];
    return s;
}

void add_program_counts(EffectiveCounts& eff, const ProgramCounts& call) {
    for (std::size_t k = 0; k < kProgramEventCount; ++k) eff[kProgramEvents[k]] += call.n[k];
}

void add_rt_lane_counts(EffectiveCounts& counts, const WaveWork& wave, const CostModel& m) {
    for (const LaneWork& l : wave.lanes) add_counts(counts, l.counts, kRtEvents, 1.0);
    for (const Event e : m.execution.lockstep_events())
        for (const LaneWork& l : wave.lanes) counts[static_cast<std::size_t>(e)] -= static_cast<double>(l.counts[e]);
}

void ProgramPrices::extend(const CallProfiles& table, CallProfiles::Id id, const CostModel& m) {
    while (price_.size() <= id) price_.push_back(program_price(table[static_cast<CallProfiles::Id>(price_.size())], m));
}

namespace {

// kLanesAtOnce: the lanes' shader and RT prices first, several lanes per
// instruction (lane_prices); the reference prices lane by lane. Both give
// the same doubles (tests/execution/test_warp_execution.cpp).
template <bool kLanesAtOnce>
WavePrice price_wave_impl(const WaveWork& wave, const CostModel& m, ProgramPrices& prices, EffectiveCounts* eff) {
    WavePrice p;
    if (wave.lanes.empty()) return p;
    // Shader work in lockstep: the wave pays its most expensive lane once.
    std::size_t shader_lane = 0, rt_lane = 0, loop_lane = 0;
    double rt_max = -1.0, loop_max = 0.0;
    std::uint32_t max_calls = 0;
    // RT-unit events the machine runs as shader code (AMD's traversal loop):
    // in lockstep, so the wave pays its slowest lane's loop, outside the unit.
    const std::vector<Event>& loop = m.execution.lockstep_events();
    thread_local std::vector<double> lane_shader, lane_rt;
    std::size_t i = 0;
    if constexpr (kLanesAtOnce) {
        // Nobody asks which lane was the slowest: the lanes' maxima and
        // sums four lanes at a time, straight from their prices.
        if (!eff && loop.empty()) i = lane_maxima(wave, m, p.shader, rt_max, p.rt_lane_sum, max_calls);
        lane_shader.resize(wave.lanes.size());
        lane_rt.resize(wave.lanes.size());
        lane_prices(wave, m, lane_shader.data(), lane_rt.data(), i);
    }
    for (; i < wave.lanes.size(); ++i) {
        const LaneWork& l = wave.lanes[i];
        const double s = kLanesAtOnce ? lane_shader[i] : price_of(l.counts, m, kShaderEvents);
        if (s > p.shader) p.shader = s, shader_lane = i;
        double r = kLanesAtOnce ? lane_rt[i] : price_of(l.counts, m, kRtEvents);
        if (!loop.empty()) {
            double in_loop = 0.0;
            for (const Event e : loop) in_loop += static_cast<double>(l.counts[e]) * m[e];
            r -= in_loop;
            if (in_loop > loop_max) loop_max = in_loop, loop_lane = i;
        }
        p.rt_lane_sum += r;
        if (r > rt_max) rt_max = r, rt_lane = i;
        max_calls = std::max(max_calls, l.calls);
    }
    p.shader += loop_max;
    // RT unit: P lanes overlap; never faster than the slowest lane.
    const double parallel = std::max(1.0, m.execution.rt_parallel_lanes);
    const bool slowest_lane_bounds = rt_max >= p.rt_lane_sum / parallel;
    p.rt = slowest_lane_bounds ? rt_max : p.rt_lane_sum / parallel;
    // Program rounds: one hand-off each, then the most expensive active call.
    p.rounds = max_calls;
    double handoff_cost = 0.0;
    for (const std::uint8_t e : kHandOffEvents) handoff_cost += m.cycles[e];
    p.handoff = static_cast<double>(max_calls) * handoff_cost;
    // Lanes outer, rounds inner: work in proportion to the calls, not rounds x lanes.
    thread_local std::vector<double> worst;
    thread_local std::vector<CallProfiles::Id> worst_call;
    worst.assign(max_calls, -1.0);
    worst_call.assign(max_calls, 0);
    // Every profile priced up front, so that the loop over calls (the model's
    // hot spot: one pass per call of the frame) is loads and compares through
    // plain pointers the stores cannot alias.
    const double* price = prices.all(*wave.profiles, m);
    double* const w = worst.data();
    CallProfiles::Id* const wc = worst_call.data();
    for (const LaneWork& l : wave.lanes) {
        if (l.calls == 0) continue;
        p.active_lane_rounds += l.calls;
        const CallProfiles::Id* call = wave.calls.data() + l.first_call;
        std::uint32_t r = 0;
        if (kLanesAtOnce && !eff) round_maxima(call, l.calls, price, w, r);
        for (; r < l.calls; ++r) {
            const double c = price[call[r]];
            if (c > w[r]) w[r] = c, wc[r] = call[r];
        }
    }
    for (std::uint32_t r = 0; r < max_calls; ++r) {
        p.programs += worst[r];
        if (eff) add_program_counts(*eff, (*wave.profiles)[worst_call[r]]);
    }
    if (eff) {
        add_counts(*eff, wave.lanes[shader_lane].counts, kShaderEvents, 1.0);
        if (slowest_lane_bounds) {
            add_counts(*eff, wave.lanes[rt_lane].counts, kRtEvents, 1.0);
        } else {
            for (const LaneWork& l : wave.lanes) add_counts(*eff, l.counts, kRtEvents, 1.0 / parallel);
        }
        // The loop's events were priced at its slowest lane, not in the unit.
        for (const Event e : loop) {
            const auto i = static_cast<std::size_t>(e);
            if (slowest_lane_bounds) {
                (*eff)[i] -= static_cast<double>(wave.lanes[rt_lane].counts[e]);
            } else {
                for (const LaneWork& l : wave.lanes) (*eff)[i] -= static_cast<double>(l.counts[e]) / parallel;
            }
            (*eff)[i] += static_cast<double>(wave.lanes[loop_lane].counts[e]);
        }
        for (const std::uint8_t e : kHandOffEvents) (*eff)[e] += max_calls;
    }
    return p;
}

}  // namespace

WavePrice price_wave(const WaveWork& wave, const CostModel& m, ProgramPrices& prices, EffectiveCounts* eff) {
    return price_wave_impl<true>(wave, m, prices, eff);
}

WavePrice price_wave_reference(const WaveWork& wave, const CostModel& m, ProgramPrices& prices,
                               EffectiveCounts* eff) {
    return price_wave_impl<false>(wave, m, prices, eff);
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

namespace {

// Events priced as the SM's own instructions (shading and program rounds):
// issue cycles, which a lone warp waits latency_per_issue times over.
bool sm_code(std::size_t e) {
    return kEventUnits[e] == EventUnit::Program || kEventUnits[e] == EventUnit::Shader;
}

}  // namespace

const char* bound_name(FrameTerms::Bound b) {
    switch (b) {
        case FrameTerms::Bound::Sum: return "sum";
        case FrameTerms::Bound::Latency: return "latency";
        case FrameTerms::Bound::Issue: return "issue";
        case FrameTerms::Bound::RtUnit: return "rt_unit";
    }
    return "sum";
}

FrameTerms WarpTotals::terms(const Roofline& roof) const {
    FrameTerms t;
    if (!roof.enabled) {
        t.cycles = lone_wave_cycles();
        return t;
    }
    // The SM's own code (shading, program rounds) is priced at issue cost;
    // a lone warp waits latency_per_issue times that. The waves' latencies
    // are hidden by the resident warps.
    t.latency = (roof.latency_per_issue * (shader + programs) + rt + handoff) / roof.warps;
    t.issue = shader + programs;
    t.rt_unit = rt_lane_sum / roof.rt_unit_lanes;
    t.cycles = t.latency, t.bound = FrameTerms::Bound::Latency;
    if (t.issue > t.cycles) t.cycles = t.issue, t.bound = FrameTerms::Bound::Issue;
    if (t.rt_unit > t.cycles) t.cycles = t.rt_unit, t.bound = FrameTerms::Bound::RtUnit;
    return t;
}

void roofline_counts(const WarpTotals& totals, const Roofline& roof, EffectiveCounts& waves,
                     const EffectiveCounts& rt_lanes, const ExecutionModel& machine) {
    const auto code = [&](std::size_t e) {
        return sm_code(e) || machine.unit(static_cast<Event>(e)) == EventUnit::Lockstep;
    };
    switch (totals.terms(roof).bound) {
        case FrameTerms::Bound::Sum: return;
        case FrameTerms::Bound::Latency:
            for (std::size_t e = 0; e < kEventCount; ++e)
                waves[e] *= (code(e) ? roof.latency_per_issue : 1.0) / roof.warps;
            return;
        case FrameTerms::Bound::Issue:
            for (std::size_t e = 0; e < kEventCount; ++e)
                if (!code(e)) waves[e] = 0.0;
            return;
        case FrameTerms::Bound::RtUnit:
            for (std::size_t e = 0; e < kEventCount; ++e) waves[e] = rt_lanes[e] / roof.rt_unit_lanes;
            return;
    }
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
