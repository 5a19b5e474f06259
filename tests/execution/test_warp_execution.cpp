// The SIMT execution model: a wave priced by hand; frames traced in warps
// count exactly what the per-ray model counts and hit the same primitives;
// the wave records re-price to the figures computed while tracing; effective
// counts reproduce the cycles linearly; nothing depends on the thread count;
// lanes priced several at once give the lane-by-lane reference's doubles;
// each program call's recorded counts are its own events.
#include "scenes/generators/bundle.h"
#include "sim/hardware/leaf_programs.h"
#include "sim/hardware/warp_trace.h"
#include "sim/methods/method.h"
#include "sim/workload/camera.h"

#include "warp_test_util.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <variant>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

CostModel test_model(double rt_parallel) {
    CostModel m;
    m.name = "test";
    for (std::size_t e = 0; e < kEventCount; ++e) m.cycles[e] = 1.0 + static_cast<double>(e);
    m[Event::Ray] = 100;
    m[Event::BlasBoxTest] = 2;
    m[Event::ContextSwitch] = 50;
    m[Event::IsCall] = 0;
    m[Event::IsCapsule] = 10;
    m[Event::ReportedHit] = 5;
    m.execution.kind = ExecutionKind::Warp;
    m.execution.rt_parallel_lanes = rt_parallel;
    return m;
}

RayCounts counts_of(std::initializer_list<std::pair<Event, std::uint32_t>> l) {
    RayCounts c;
    for (const auto& [e, n] : l) c.n[static_cast<std::size_t>(e)] = n;
    return c;
}

ProgramCounts call_of(std::initializer_list<Event> events) {
    ProgramCounts c;
    for (const Event e : events) ++c.n[kProgramSlot[static_cast<std::size_t>(e)]];
    return c;
}

struct TestFrame {
    Geometry geometry;
    RayWorkload workload;
};

// A bundle tilted 30 degrees, framed by the camera; phantom curves at 2
// subdivisions.
TestFrame tilted_bundle(int width, int height, PrimitiveKind kind = PrimitiveKind::Capsule, std::uint32_t count = 200,
                        float radius = 0.004f) {
    BundleDesc d;
    d.count = count;
    d.radius = radius;
    d.tilt_deg = 30.0f;
    TestFrame f;
    f.geometry = make_geometry(make_bundle(d), kind, kind == PrimitiveKind::Phantom ? 2 : 1);
    f.workload.camera = auto_frame(geometry_bounds(f.geometry), 45.0f, width, height);
    f.workload.path.spp = 2;
    f.workload.path.bounces = 2;
    return f;
}

FrameResult run(const BuiltMethod& m, const TestFrame& f, const ExecutionModel* warp,
                std::vector<const CostModel*> presets, unsigned threads, bool record = false) {
    FrameOptions o;
    o.threads = threads;
    o.progress = false;
    o.record_hits = true;
    o.warp = warp;
    o.warp_presets = std::move(presets);
    o.record_warps = record;
    return m.run(f.geometry, f.workload, TraceOptions{}, o);
}

}  // namespace

TEST_CASE("warp pricing: a two-lane wave by hand") {
    const CostModel m = test_model(/*rt_parallel=*/1.0);  // RT work sums over lanes
    WaveWork w;
    // Lane 0: 10 BLAS box tests, two calls (a miss, then a hit); lane 1: 4 box tests, one miss.
    w.lanes.push_back({counts_of({{Event::Ray, 1}, {Event::BlasBoxTest, 10}, {Event::ContextSwitch, 2}}), 0, 2, 0});
    w.lanes.push_back({counts_of({{Event::Ray, 1}, {Event::BlasBoxTest, 4}, {Event::ContextSwitch, 1}}), 2, 1, 1});
    const ProgramCounts miss = call_of({Event::IsCall, Event::IsCapsule});
    const ProgramCounts hit = call_of({Event::IsCall, Event::IsCapsule, Event::ReportedHit});
    CHECK(hit[Event::ReportedHit] == 1);
    CHECK(hit[Event::BlasBoxTest] == 0);  // not a program event
    CallProfiles table;
    w.calls = {table.id(miss), table.id(hit), table.id(miss)};
    w.profiles = &table;
    CHECK(table.size() == 2);
    EffectiveCounts eff{};
    ProgramPrices prices;
    const WavePrice p = price_wave(w, m, prices, &eff);
    CHECK(p.shader == 100.0);          // lockstep: once
    CHECK(p.rt == 2.0 * (10 + 4));     // P = 1: the sum
    CHECK(p.rounds == 2);
    CHECK(p.handoff == 2 * 50.0);      // one hand-off per round
    CHECK(p.programs == 10.0 + 15.0);  // round 0: max(10, 10); round 1: the hit alone
    CHECK(p.active_lane_rounds == 3);
    double linear = 0.0;
    for (std::size_t e = 0; e < kEventCount; ++e) linear += eff[e] * m.cycles[e];
    CHECK(linear == doctest::Approx(p.total()));
    // Latency-bound RT unit: the slowest lane alone.
    ProgramPrices p32, p2, p125;
    CHECK(price_wave(w, test_model(32.0), p32).rt == 20.0);
    CHECK(price_wave(w, test_model(2.0), p2).rt == 20.0);  // max(20, 28 / 2)
    CHECK(price_wave(w, test_model(1.25), p125).rt == doctest::Approx(28.0 / 1.25));  // sum / P bounds
}

