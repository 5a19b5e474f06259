// Intervals on speedups (docs/calibration.md): a run whose cost presets carry
// an uncertainty block prices each method under draws of it and reports the
// 90 % interval of each speedup; identical at any thread count, containing
// the point estimate, narrower for a smaller covariance, absent (with the
// reason) for a preset without one, in report.json, results.csv and tables.
#include "sim/hardware/uncertainty/draw_pricing.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"
#include "sim/run/simulation.h"
#include "sim/util/json_file.h"

#include "warp_test_util.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <random>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

// `base` (a shipped preset) named `name`, with a block over context_switch,
// a scale on the box tests and a program price (the capsule program's for a
// preset pricing programs by name, the load class for one pricing operation
// classes), covariance `scale` x a fixed matrix.
std::string write_preset(const fs::path& dir, const std::string& base, const std::string& name, double scale) {
    nlohmann::json j = nlohmann::json::parse(read_text_file(std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/" + base + ".json"));
    j["name"] = name;
    const std::string program = j["cycles"].contains("is_capsule") ? "is_capsule" : "op_load";
    if (scale > 0)
        j["uncertainty"] = {
            {"source", "test"},
            {"parameters",
             {{{"events", {"context_switch"}}, {"tie", "value"}, {"value", j["cycles"]["context_switch"]["value"]},
               {"min", 50}, {"max", 1000}, {"free", true}},
              {{"events", {"tlas_box_test", "blas_box_test"}}, {"tie", "scale"}, {"value", 1.0}, {"min", 0.25},
               {"max", 4}, {"free", true}},
              // A program's cost: the draws re-price the rounds too.
              {{"events", {program}}, {"tie", "value"}, {"value", j["cycles"][program]["value"]},
               {"min", 1}, {"max", 1000}, {"free", true}}}},
            {"covariance", {{0.04 * scale, -0.01 * scale, 0.0}, {-0.01 * scale, 0.09 * scale, 0.0}, {0.0, 0.0, 0.0625 * scale}}}};
    const fs::path p = dir / (name + ".json");
    write_text_file(p.string(), j.dump(2));
    return p.string();
}

struct Runs {
    RunResult one, two;  // at 1 and 2 threads
};

Runs run_both(int draws) {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "intervals_test";
    fs::create_directories(dir);
    const nlohmann::json config = {
        {"name", "intervals"},
        {"scene", {{"type", "bundle"}, {"count", 60}, {"radius", 0.01}, {"tilt_deg", 30}, {"seed", 2}}},
        {"primitives", {{"kind", "capsule"}}},
        {"cost", {write_preset(dir, "turing-per-ray-guess", "guess-u", 1.0), write_preset(dir, "turing-warp-guess", "warp-u", 1.0),
                  write_preset(dir, "turing-per-ray-guess", "plain", 0.0), write_preset(dir, "turing-per-ray-guess", "guess-q", 0.25)}},
        {"memory", std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/memory-optix7.json"},
        {"workload", {{"type", "camera"}, {"camera", "auto"}, {"width", 16}, {"height", 16}, {"spp", 1}, {"bounces", 1}}},
        {"output", {{"images", false}, {"arrays", false}}},
        {"uncertainty", {{"draws", draws}, {"seed", 3}}}};
    const RunConfig c = parse_run_config(config, (dir / "c.json").string());
    RunContext ctx;
    ctx.quiet = true;
    ctx.threads = 1;
    ctx.record_warps = true;  // to check the batched draw pricing against price_wave
    Runs r{run_simulation(c, ctx), {}};
    ctx.record_warps = false;
    ctx.threads = 2;
    r.two = run_simulation(c, ctx);
    return r;
}

}  // namespace

TEST_CASE("intervals: per-ray and warp presets, thread counts, covariance scale, presets without one") {
    const Runs r = run_both(32);
    for (std::size_t p : {0u, 1u, 3u}) {  // guess-u (per ray), warp-u (warp), guess-q
        CAPTURE(p);
        const auto i = r.one.speedup_interval("obb", p);
        REQUIRE(i);
        CHECK(r.two.speedup_interval("obb", p) == i);  // bit-identical at 2 threads
        const double s = r.one.speedup("obb", p);
        CHECK((*i)[0] <= s);
        CHECK(s <= (*i)[1]);
        CHECK((*i)[0] < (*i)[1]);
        CHECK(r.one.no_interval_reason(p).empty());
    }
    // The warp draws, priced in batches while tracing, equal each draw priced
    // wave by wave from the recorded waves (up to the order of a lane's sums).
    const std::vector<CostModel> draws = draw_cost_models(r.one.costs[1], 32, 3);
    for (const MethodRun& m : r.one.methods)
        for (std::size_t d = 0; d < draws.size(); ++d)
            CHECK(m.draw_cycles[1][d] == doctest::Approx(m.frame.warp_trace.price(draws[d]).cycles(m.roof[1])).epsilon(1e-12));
    CHECK_FALSE(r.one.speedup_interval("obb", 2));
    CHECK(r.one.no_interval_reason(2) == "no covariance in the preset (a guess): no interval");
    // A quarter of the covariance: about half the width (the same normals, halved).
    const auto wide = *r.one.speedup_interval("obb", 0), narrow = *r.one.speedup_interval("obb", 3);
    CHECK(narrow[1] - narrow[0] < 0.7 * (wide[1] - wide[0]));
    CHECK(narrow[1] - narrow[0] > 0.3 * (wide[1] - wide[0]));

    const nlohmann::ordered_json j = report_json(r.one);
    const auto& in = j["speedup_interval_over_ref"]["obb"];
    CHECK(in.contains("guess-u"));
    CHECK(in.contains("warp-u"));
    CHECK_FALSE(in.contains("plain"));
    CHECK(in["warp-u"][0].get<double>() == (*r.one.speedup_interval("obb", 1))[0]);
    CHECK(j["uncertainty"]["plain"] == "no covariance in the preset (a guess): no interval");
    CHECK(j["uncertainty"]["guess-u"].get<std::string>().find("32 draws") != std::string::npos);
    CHECK(j["speedup_interval_over_ref"].size() == 1);  // the baseline has no entry, as in speedup_over_ref

    const std::string csv = results_csv({r.one});
    CHECK(csv.find(",speedup,speedup_low,speedup_high,") != std::string::npos);
    const std::string table = summary_table({r.one}).to_markdown();
    CHECK(table.find("x [") != std::string::npos);
}

TEST_CASE("intervals: draws 0 turns them off and says so") {
    const Runs r = run_both(0);
    for (std::size_t p = 0; p < 4; ++p) CHECK_FALSE(r.one.speedup_interval("obb", p));
    CHECK(r.one.no_interval_reason(0) == "uncertainty.draws is 0: no interval");
    CHECK(report_json(r.one)["speedup_interval_over_ref"]["obb"].empty());
}

TEST_CASE("draw pricing: rows compared on AVX lanes give the lane-by-lane reference's doubles") {
    std::mt19937 rng(27);
    std::uniform_real_distribution<double> cost(0.0, 300.0);
    CallProfiles table;
    const std::vector<ProgramCounts> calls = rtc::test::random_program_calls(rng, 8);
    using rtc::test::same_bits;
    int compared = 0;
    for (int trial = 0; trial < 200; ++trial) {
        CostModel base;
        for (double& c : base.cycles) c = cost(rng);
        base.execution.kind = ExecutionKind::Warp;
        base.execution.rt_parallel_lanes = trial % 3 == 0 ? 4.0 : 1.0;
        if (trial % 4 == 0) base.execution.set_lockstep_events({Event::BlasNodeVisit, Event::TlasBoxTest});
        // Draws that change 1 to 12 events (past 7 in the RT unit: the
        // reference's path in both), programs in some trials.
        const std::size_t changed = 1 + rng() % 12;
        std::vector<CostModel> models(1 + rng() % 9, base);
        for (CostModel& m : models)
            for (std::size_t k = 0; k < changed; ++k) m.cycles[rng() % kEventCount] = cost(rng);
        DrawSet set{&base, {}};
        for (const CostModel& m : models) set.draws.push_back(&m);
        WaveWork w;
        w.profiles = &table;
        const std::size_t lanes = 1 + rng() % 32;
        for (std::size_t i = 0; i < lanes; ++i) {
            LaneWork& l = w.lanes.emplace_back();
            l.counts.clear();
            // Lanes alike in some trials (many dominated), counts past 2^31 in a few.
            const std::uint32_t spread = trial % 2 ? 3 : 200;
            for (std::uint32_t& n : l.counts.n) n = rng() % 50 == 0 ? rng() : rng() % spread;
            for (const std::uint8_t e : kProgramEvents) l.counts.n[e] = 0;
            l.first_call = static_cast<std::uint32_t>(w.calls.size());
            l.calls = rng() % 5;
            l.pixel = static_cast<std::uint32_t>(i);
            for (std::uint32_t c = 0; c < l.calls; ++c) w.calls.push_back(table.id(calls[rng() % calls.size()]));
        }
        WaveDrawPricer fast(set), reference(set, true);
        std::vector<WarpTotals> a(models.size()), b(models.size());
        fast.add(w, a.data());
        reference.add(w, b.data());
        for (std::size_t d = 0; d < models.size(); ++d) {
            CAPTURE(trial);
            CAPTURE(d);
            CHECK(same_bits(a[d].shader, b[d].shader));
            CHECK(same_bits(a[d].rt, b[d].rt));
            CHECK(same_bits(a[d].rt_lane_sum, b[d].rt_lane_sum));
            CHECK(same_bits(a[d].handoff, b[d].handoff));
            CHECK(same_bits(a[d].programs, b[d].programs));
            ++compared;
        }
    }
    CHECK(compared >= 200);
}

}  // namespace RTCSIM_TEST_FILE
