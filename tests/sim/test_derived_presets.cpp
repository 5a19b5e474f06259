// Hardware presets after Turing (issue "Predictions for the hardware after
// Turing"): each is a fitted Turing preset plus sourced deltas (NVIDIA's
// turing-calibrated, AMD's turing-sm with RDNA's own issue prices and SM),
// so every hardware preset runs the warp model and inherits a fit's
// covariance; the same arithmetic has the same price in every method
// (sum_of); AMD's traversal loop runs in lockstep as shader code (lockstep
// events), and its batched draw pricing equals pricing each draw wave by
// wave; a preset's BVH width (rdna4: 8) is the run's.
#include "core/input_error.h"
#include "sim/hardware/cost_model.h"
#include "sim/hardware/presets/derived_preset.h"
#include "sim/hardware/warp_pricing.h"
#include "sim/methods/method.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"
#include "sim/run/simulation.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const std::string kHw = std::string(RTCSIM_SOURCE_DIR) + "/configs/hw/";

CostModel shipped(const std::string& name) { return load_cost_model(kHw + name + ".json"); }

// A scratch folder with a copy of turing-calibrated.json, for derived presets.
fs::path scratch() {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "derived_presets_test";
    fs::create_directories(dir);
    fs::copy_file(kHw + "turing-calibrated.json", dir / "turing-calibrated.json", fs::copy_options::overwrite_existing);
    return dir;
}

std::string error_of(const fs::path& dir, const nlohmann::json& preset) {
    const fs::path p = dir / "derived.json";
    write_text_file(p.string(), preset.dump(2));
    try {
        (void)load_cost_model(p.string());
    } catch (const InputError& e) {
        return std::string(e.what()).substr(p.string().size());
    }
    return "";
}

nlohmann::json derived(nlohmann::json deltas) {
    return {{"name", "d"}, {"derived_from", "turing-calibrated.json"}, {"deltas", std::move(deltas)}};
}

RayCounts counts_of(std::initializer_list<std::pair<Event, std::uint32_t>> l) {
    RayCounts c;
    for (const auto& [e, n] : l) c.n[static_cast<std::size_t>(e)] = n;
    return c;
}

}  // namespace