TEST_CASE("warp execution: same counts and hits as per ray, records re-price exactly, thread-count independent") {
    const TestFrame f = tilted_bundle(40, 28);  // 5 x 7 tiles of 8 x 4
    MethodOptions mo;
    const CostModel a = test_model(32.0);
    CostModel b = test_model(4.0);
    b.name = "test-4";  // results are found by preset name
    ExecutionModel grouping = a.execution;
    for (const char* name : {"ref", "obb"}) {
        CAPTURE(name);
        const auto method = find_method(name)->build(f.geometry, mo);
        const FrameResult per_ray = run(*method, f, nullptr, {}, 2);
        const FrameResult warp1 = run(*method, f, &grouping, {&a, &b}, 1, true);
        const FrameResult warp2 = run(*method, f, &grouping, {&a, &b}, 2);
        CHECK(warp1.totals == per_ray.totals);
        CHECK(warp1.rays_traced == per_ray.rays_traced);
        REQUIRE(warp1.hits.size() == per_ray.hits.size());
        bool same_hits = true;
        for (std::size_t i = 0; i < per_ray.hits.size(); ++i)
            same_hits = same_hits && warp1.hits[i].prim == per_ray.hits[i].prim && warp1.hits[i].t == per_ray.hits[i].t;
        CHECK(same_hits);
        CHECK(warp1.radiance == per_ray.radiance);
        // Threads change nothing.
        REQUIRE(warp2.warp.size() == 2);
        CHECK(warp2.warp[0].totals.lone_wave_cycles() == warp1.warp[0].totals.lone_wave_cycles());
        CHECK(warp2.warp[1].totals.lone_wave_cycles() == warp1.warp[1].totals.lone_wave_cycles());
        CHECK(warp2.warp[0].pixel_cycles == warp1.warp[0].pixel_cycles);
        CHECK(warp2.warp[1].pixel_cycles == warp1.warp[1].pixel_cycles);
        CHECK(warp2.pixel_simt_active == warp1.pixel_simt_active);
        // One wave per tile, sample and bounce that had rays.
        CHECK(warp1.warp[0].totals.waves >= 35u * 2u);
        CHECK(warp1.warp[0].totals.lanes == warp1.rays_traced);
        // Re-pricing the records gives what was priced while tracing.
        CHECK(warp1.warp_trace.waves() == warp1.warp[0].totals.waves);
        for (const CostModel* m : {&a, static_cast<const CostModel*>(&b)}) {
            EffectiveCounts eff{};
            const WarpTotals again = warp1.warp_trace.price(*m, Roofline{}, eff);
            const WarpTotals& live = warp1.warp[m == &a ? 0 : 1].totals;
            CHECK(warp1.warp_of(m->name) == &warp1.warp[m == &a ? 0 : 1]);
            CHECK(again.lone_wave_cycles() == doctest::Approx(live.lone_wave_cycles()).epsilon(1e-12));
            CHECK(again.rounds == live.rounds);
            CHECK(again.active_lane_rounds == live.active_lane_rounds);
            double linear = 0.0;
            for (std::size_t e = 0; e < kEventCount; ++e) linear += eff[e] * m->cycles[e];
            CHECK(linear == doctest::Approx(again.lone_wave_cycles()).epsilon(1e-9));
        }
        // Warps pay their slowest lane: never less than the per-ray sum over W lanes in parallel.
        CHECK(warp1.warp[0].totals.simt_efficiency(32) <= 1.0);
        CHECK(warp1.warp[0].totals.simt_efficiency(32) > 0.0);
        double pixel_sum = 0.0;
        for (const float c : warp1.warp[0].pixel_cycles) pixel_sum += c;
        CHECK(pixel_sum == doctest::Approx(warp1.warp[0].totals.lone_wave_cycles()).epsilon(1e-4));
    }
}

