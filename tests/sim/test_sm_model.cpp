// The SM around the warps (sim/hardware/sm_model.h): resident warps from a
// pipeline's register footprint, the frame's roofline terms, and effective
// counts that price the binding term exactly (calibration's linearization).
#include "core/input_error.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/sm_model.h"
#include "sim/hardware/warp_pricing.h"
#include "sim/run/simulation.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kHw = std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/";

// A tiny capsule bundle, ref and obb, priced under `costs` (preset paths).
nlohmann::json capsule_bundle(const std::vector<std::string>& costs, int count) {
    return {{"name", "sm"},
            {"scene", {{"type", "bundle"}, {"count", count}, {"radius", 0.01}, {"tilt_deg", 30}, {"seed", 2}}},
            {"primitives", {{"kind", "capsule"}}},
            {"methods", {"ref", "obb"}},
            {"cost", costs},
            {"memory", kHw + "memory-optix7.json"},
            {"workload",
             {{"type", "camera"}, {"camera", "auto"}, {"width", 16}, {"height", 16}, {"spp", 1}, {"bounces", 1}}},
            {"output", {{"images", false}, {"arrays", false}}}};
}

}  // namespace

TEST_CASE("SM: resident warps follow CC 7.5's register rule (cuda_occupancy.h's figures for the measured pipelines)") {
    SmModel sm;  // CC 7.5: 64 K registers in 4 sub-partitions, 256-register units, 32 warps
    // The warps scripts/registers/measure reports from NVIDIA's own
    // occupancy calculator for these footprints (docs/sm-model-evidence.md).
    CHECK(resident_warps(sm, 88, 32) == 20);   // shader alone: 2,816 per warp, 5 per sub-partition
    CHECK(resident_warps(sm, 96, 32) == 20);   // cylinder
    CHECK(resident_warps(sm, 103, 32) == 16);  // capsule: rounded to 3,328
    CHECK(resident_warps(sm, 108, 32) == 16);  // link
    CHECK(resident_warps(sm, 131, 32) == 12);  // paper phantom
    CHECK(resident_warps(sm, 149, 32) == 12);  // bracketed phantom
    CHECK(resident_warps(sm, 32, 32) == 32);   // capped by max_warps
    CHECK(resident_warps(sm, 255, 32) == 8);   // 8,192 per warp: 2 per sub-partition
    // The whole register file at once would give 23 warps for 88 registers:
    // the sub-partitions are what make it 20.
    sm.partitions = 1;
    CHECK(resident_warps(sm, 88, 32) == 23);
}

TEST_CASE("SM: the shipped turing-sm names every pipeline, with its roofline per program") {
    const CostModel m = load_cost_model(kHw + "turing-sm.json");
    REQUIRE(m.execution.sm.enabled);
    CHECK(roofline(m.execution.sm, "", 32).warps == 20);
    CHECK(roofline(m.execution.sm, "capsule", 32).warps == 16);
    CHECK(roofline(m.execution.sm, "phantom_paper", 32).warps == 12);
    CHECK(pipeline_program(PrimitiveKind::Phantom, PhantomProgram::Paper, true) == "phantom_paper");
    CHECK(pipeline_program(PrimitiveKind::Capsule, PhantomProgram::Paper, false).empty());
    CHECK_THROWS_AS((void)m.execution.sm.pipeline_registers("nurbs"), std::invalid_argument);
    // turing-calibrated has no SM block: the lone-wave sum.
    CHECK_FALSE(load_cost_model(kHw + "turing-calibrated.json").execution.sm.enabled);
}