TEST_CASE("derived presets: deltas scale, replace or compose, the rest is the base's with its name") {
    const CostModel turing = shipped("turing-calibrated"), ampere = shipped("ampere"), ada = shipped("ada");
    CHECK(ampere.derived_from == "turing-calibrated");
    CHECK(ampere.execution.warp());
    CHECK(ampere[Event::TriangleTest] == 0.5 * turing[Event::TriangleTest]);
    CHECK(ampere[Event::OpFma] == 0.5 * turing[Event::OpFma]);
    CHECK(ampere[Event::OpSqrt] == turing[Event::OpSqrt]);
    CHECK(ada[Event::TriangleTest] == 0.25 * turing[Event::TriangleTest]);
    // Blackwell doubles Ada's triangle rate (its whitepaper), and the LSS
    // test, priced as 2 triangle passes (sum_of), follows it.
    const CostModel blackwell = shipped("blackwell");
    CHECK(blackwell[Event::TriangleTest] == 0.5 * ada[Event::TriangleTest]);
    CHECK(blackwell[Event::LssTest] == 2.0 * blackwell[Event::TriangleTest]);
    CHECK(blackwell.source[static_cast<std::size_t>(Event::TriangleTest)].find("RTX Blackwell") != std::string::npos);
    CHECK(ampere.source[static_cast<std::size_t>(Event::Ray)].rfind("turing-calibrated: fitted by rtcsim calibrate", 0) == 0);
    CHECK(ampere.source[static_cast<std::size_t>(Event::TriangleTest)].rfind("[D] NVIDIA GA102", 0) == 0);

    // The fit's covariance is inherited: draw d of ampere moves the fitted
    // costs exactly as draw d of turing-calibrated does.
    REQUIRE(ampere.uncertainty);
    const auto t = draw_cost_models(turing, 8, 5), a = draw_cost_models(ampere, 8, 5);
    REQUIRE(a.size() == 8);
    bool ray_moves = false;
    for (std::size_t d = 0; d < a.size(); ++d) {
        CHECK(a[d][Event::Ray] == t[d][Event::Ray]);
        CHECK(a[d][Event::BlasNodeVisit] == t[d][Event::BlasNodeVisit]);
        CHECK(a[d][Event::TriangleTest] == 0.5 * t[d][Event::TriangleTest]);
        ray_moves = ray_moves || a[d][Event::Ray] != ampere[Event::Ray];
    }
    CHECK(ray_moves);

    // A replaced cost leaves the fit: rdna3's loop is priced by its operations
    // at RDNA's own issue prices, which no draw moves, while its box tests
    // keep the fit's interval (rdna3 derives from turing-sm, the SM model).
    const CostModel rdna3 = shipped("rdna3");
    CHECK(rdna3.derived_from == "turing-sm");
    const auto r = draw_cost_models(rdna3, 8, 5), sm = draw_cost_models(shipped("turing-sm"), 8, 5);
    for (std::size_t d = 0; d < r.size(); ++d) {
        CHECK(r[d][Event::BlasNodeVisit] == rdna3[Event::BlasNodeVisit]);
        CHECK(r[d][Event::OpFma] == rdna3[Event::OpFma]);
        CHECK(r[d][Event::BlasBoxTest] == sm[d][Event::BlasBoxTest]);
        CHECK(r[d][Event::Ray] == sm[d][Event::Ray]);
        CHECK(r[d][Event::TriangleTest] == 4.0 * r[d][Event::BlasBoxTest]);  // sum_of follows the draw
    }
    CHECK(rdna3[Event::BlasNodeVisit] == doctest::Approx(12 * rdna3[Event::OpFma] + 3 * rdna3[Event::OpBranch]));
    CHECK(rdna3[Event::BlasNodeVisit] == doctest::Approx(9.0));  // 12 x 0.5 + 3 x 1.0 CU issue cycles

    // The flattened form reads back to the same costs (report.json, shards).
    const CostModel again = parse_cost_model(cost_model_to_json(rdna3), "again.json");
    CHECK(again.cycles == rdna3.cycles);
    CHECK(again.execution.lockstep_events() == rdna3.execution.lockstep_events());
    CHECK(again.uncertainty->parameters.size() == rdna3.uncertainty->parameters.size());
    CHECK(again.execution.bvh_width == 4);
    CHECK(again.execution.sm.allocation_unit == rdna3.execution.sm.allocation_unit);
}

TEST_CASE("AMD presets: priced by RDNA's own issue rates, not by the NVIDIA fits' operation-class scale") {
    // Copies of every preset, with turing-calibrated's fitted 1/20 scale on
    // the operation classes (and turing-sm's issue prices) changed: the AMD
    // presets' costs must not move.
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "amd_own_prices";
    fs::create_directories(dir);
    for (const auto& entry : fs::directory_iterator(kHw))
        if (entry.path().extension() == ".json")
            fs::copy_file(entry.path(), dir / entry.path().filename(), fs::copy_options::overwrite_existing);
    for (const char* base : {"turing-calibrated.json", "turing-sm.json"}) {
        nlohmann::json j = nlohmann::json::parse(read_text_file(kHw + base));
        for (const char* op : {"op_fma", "op_div", "op_sqrt", "op_branch", "op_load"})
            j["cycles"][op]["value"] = 7.0 * j["cycles"][op]["value"].get<double>();
        for (auto& p : j["uncertainty"]["parameters"])
            if (p["events"].size() == 5 && p["events"][0] == "op_fma") p["value"] = 7.0 * p["value"].get<double>();
        write_text_file((dir / base).string(), j.dump(2));
    }
    REQUIRE(load_cost_model((dir / "turing-calibrated.json").string())[Event::OpFma] ==
            doctest::Approx(7.0 * shipped("turing-calibrated")[Event::OpFma]));
    for (const char* name : {"rdna3", "rdna4"}) {
        CAPTURE(name);
        const CostModel moved = load_cost_model((dir / (std::string(name) + ".json")).string()), amd = shipped(name);
        for (std::size_t e = 0; e < kEventCount; ++e) {
            CAPTURE(kEventNames[e]);
            CHECK(moved.cycles[e] == amd.cycles[e]);
        }
        // RDNA's issue prices per compute unit (2 SIMD32s, a wave32 VALU
        // instruction per SIMD per cycle), with their sources tagged.
        CHECK(amd[Event::OpFma] == 0.5);
        CHECK(amd[Event::OpDiv] == 6.5);
        for (const Event op : {Event::OpFma, Event::OpDiv, Event::OpSqrt, Event::OpBranch, Event::OpLoad}) {
            const std::string& source = amd.source[static_cast<std::size_t>(op)];
            CHECK(has_source_tag(source));
            CHECK(source.find("fitted by rtcsim calibrate") == std::string::npos);
        }
        // Resident waves from the VGPR footprint on RDNA3's CU: 2 SIMDs of
        // 1536 VGPRs per lane, 24-VGPR blocks, at most 16 waves per SIMD.
        const SmModel& cu = amd.execution.sm;
        REQUIRE(cu.enabled);
        CHECK(resident_warps(cu, 112, 32) == 24);  // ray generation + shading + the loop
        CHECK(resident_warps(cu, 127, 32) == 20);  // ... + the capsule program
        CHECK(resident_warps(cu, 173, 32) == 16);  // ... + the bracketed phantom program
        CHECK(resident_warps(cu, 64, 32) == 32);   // at most 16 per SIMD
        CHECK(amd.execution.sm.latency_per_issue == 5.0);
    }
    CHECK(shipped("rdna3").execution.bvh_width == 4);
    CHECK(shipped("rdna4").execution.bvh_width == 8);
}