TEST_CASE("warp execution: ray lists run W consecutive rays per wave") {
    const TestFrame f = tilted_bundle(16, 16);
    const auto method = find_method("ref")->build(f.geometry, MethodOptions{});
    // The camera frame's rays, replayed as a ray list.
    FrameOptions o;
    o.progress = false;
    o.record_rays = true;
    const FrameResult cam = method->run(f.geometry, f.workload, TraceOptions{}, o);
    RayWorkload list;
    list.from_camera = false;
    list.rays = cam.rays;
    const CostModel m = test_model(8.0);
    o.record_rays = false;
    o.warp = &m.execution;
    o.warp_presets = {&m};
    const FrameResult r = method->run(f.geometry, list, TraceOptions{}, o);
    CHECK(r.totals == cam.totals);
    CHECK(r.warp[0].totals.waves == (cam.rays.size() + 31) / 32);
    CHECK(r.warp[0].totals.lanes == cam.rays.size());
    CHECK(r.warp[0].pixel_cycles.empty());  // a ray list has no pixels
}

namespace {

CostModel random_model(std::mt19937& rng, double rt_parallel, bool lockstep) {
    std::uniform_real_distribution<double> cost(0.0, 300.0);
    CostModel m;
    for (double& c : m.cycles) c = cost(rng);
    m.cycles[static_cast<std::size_t>(Event::TlasNodeVisit)] = 0.0;  // a free event
    m.execution.kind = ExecutionKind::Warp;
    m.execution.rt_parallel_lanes = rt_parallel;
    if (lockstep) m.execution.set_lockstep_events({Event::BlasNodeVisit, Event::TlasBoxTest});
    return m;
}

using rtc::test::same_bits;

}  // namespace

TEST_CASE("call counts: zeroed slots kept through growth and copies, profiles tell every slot apart") {
    CallCounts calls;
    for (int round = 0; round < 2; ++round) {  // again after clear(): reused slots start zeroed
        calls.clear();
        for (std::uint16_t k = 0; k < 200; ++k) {  // past the first 64 slots: grown
            ProgramCounts& c = calls.add();
            CHECK(c == ProgramCounts{});
            c.n[k % kProgramSlots] = static_cast<std::uint16_t>(k + 1);
        }
        REQUIRE(calls.size() == 200);
        const CallCounts copy = calls;
        calls.add().n[0] = 7;  // the copy has its own slots
        REQUIRE(copy.size() == 200);
        std::uint16_t k = 0;
        bool kept = true;
        for (const ProgramCounts& c : copy) {
            ProgramCounts expected;
            expected.n[k % kProgramSlots] = static_cast<std::uint16_t>(k + 1);
            kept = kept && c == expected;
            ++k;
        }
        CHECK(kept);
        CHECK(calls.size() == 201);
    }
    // Equality looks at every slot (the vector compares and the tail word).
    for (std::size_t k = 0; k < kProgramSlots; ++k) {
        ProgramCounts a, b;
        b.n[k] = 1;
        CHECK_FALSE(a == b);
        a.n[k] = 1;
        CHECK(a == b);
    }
}