TEST_CASE("SM: a frame is its binding term, and without an SM the lone-wave sum") {
    WarpTotals w;
    w.shader = 100, w.rt = 400, w.handoff = 300, w.programs = 50, w.rt_lane_sum = 1600;
    CHECK(w.terms(Roofline{}).cycles == 850.0);
    CHECK(w.terms(Roofline{}).bound == FrameTerms::Bound::Sum);
    Roofline roof;
    roof.enabled = true, roof.warps = 10, roof.latency_per_issue = 4.0, roof.rt_unit_lanes = 16.0;
    FrameTerms t = w.terms(roof);
    CHECK(t.latency == doctest::Approx((4.0 * (100 + 50) + 400 + 300) / 10.0));  // 130
    CHECK(t.issue == 150.0);
    CHECK(t.rt_unit == 100.0);
    CHECK(t.bound == FrameTerms::Bound::Issue);
    CHECK(t.cycles == 150.0);
    roof.warps = 2;  // few warps: latency shows
    t = w.terms(roof);
    CHECK(t.bound == FrameTerms::Bound::Latency);
    CHECK(t.cycles == doctest::Approx(650.0));
    roof.warps = 20, roof.rt_unit_lanes = 4.0;  // a narrow RT unit
    t = w.terms(roof);
    CHECK(t.bound == FrameTerms::Bound::RtUnit);
    CHECK(t.cycles == 400.0);
}

TEST_CASE("SM: a preset's sm block is read strictly, and a run's pipeline is checked before tracing") {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "sm_model_test";
    fs::create_directories(dir);
    std::ifstream in(kHw + "turing-sm.json");
    const nlohmann::json shipped = nlohmann::json::parse(in);
    nlohmann::json typo = shipped;
    typo["execution"]["sm"]["warps_max"] = {{"value", 4}, {"source", "s"}};
    CHECK_THROWS_WITH_AS((void)parse_cost_model(typo.dump(), "typo.json"),
                         doctest::Contains("/execution/sm"), InputError);
    nlohmann::json no_capsule = shipped;
    no_capsule["execution"]["sm"]["registers"]["value"].erase("capsule");
    const std::string path = (dir / "no_capsule.json").string();
    std::ofstream(path) << no_capsule.dump(1);
    CHECK_THROWS_WITH_AS((void)parse_run_config(capsule_bundle({path}, 30), (dir / "c.json").string()),
                         doctest::Contains("/cost/0"), InputError);
}

TEST_CASE("SM: a run's cycles are its frame's binding term, and the effective counts price it exactly") {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "sm_model_test";
    fs::create_directories(dir);
    const RunConfig c = parse_run_config(capsule_bundle({kHw + "turing-sm.json", kHw + "turing-calibrated.json"}, 60),
                                         (dir / "c.json").string());
    RunContext ctx;
    ctx.quiet = true;
    ctx.threads = 1;
    ctx.record_warps = true;
    const RunResult r = run_simulation(c, ctx);
    for (const MethodRun& m : r.methods) {
        CAPTURE(m.method);
        REQUIRE(m.roof.size() == 2);
        CHECK(m.roof[0].enabled);
        CHECK(m.roof[0].warps == 16);  // the capsule pipeline
        CHECK_FALSE(m.roof[1].enabled);
        const FrameTerms t = m.warp[0].terms(m.roof[0]);
        CHECK(m.priced[0].total_cycles == t.cycles);
        CHECK(t.cycles == std::max({t.latency, t.issue, t.rt_unit}));
        CHECK(m.priced[1].total_cycles == m.warp[1].lone_wave_cycles());
        // Re-priced from the recorded waves: the same cycles, and counts
        // whose linear price is exactly them (what calibration fits with).
        EffectiveCounts eff{};
        const WarpTotals again = m.frame.warp_trace.price(r.costs[0], m.roof[0], eff);
        CHECK(again.cycles(m.roof[0]) == doctest::Approx(t.cycles).epsilon(1e-12));
        double linear = 0.0;
        for (std::size_t e = 0; e < kEventCount; ++e) linear += eff[e] * r.costs[0].cycles[e];
        CHECK(linear == doctest::Approx(t.cycles).epsilon(1e-9));
    }
}

}  // namespace RTCSIM_TEST_FILE