TEST_CASE("derived presets: every error names the file and JSON path") {
    const fs::path dir = scratch();
    CHECK(error_of(dir, derived({{{"events", {"ray"}}, {"scale", 2}, {"source", "a guess"}}})) ==
          ": /deltas/0/source: tag the source [D] documented, [M] measured, [C] read from code or [I] inferred");
    CHECK(error_of(dir, derived({{{"events", {"rays"}}, {"scale", 2}, {"source", "[I] x"}}}))
              .find(": /deltas/0/events/0: unknown event") == 0);
    CHECK(error_of(dir, derived({{{"events", {"is_capsule"}}, {"value", 2}, {"source", "[I] x"}}}))
              .find(": /deltas/0/events/0: preset \"d\" does not price is_capsule (it prices programs by operation class") == 0);
    CHECK(error_of(dir, derived({{{"events", {"ray"}}, {"scale", 2}, {"source", "[I] x"}},
                                 {{"events", {"ray"}}, {"value", 2}, {"source", "[I] y"}}})) ==
          ": /deltas/1/events/0: ray is changed by an earlier delta: merge the two");
    CHECK(error_of(dir, derived({{{"events", {"obb_box_test"}}, {"scale", 2}, {"source", "[I] x"}}}))
              .find(": /deltas/0/events/0: obb_box_test is a sum of other costs in turing-calibrated") == 0);
    CHECK(error_of(dir, derived({{{"events", {"ray"}}, {"scale", 2}, {"value", 3}, {"source", "[I] x"}}})) ==
          ": /deltas/0: give exactly one of \"scale\", \"value\" or \"sum_of\"");
    // Sums of sums are computed in order; a cycle is refused.
    CHECK(error_of(dir, derived({{{"events", {"instance_transform"}}, {"sum_of", {{"obb_box_test", 1}}}, {"source", "[I] x"}}}))
              .find(": /deltas: sums of costs refer to each other in a cycle") == 0);
    // A preset deriving from itself stops, with an error, not a stack overflow.
    nlohmann::json self = derived(nlohmann::json::array());
    self["derived_from"] = "derived.json";
    CHECK(error_of(dir, self).find(": /derived_from: presets derive from each other in a cycle: derived.json -> derived.json") !=
          std::string::npos);
    nlohmann::json missing = derived(nlohmann::json::array());
    missing["derived_from"] = "nope.json";
    CHECK(error_of(dir, missing).find(": /derived_from: no preset file " + (dir / "nope.json").string()) == 0);

    // In a plain preset: a sum_of whose written value is not the sum.
    nlohmann::json plain = nlohmann::json::parse(read_text_file(kHw + "turing-calibrated.json"));
    plain["cycles"]["obb_box_test"]["value"] = 1.0;
    CHECK_THROWS_WITH_AS((void)parse_cost_model(plain.dump(), "p.json"),
                         doctest::Contains("p.json: /cycles/obb_box_test/value: 1.0 is not the sum of its terms"), InputError);
}