TEST_CASE("call counts: every recorded call's counts are its own events, for every primitive kind") {
    // The reference: a ray's program events, counted for the ray as a whole,
    // are the sum of the counts recorded apart for each of its calls (a call
    // counted into the wrong slot, or an event missed or counted twice by
    // CallSink, breaks the sum).
    std::mt19937 rng(7);
    for (std::size_t k = 0; k < kPrimitiveKindNames.size(); ++k) {  // every kind, a new one too
        const auto kind = static_cast<PrimitiveKind>(k);
        CAPTURE(kPrimitiveKindNames[k]);
        const TestFrame f = tilted_bundle(64, 64, kind, 40, 0.02f);
        const Geometry& g = f.geometry;
        const CameraFrame cam = camera_frame(f.workload.camera);
        std::visit(
            [&](const auto& prims) {
                using Prim = typename std::decay_t<decltype(prims)>::value_type;
                TraceScratch scratch;
                CountingSink sink;
                const TraceOptions options;
                LeafPrograms<Prim, CountingSink, true> programs(prims, g.triangles, options, scratch, sink);
                CallProfiles table;
                int rays_summed = 0, hits = 0;
                for (int r = 0; r < 300; ++r) {
                    const Ray ray = frame_ray_reference(cam, static_cast<float>(rng() % 64) + 0.5f,
                                                        static_cast<float>(rng() % 64) + 0.5f);
                    sink.ray.clear();
                    programs.begin();
                    float tmax = ray.tmax;
                    for (std::uint32_t i = 0; i < prims.size(); ++i) tmax = std::min(tmax, programs.custom(i, ray, tmax));
                    hits += tmax < ray.tmax;
                    REQUIRE(scratch.calls.size() == prims.size());
                    RayCounts summed;
                    for (const ProgramCounts& c : scratch.calls) {
                        summed += c.ray_counts();
                        (void)table.id(c);
                    }
                    bool same = true;
                    for (const std::uint8_t e : kProgramEvents) same = same && summed.n[e] == sink.ray.n[e];
                    rays_summed += same;
                }
                CHECK(rays_summed == 300);
                CHECK(hits > 30);          // hit exits too, not only rejects
                CHECK(table.size() >= 3);  // several exits, counted apart
            },
            g.prims);
    }
}

TEST_CASE("warp pricing: lanes priced at once give the reference's doubles") {
    std::mt19937 rng(39);
    CallProfiles table;
    const std::vector<ProgramCounts> calls = rtc::test::random_program_calls(rng, 12);
    int checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const double parallel = std::array{1.0, 4.0, 32.0, 2.5}[trial % 4];
        const CostModel m = random_model(rng, parallel, trial % 5 == 0);
        WaveWork w;
        w.profiles = &table;
        const std::size_t lanes = 1 + rng() % 32;  // partial warps too (a lane tail)
        for (std::size_t i = 0; i < lanes; ++i) {
            LaneWork& l = w.lanes.emplace_back();
            l.counts.clear();
            // Some counts past 2^31: converted as unsigned.
            for (std::uint32_t& n : l.counts.n) n = rng() % 7 == 0 ? rng() : rng() % 200;
            for (const std::uint8_t e : kProgramEvents) l.counts.n[e] = 0;
            l.first_call = static_cast<std::uint32_t>(w.calls.size());
            l.calls = rng() % 12;  // the rounds four at a time, and their tails
            l.pixel = static_cast<std::uint32_t>(i);
            for (std::uint32_t c = 0; c < l.calls; ++c) w.calls.push_back(table.id(calls[rng() % calls.size()]));
        }
        ProgramPrices fast_prices, ref_prices;
        EffectiveCounts fast_eff{}, ref_eff{};
        const WavePrice a = price_wave(w, m, fast_prices, &fast_eff);
        const WavePrice b = price_wave_reference(w, m, ref_prices, &ref_eff);
        const WavePrice c = price_wave(w, m, fast_prices);
        CHECK(same_bits(a.shader, b.shader));
        CHECK(same_bits(a.rt, b.rt));
        CHECK(same_bits(a.rt_lane_sum, b.rt_lane_sum));
        CHECK(same_bits(a.handoff, b.handoff));
        CHECK(same_bits(a.programs, b.programs));
        CHECK(a.rounds == b.rounds);
        CHECK(a.active_lane_rounds == b.active_lane_rounds);
        // Without effective counts the lanes and rounds take only their
        // maxima and sums (lane_maxima, round_maxima).
        CHECK(same_bits(c.shader, b.shader));
        CHECK(same_bits(c.rt, b.rt));
        CHECK(same_bits(c.rt_lane_sum, b.rt_lane_sum));
        CHECK(same_bits(c.programs, b.programs));
        CHECK(same_bits(c.total(), b.total()));
        CHECK(c.rounds == b.rounds);
        CHECK(c.active_lane_rounds == b.active_lane_rounds);
        bool same_eff = true;
        for (std::size_t e = 0; e < kEventCount; ++e) same_eff = same_eff && same_bits(fast_eff[e], ref_eff[e]);
        CHECK(same_eff);
        ++checked;
    }
    CHECK(checked == 400);
}

}  // namespace RTCSIM_TEST_FILE