TEST_CASE("shipped presets: hardware presets run the warp model, carry sources and an interval, same work at the same price") {
    int hardware = 0;
    for (const auto& entry : fs::directory_iterator(kHw)) {
        const std::string file = entry.path().filename().string();
        if (entry.path().extension() != ".json" || file.rfind("memory-", 0) == 0) continue;
        CAPTURE(file);
        const CostModel m = load_cost_model(entry.path().string());
        // The per-ray model stays only where the name says so.
        CHECK(m.execution.warp() == (m.name.find("per-ray") == std::string::npos));
        for (std::size_t i = 0; i < kEventCount; ++i) {
            CAPTURE(kEventNames[i]);
            if (m.prices(static_cast<Event>(i))) CHECK(!m.source[i].empty());
        }
        if (m.derived_from.empty()) continue;
        ++hardware;
        CHECK(m.uncertainty);  // derived from a fitted preset: speedups carry intervals
        // An oriented box test is a ray transform plus a box test wherever it is priced.
        CHECK(m[Event::ObbBoxTest] == doctest::Approx(m[Event::InstanceTransform] + m[Event::BlasBoxTest]));
        CHECK(m[Event::LssTest] == doctest::Approx(2.0 * m[Event::TriangleTest]));
    }
    CHECK(hardware == 6);  // ampere, ada, blackwell, hypothetical-obb, rdna3, rdna4
    CHECK(shipped("rdna4").hypothetical_reason("obb-quantized").find("[C] AMD GPURT") == 0);
    CHECK(shipped("rdna4").execution.lockstep_events().size() == 2);  // instance transforms in hardware
}

TEST_CASE("lockstep events: each preset's event units are computed once when it is loaded") {
    // Where each event runs on the machine: kEventUnits, except the preset's
    // lockstep events, which every pricer reads from ExecutionModel::unit.
    for (const char* name : {"turing-calibrated", "rdna3", "rdna4"}) {
        CAPTURE(name);
        const ExecutionModel& x = shipped(name).execution;
        for (std::size_t i = 0; i < kEventCount; ++i) {
            const auto e = static_cast<Event>(i);
            CAPTURE(kEventNames[i]);
            const bool loop = std::find(x.lockstep_events().begin(), x.lockstep_events().end(), e) !=
                              x.lockstep_events().end();
            CHECK(x.unit(e) == (loop ? EventUnit::Lockstep : kEventUnits[i]));
        }
    }
    CHECK(shipped("turing-calibrated").execution.lockstep_events().empty());
    CHECK(shipped("rdna3").execution.unit(Event::InstanceTransform) == EventUnit::Lockstep);
    CHECK(shipped("rdna4").execution.unit(Event::InstanceTransform) == EventUnit::RtUnit);  // in the intersect instruction
    // Setting them again moves the units with them.
    ExecutionModel m = shipped("rdna3").execution;
    m.set_lockstep_events({Event::TlasBoxTest});
    CHECK(m.unit(Event::TlasBoxTest) == EventUnit::Lockstep);
    CHECK(m.unit(Event::InstanceTransform) == EventUnit::RtUnit);
}

TEST_CASE("lockstep events: a shader traversal loop costs the wave its slowest lane, outside the RT unit") {
    CostModel m;
    for (std::size_t e = 0; e < kEventCount; ++e) m.cycles[e] = 1.0;
    m[Event::BlasNodeVisit] = 3;
    m[Event::BlasBoxTest] = 2;
    m.execution.kind = ExecutionKind::Warp;
    m.execution.rt_parallel_lanes = 1.0;  // the unit's work sums over lanes
    WaveWork w;
    CallProfiles table;
    w.profiles = &table;
    w.lanes.push_back({counts_of({{Event::Ray, 1}, {Event::BlasNodeVisit, 10}, {Event::BlasBoxTest, 20}}), 0, 0, 0});
    w.lanes.push_back({counts_of({{Event::Ray, 1}, {Event::BlasNodeVisit, 4}, {Event::BlasBoxTest, 8}}), 0, 0, 1});
    ProgramPrices prices;
    const WavePrice nvidia = price_wave(w, m, prices);
    CHECK(nvidia.shader == 1.0);
    CHECK(nvidia.rt == 3.0 * 14 + 2.0 * 28);
    m.execution.set_lockstep_events({Event::BlasNodeVisit});
    EffectiveCounts eff{};
    ProgramPrices prices2;
    const WavePrice amd = price_wave(w, m, prices2, &eff);
    CHECK(amd.shader == 1.0 + 3.0 * 10);  // the slowest lane's loop, once
    CHECK(amd.rt == 2.0 * 28);            // only the box tests in the accelerator
    double linear = 0.0;
    for (std::size_t e = 0; e < kEventCount; ++e) linear += eff[e] * m.cycles[e];
    CHECK(linear == doctest::Approx(amd.total()));
    CHECK(eff[static_cast<std::size_t>(Event::BlasNodeVisit)] == 10.0);
}

TEST_CASE("pricing engine: on every shipped warp preset, live, batched-draw, break-even and re-pricing equal the reference pricer") {
    // The specification of a wave's price is price_wave_reference (lane by
    // lane). The fast pricers must agree with it under every preset a user
    // can name, lockstep events (rdna3, rdna4), SM rooflines and composed
    // costs included: the waves priced while tracing, the recorded waves
    // re-priced, the batched draws of the intervals and the break-even
    // maps' linear counts.
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "derived_presets_test";
    fs::create_directories(dir);
    std::vector<std::string> presets;
    for (const fs::path& folder : {fs::path(kHw), fs::path(kHw) / "sensitivity"})
        for (const auto& entry : fs::directory_iterator(folder)) {
            const std::string file = entry.path().filename().string();
            if (entry.path().extension() == ".json" && file.rfind("memory-", 0) != 0 &&
                load_cost_model(entry.path().string()).execution.warp())
                presets.push_back(entry.path().string());
        }
    std::sort(presets.begin(), presets.end());
    CHECK(presets.size() >= 16);  // 10 in configs/hw (the guesses, turing-calibrated, turing-sm, ..., rdna4), 6 AMD variants
    // One run each: a preset's node width is the run's (rdna4: 8-wide).
    for (const std::string& preset : presets) {
        CAPTURE(preset);
        const nlohmann::json config = {
            {"name", "lockstep"},
            {"scene", {{"type", "bundle"}, {"count", 60}, {"radius", 0.01}, {"tilt_deg", 30}, {"seed", 2}}},
            {"primitives", {{"kind", "capsule"}}},
            {"methods", {"ref", "obb"}},
            {"cost", nlohmann::json::array({preset})},
            {"memory", kHw + "memory-optix7.json"},
            {"workload", {{"type", "camera"}, {"camera", "auto"}, {"width", 16}, {"height", 16}, {"spp", 1}, {"bounces", 1}}},
            {"output", {{"images", false}, {"arrays", false}}},
            {"uncertainty", {{"draws", 8}, {"seed", 3}}}};
        const RunConfig c = parse_run_config(config, (dir / "c.json").string());
        if (c.costs[0]->execution.bvh_width > 0) CHECK(c.build.tlas.width == c.costs[0]->execution.bvh_width);
        RunContext ctx;
        ctx.quiet = true;
        ctx.threads = 1;
        ctx.record_warps = true;
        const RunResult r = run_simulation(c, ctx);
        const std::size_t p = 0;
        const std::vector<CostModel> draws = draw_cost_models(r.costs[p], 8, 3);
        for (const MethodRun& m : r.methods) {
            CAPTURE(m.method);
            REQUIRE(m.frame.warp_trace.waves() > 0);  // recorded (record_warps)
            const WarpTotals reference = m.frame.warp_trace.price_reference(r.costs[p]);
            const WarpTotals& live = m.frame.warp_of(r.costs[p].name)->totals;
            CHECK(live.lone_wave_cycles() == doctest::Approx(reference.lone_wave_cycles()).epsilon(1e-12));
            CHECK(live.rt_lane_sum == doctest::Approx(reference.rt_lane_sum).epsilon(1e-12));
            CHECK(live.rounds == reference.rounds);
            CHECK(live.active_lane_rounds == reference.active_lane_rounds);
            CHECK(m.priced[p].total_cycles == doctest::Approx(reference.cycles(m.roof[p])).epsilon(1e-12));
            CHECK(m.priced[p].total_cycles == doctest::Approx(m.frame.warp_trace.price(r.costs[p]).cycles(m.roof[p])).epsilon(1e-12));
            // Break-even maps price a method linearly around the preset: exact at it.
            CHECK(m.roof[p].enabled == r.costs[p].execution.sm.enabled);
            const auto linear = break_even_counts(m, &r.costs[p], m.roof[p]);
            double at_preset = 0.0;
            for (std::size_t i = 0; i < kEventCount; ++i) at_preset += linear[i] * r.costs[p].cycles[i];
            CHECK(at_preset == doctest::Approx(m.priced[p].total_cycles).epsilon(1e-12));
            REQUIRE(m.draw_cycles[p].size() == draws.size());  // none for the guesses (no covariance)
            for (std::size_t d = 0; d < draws.size(); ++d)
                CHECK(m.draw_cycles[p][d] == doctest::Approx(m.frame.warp_trace.price_reference(draws[d]).cycles(m.roof[p])).epsilon(1e-12));
        }
    }
}

TEST_CASE("BVH width: a run takes its presets' node width, rdna4's 8, and presets of other widths do not share a run") {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "derived_presets_test";
    fs::create_directories(dir);
    const auto config = [&](nlohmann::json cost) {
        return nlohmann::json{{"name", "width"},
                              {"scene", {{"type", "bundle"}, {"count", 10}, {"radius", 0.01}, {"tilt_deg", 30}, {"seed", 2}}},
                              {"methods", {"ref", "obb"}},
                              {"cost", std::move(cost)},
                              {"memory", kHw + "memory-optix7.json"},
                              {"workload", {{"type", "camera"}, {"camera", "auto"}, {"width", 8}, {"height", 8}, {"spp", 1}, {"bounces", 0}}},
                              {"output", {{"images", false}, {"arrays", false}}}};
    };
    const std::string file = (dir / "w.json").string();
    const RunConfig amd4 = parse_run_config(config({kHw + "rdna4.json"}), file);
    CHECK(amd4.build.tlas.width == 8);
    CHECK(amd4.build.custom_blas.width == 8);
    CHECK(amd4.build.triangle_blas.width == 8);
    // NVIDIA presets name no width: the config's (4 by default) stands.
    const RunConfig mixed = parse_run_config(config({kHw + "turing-calibrated.json", kHw + "rdna3.json"}), file);
    CHECK(mixed.build.tlas.width == 4);
    CHECK(parse_run_config(config({kHw + "turing-calibrated.json"}), file).build.custom_blas.width == 4);
    CHECK_THROWS_WITH_AS((void)parse_run_config(config({kHw + "rdna3.json", kHw + "rdna4.json"}), file),
                         doctest::Contains("rdna4 builds 8-wide nodes (its execution.bvh_width), /cost/0 (rdna3) 4-wide ones"),
                         InputError);
    nlohmann::json four = config({kHw + "rdna4.json"});
    four["bvh"] = {{"width", 4}};
    CHECK_THROWS_WITH_AS((void)parse_run_config(four, file), doctest::Contains("but the config sets bvh.width 4"), InputError);
    four["bvh"] = {{"width", 8}};
    CHECK(parse_run_config(four, file).build.tlas.width == 8);
    // And the built structures are 8-wide.
    RunContext ctx;
    ctx.quiet = true;
    ctx.threads = 1;
    const RunResult r = run_simulation(amd4, ctx);
    for (const MethodRun& m : r.methods) {
        CAPTURE(m.method);
        CHECK(m.structures.width == 8);
    }
}

TEST_CASE("hardware features: a preset lists only known ones, and every method's needs are known") {
    nlohmann::json j = nlohmann::json::parse(read_text_file(kHw + "turing-calibrated.json"));
    j["features"] = {"custom_primitives", "instance_transform"};  // a typo would make obb n/a with exit 0
    CHECK_THROWS_WITH_AS((void)parse_cost_model(j.dump(), "p.json"),
                         doctest::Contains("p.json: /features/1: unknown hardware feature \"instance_transform\" (known: "),
                         InputError);
    const fs::path dir = scratch();
    nlohmann::json d = derived(nlohmann::json::array());
    d["features"] = {"lss", "obb-nodes"};
    CHECK(error_of(dir, d).find(": /features/1: unknown hardware feature \"obb-nodes\"") == 0);
    for (const MethodEntry& m : registered_methods())
        for (const std::string& need : m.info.needs) {
            CAPTURE(m.info.name);
            CHECK(std::find(std::begin(kHardwareFeatures), std::end(kHardwareFeatures), need) != std::end(kHardwareFeatures));
        }
}

}  // namespace RTCSIM_TEST_FILE
