#include "sim/report/report.h"

#include "sim/util/version.h"

#include <algorithm>
#include <cmath>

namespace rtc {

namespace {

nlohmann::ordered_json scene_stats_json(const SceneStats& s) {
    nlohmann::ordered_json j;
    j["strands"] = s.strands;
    j["segments"] = s.segments;
    j["points"] = s.points;
    j["triangles"] = s.triangles;
    j["curve_basis"] = std::string(curve_basis_name(s.curve_basis));
    j["curves"] = s.curves;
    if (!s.bounds.empty())
        j["bounds"] = {{s.bounds.lo.x, s.bounds.lo.y, s.bounds.lo.z}, {s.bounds.hi.x, s.bounds.hi.y, s.bounds.hi.z}};
    j["mean_segment_length"] = s.mean_segment_length;
    j["mean_radius"] = s.mean_radius;
    j["mean_length_over_radius"] = s.mean_length_over_radius;
    j["thin_segments"] = s.thin_segments;
    return j;
}

nlohmann::ordered_json events_json(const EventTotals& totals, std::uint64_t rays, const SampledMethod* sampled) {
    nlohmann::ordered_json j;
    for (std::size_t i = 0; i < kEventCount; ++i) {
        const double per_ray = rays ? static_cast<double>(totals.n[i]) / static_cast<double>(rays) : 0.0;
        j[std::string(kEventNames[i])] = {{"total", totals.n[i]}, {"per_ray", per_ray}};
        if (sampled) j[std::string(kEventNames[i])]["sampling_interval"] = sampled->event_intervals[i];
    }
    return j;
}

// A sampled run's design: what was traced and how the totals were scaled.
nlohmann::ordered_json sampling_json(const RunResult& run) {
    const TileSample& s = *run.sample;
    return {{"fraction", s.fraction()},
            {"requested_fraction", run.config.sampling.fraction},
            {"seed", s.seed()},
            {"tile", {s.tile_width(), s.tile_height()}},
            {"tiles", s.tiles()},
            {"tiles_traced", s.traced_tiles()},
            {"strata", s.strata()},
            {"tiles_per_stratum", 2 * s.k()},
            {"stratum_tiles", {s.block_width(), s.block_height()}},
            {"confidence", 0.95},
            {"method", "stratified sample of warp tiles, two per stratum, a block of " +
                           std::to_string(s.block_width()) + " x " + std::to_string(s.block_height()) +
                           " tiles; totals are " + std::to_string(s.k()) +
                           " x the traced tiles' sums; speedups are ratio estimators over the same tiles for every "
                           "method; intervals are 95 % (Student t, Satterthwaite's degrees of freedom): "
                           "docs/sampling.md"},
            {"images", "per-pixel images and arrays show the traced tiles only (the others are zero): " +
                           std::to_string(s.traced_tiles()) + " of " + std::to_string(s.tiles()) + " tiles"}};
}

nlohmann::ordered_json method_json(const MethodRun& m, const RunResult& run) {
    nlohmann::ordered_json j;
    j["runnable"] = m.runnable;
    if (!m.runnable) {
        j["reason"] = m.reason;
        j["instances"] = m.instances;
        return j;
    }
    const std::uint64_t rays = m.rays();
    j["instances"] = m.instances;
    j["rays"] = rays;
    if (m.sampled) {
        j["rays_traced"] = m.frame.rays_traced;
        j["rays_sampling_interval"] = m.sampled->rays_interval;
    }
    j["events"] = events_json(m.totals(), rays, m.sampled ? &*m.sampled : nullptr);
    if (m.agreement) {  // an approximate method's hits against the baseline's (sim/run/hit_agreement.h)
        const HitAgreement& a = *m.agreement;
        j["hit_agreement"] = {{"baseline", a.baseline},
                              {"rays", a.rays},
                              {"fraction", a.fraction()},
                              {"hit_miss_fraction", a.hit_miss_fraction()},
                              {"both_hit", a.both_hit},
                              {"tolerance_radii", a.tolerance_radii}};
    }
    nlohmann::ordered_json cycles;
    for (std::size_t p = 0; p < run.costs.size(); ++p) {
        const PricedRun& pr = m.priced[p];
        if (!pr.supported) {
            cycles[run.costs[p].name] = {{"n/a", "the preset's hardware has no " + pr.missing_feature}};
            continue;
        }
        nlohmann::ordered_json breakdown;
        for (std::size_t i = 0; i < kEventCount; ++i)
            if (pr.by_event[i] > 0.0) breakdown[std::string(kEventNames[i])] = pr.by_event[i];
        nlohmann::ordered_json entry = {
            {"total", pr.total_cycles},
            {"per_ray", rays ? pr.total_cycles / static_cast<double>(rays) : 0.0},
            {"breakdown", breakdown}};
        if (m.sampled && p < m.sampled->cycles.size() && m.sampled->cycles[p]) {
            entry["sampling_interval"] = m.sampled->cycles[p]->interval;
            entry["sampling_std_error"] = m.sampled->cycles[p]->std_error;
        }
        // Priced, but not what this machine builds (CostModel::hypothetical).
        if (const std::string why = run.costs[p].hypothetical_reason(m.method); !why.empty()) entry["hypothetical"] = why;
        // What one intersection-program call costs on average under this
        // preset (its program events, priced per call): the derived figure of
        // a preset that prices operation classes (docs/execution-model.md).
        if (const std::uint64_t calls = m.totals()[Event::IsCall]; calls > 0) {
            double program = 0.0;
            for (std::size_t i = 0; i < kEventCount; ++i)
                if (kEventUnits[i] == EventUnit::Program) program += pr.by_event[i];
            entry["program_cycles_per_call"] = program / static_cast<double>(calls);
        }
        if (pr.execution == ExecutionKind::Warp) {
            // The breakdown above is the per-ray sum's; the warp model's is by unit.
            const WarpTotals& w = m.warp[p];
            const int width = run.costs[p].execution.warp_width;
            const double waves = static_cast<double>(std::max<std::uint64_t>(w.waves, 1));
            entry["execution"] = "warp";
            entry["per_ray_model_total"] = pr.per_ray_cycles;
            entry["warp"] = {{"waves", w.waves},
                             {"cycles_per_wave", pr.total_cycles / waves},
                             {"rounds_per_wave", static_cast<double>(w.rounds) / waves},
                             {"active_lanes_per_wave", static_cast<double>(w.lanes) / waves},
                             {"simt_efficiency", w.simt_efficiency(width)},
                             {"rt_simt_efficiency", w.rt_efficiency(width)},
                             {"occupancy", w.occupancy(width)},
                             {"breakdown", {{"shader", w.shader}, {"rt_unit", w.rt},
                                            {"hand_off", w.handoff}, {"programs", w.programs}}}};
            if (p < m.roof.size() && m.roof[p].enabled) {
                // The SM the waves ran on (sm_model.h): its roofline terms
                // over the frame, and which one bound the cycles.
                const Roofline& roof = m.roof[p];
                const FrameTerms t = w.terms(roof);
                entry["sm"] = {{"registers_per_thread", roof.registers},
                               {"resident_warps", roof.warps},
                               {"latency_per_issue", roof.latency_per_issue},
                               {"rt_unit_lanes", roof.rt_unit_lanes},
                               {"bound", bound_name(t.bound)},
                               {"latency", t.latency},
                               {"issue", t.issue},
                               {"rt_unit", t.rt_unit},
                               {"lone_wave_sum", w.lone_wave_cycles()}};
            }
        }
        cycles[run.costs[p].name] = entry;
    }
    j["cycles"] = cycles;
    if (const std::uint64_t calls = m.totals()[Event::IsPhantom]; calls > 0) {
        // Either program counts one is_phantom per call and its own iterations.
        const EventTotals& e = m.totals();
        const auto per_call = [&](std::uint64_t n) { return static_cast<double>(n) / static_cast<double>(calls); };
        j["phantom"] = {
            {"program", std::string(phantom_program_name(run.config.trace.phantom.program))},
            {"calls", calls},
            {"iterations_per_call", per_call(e[Event::PhantomIteration] + e[Event::PhantomPaperIteration])},
            {"early_out_rejects_per_call",
             per_call(e[Event::PhantomEarlyReject] + e[Event::PhantomCylinderTest] -
                      std::min(e[Event::PhantomCylinderTest], e[Event::PhantomSetup]))},
            {"second_end_per_call", per_call(e[Event::PhantomSecondEnd])}};
    }
    const MemoryBreakdown& mem = m.memory;
    j["memory_bytes"] = {{"tlas_nodes", mem.tlas_nodes},     {"blas_nodes", mem.blas_nodes},
                         {"instances", mem.instances},       {"custom_prims", mem.custom_prims},
                         {"triangles", mem.triangles},       {"lss_prims", mem.lss_prims},
                         {"oriented_children", mem.oriented_children},
                         {"leaf_obbs", mem.leaf_obbs},       {"blas_headers", mem.blas_headers},
                         {"strip_buffers", mem.strip_buffers},
                         {"acceleration", mem.acceleration()},
                         {"common", mem.common},             {"total", mem.total()}};
    j["structures"] = {{"width", m.structures.width},
                       {"tlas_nodes", m.structures.tlas_nodes},
                       {"blas_nodes", m.structures.blas_nodes},
                       {"instances", m.structures.instances},
                       {"custom_prims", m.structures.custom_prims},
                       {"triangles", m.structures.triangles},
                       {"lss_prims", m.structures.lss_prims},
                       {"oriented_children", m.structures.oriented_children},
                       {"leaf_obbs", m.structures.leaf_obbs},
                       {"strip_vertices", m.structures.strip_vertices},
                       {"strip_triangles", m.structures.strip_triangles},
                       {"blases", m.structures.blases}};
    j["simulator"] = {{"build_seconds", m.build_seconds},
                      {"trace_seconds", m.frame.trace_seconds},
                      {"rays_per_second", m.frame.trace_seconds > 0
                                              ? static_cast<double>(m.frame.rays_traced) / m.frame.trace_seconds
                                              : 0.0},
                      {"structure_bytes", m.simulator_bytes}};
    return j;
}

// "2.86x [2.61-3.10]": the speedup and its 90 % interval, when there is one.
std::string format_speedup_interval(double s, const std::optional<std::array<double, 2>>& i) {
    if (!i) return format_speedup(s);
    return format_speedup(s) + " [" + format_sig((*i)[0], 3) + "-" + format_sig((*i)[1], 3) + "]";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> resolution_notes(const RunResult& run) {
    std::vector<std::pair<std::string, std::string>> notes;
    if (run.config.workload.type == WorkloadType::Rays) return notes;
    const auto pixels = static_cast<std::uint64_t>(run.camera.width) * static_cast<std::uint64_t>(run.camera.height);
    for (const CostModel& c : run.costs)
        if (std::string note = resolution_note(c, pixels); !note.empty()) notes.emplace_back(c.name, std::move(note));
    return notes;
}

nlohmann::ordered_json report_json(const RunResult& run, const nlohmann::ordered_json* break_even) {
    nlohmann::ordered_json j;
    j["rtcsim_version"] = kVersion;
    j["name"] = run.config.name;
    if (!run.sweep_label.empty()) {
        j["sweep_point"] = run.point.values;
        j["sweep_label"] = run.sweep_label;
    }
    j["config"] = run.point.config;
    const SceneStats& s = run.scene;
    j["scene"] = scene_stats_json(s);
    j["scene"]["primitive_kind"] = std::string(kind_name(run.config.kind));
    j["scene"]["primitives"] = run.primitives;
    if (!run.scene_notes.empty()) j["scene"]["notes"] = run.scene_notes;
    j["scene"]["surface_area"] = {{"aabb", run.areas.aabb},
                                  {"obb_paper", run.areas.obb_paper},
                                  {"obb_tight", run.areas.obb_tight},
                                  {"aabb_over_obb_paper", run.areas.ratio_paper()},
                                  {"aabb_over_obb_tight", run.areas.ratio_tight()}};
    if (run.config.workload.type != WorkloadType::Rays) {
        const Camera& c = run.camera;  // resolved: what "auto" framing chose
        j["camera"] = {{"position", {c.position.x, c.position.y, c.position.z}},
                       {"target", {c.target.x, c.target.y, c.target.z}},
                       {"up", {c.up.x, c.up.y, c.up.z}},
                       {"fov_deg", c.fov_deg},
                       {"width", c.width},
                       {"height", c.height}};
    }
    j["cost_presets"] = nlohmann::ordered_json::array();
    for (const CostModel& c : run.costs) j["cost_presets"].push_back(c.name);
    nlohmann::ordered_json resolution = nlohmann::ordered_json::object();
    for (const auto& [preset, note] : resolution_notes(run)) resolution[preset] = note;
    if (!resolution.empty()) j["resolution_notes"] = resolution;
    j["memory_preset"] = run.memory.name;
    if (run.sample) j["sampling"] = sampling_json(run);
    nlohmann::ordered_json methods;
    for (const MethodRun& m : run.methods) methods[m.method] = method_json(m, run);
    j["methods"] = methods;
    nlohmann::ordered_json speedups = nlohmann::ordered_json::object(), overhead = nlohmann::ordered_json::object();
    nlohmann::ordered_json intervals = nlohmann::ordered_json::object(), sampled = nlohmann::ordered_json::object();
    for (const MethodRun& m : run.methods) {
        if (m.method == run.config.baseline) continue;
        nlohmann::ordered_json per_preset, interval_per_preset = nlohmann::ordered_json::object();
        nlohmann::ordered_json sampled_per_preset = nlohmann::ordered_json::object();
        for (std::size_t p = 0; p < run.costs.size(); ++p) {
            const double s = run.speedup(m.method, p);
            per_preset[run.costs[p].name] = s > 0 ? nlohmann::ordered_json(s) : nlohmann::ordered_json();
            // Presets without draws get no entry; "uncertainty" below says why.
            if (const auto i = run.speedup_interval(m.method, p)) interval_per_preset[run.costs[p].name] = *i;
            if (const auto e = run.sampled_speedup(m.method, p)) sampled_per_preset[run.costs[p].name] = e->interval;
        }
        speedups[m.method] = per_preset;
        intervals[m.method] = interval_per_preset;
        sampled[m.method] = sampled_per_preset;
        const double o = run.memory_overhead_percent(m.method);
        if (!std::isnan(o)) overhead[m.method] = o;
    }
    j["speedup_over_" + run.config.baseline] = speedups;
    j["speedup_interval_over_" + run.config.baseline] = intervals;
    // The sampling error of a sampled run's speedups (95 %), beside the
    // calibration band above; absent when every tile was traced.
    if (run.sample) j["speedup_sampling_interval_over_" + run.config.baseline] = sampled;
    nlohmann::ordered_json why = nlohmann::ordered_json::object();
    for (std::size_t p = 0; p < run.costs.size(); ++p) {
        const std::string reason = run.no_interval_reason(p);
        why[run.costs[p].name] = !reason.empty() ? reason
                                 : "90 % interval (5th-95th percentile) over " + std::to_string(run.config.uncertainty.draws) +
                                       " draws of the preset's fitted costs from its covariance: calibration uncertainty only, "
                                       "not model-structure error";
    }
    j["uncertainty"] = why;
    j["memory_overhead_percent"] = overhead;
    if (!run.config.break_even.empty()) j["break_even"] = break_even ? *break_even : break_even_json(run);
    j["wall_seconds"] = {{"load_scene", run.load_seconds},
                         {"convert", run.convert_seconds},
                         {"total", run.total_seconds}};
    if (!run.point.provenance.is_null()) j["provenance"] = run.point.provenance;  // set by sim/app (provenance.h)
    return j;
}

// One row per run; per method its cycles and IS calls per ray under the
// primary (first) cost preset, named in the "cost preset" column (every preset:
// speedups.csv and results.csv), per non-baseline method its speedup; per
// method its total memory in MiB, and the memory overhead over the baseline.
Table summary_table(const std::vector<RunResult>& runs) {
    std::vector<std::string> names;  // every method of any run, in first-seen order
    for (const RunResult& r : runs)
        for (const MethodRun& m : r.methods)
            if (std::find(names.begin(), names.end(), m.method) == names.end()) names.push_back(m.method);
    const std::string baseline = runs.empty() ? "ref" : runs.front().config.baseline;
    std::vector<std::string> others;
    for (const std::string& n : names)
        if (n != baseline) others.push_back(n);
    std::vector<std::string> header{"run", "kind", "prims", "rays", "cost preset"};
    for (const std::string& n : names) header.push_back(n + " cyc/ray");
    for (const std::string& n : names) header.push_back(n + " IS/ray");
    for (const std::string& n : others) header.push_back(n + " speedup");
    header.push_back("AABB/OBB area");
    for (const std::string& n : names) header.push_back(n + " MiB");
    for (const std::string& n : others) header.push_back(n + " mem overhead");
    Table t(header);
    for (const RunResult& r : runs) {
        const auto per_ray = [](const MethodRun* m, double v) -> std::string {
            if (!m) return "-";
            if (!m->runnable) return "n/a";
            return m->rays() ? format_sig(v / static_cast<double>(m->rays()), 4) : "-";
        };
        const MethodRun* any = nullptr;
        for (const MethodRun& m : r.methods)
            if (!any && m.runnable) any = &m;
        std::vector<std::string> row{r.sweep_label.empty() ? r.config.name : r.sweep_label,
                                     std::string(kind_name(r.config.kind)),
                                     format_thousands(static_cast<std::int64_t>(r.primitives)),
                                     any ? format_thousands(static_cast<std::int64_t>(any->rays())) : "-",
                                     r.costs.empty() ? "-" : r.costs.front().name};
        for (const std::string& n : names) {
            const MethodRun* m = r.find(n);
            const bool priced = m && m->runnable && !m->priced.empty() && m->priced[0].supported;
            row.push_back(m && m->runnable && !priced ? "n/a" : per_ray(m, priced ? m->priced[0].total_cycles : 0.0));
        }
        for (const std::string& n : names) {
            const MethodRun* m = r.find(n);
            row.push_back(per_ray(m, m && m->runnable ? static_cast<double>(m->totals()[Event::IsCall]) : 0.0));
        }
        for (const std::string& n : others) {
            const double s = r.speedup(n);
            row.push_back(s > 0 ? format_speedup_interval(s, r.speedup_interval(n)) : "n/a");
        }
        row.push_back(format_sig(r.areas.ratio_paper(), 3));
        for (const std::string& n : names) {
            const MethodRun* m = r.find(n);
            row.push_back(m && m->runnable ? format_sig(m->memory.total() / (1024.0 * 1024.0), 4) : "n/a");
        }
        for (const std::string& n : others) {
            const double o = r.memory_overhead_percent(n);
            row.push_back(std::isnan(o) ? "-" : format_sig(o, 3) + "%");
        }
        t.add_row(row);
    }
    return t;
}

// One row per run and method: its speedup over the baseline under every cost
// preset ("n/a" where the preset's hardware lacks a feature the method needs
// or the method cannot run), its IS calls per ray and memory overhead.
Table speedup_table(const std::vector<RunResult>& runs) {
    std::vector<std::string> header{"run", "method", "IS/ray", "mem overhead"};
    if (!runs.empty())
        for (const CostModel& c : runs.front().costs) header.push_back(c.name);
    Table t(header);
    for (const RunResult& r : runs) {
        const std::string label = r.sweep_label.empty() ? r.config.name : r.sweep_label;
        for (const MethodRun& m : r.methods) {
            std::vector<std::string> row{label, m.method};
            if (!m.runnable) {
                row.push_back("n/a");
                row.push_back("-");
                for (std::size_t p = 0; p < r.costs.size(); ++p) row.push_back("n/a");
                t.add_row(row);
                continue;
            }
            const double rays = static_cast<double>(m.rays());
            row.push_back(rays > 0 ? format_sig(static_cast<double>(m.totals()[Event::IsCall]) / rays, 4) : "-");
            const double o = r.memory_overhead_percent(m.method);
            row.push_back(m.method == r.config.baseline ? "0%" : std::isnan(o) ? "-" : format_sig(o, 3) + "%");
            for (std::size_t p = 0; p < r.costs.size(); ++p) {
                if (m.method == r.config.baseline) {
                    row.push_back(m.priced[p].supported ? "1.00x" : "n/a");
                    continue;
                }
                const double s = r.speedup(m.method, p);
                // "hyp.": priced, but the machine does not build it (its preset says why).
                const bool hypothetical = !r.costs[p].hypothetical_reason(m.method).empty();
                row.push_back(s > 0 ? format_speedup_interval(s, r.speedup_interval(m.method, p)) + (hypothetical ? " hyp." : "")
                                    : "n/a");
            }
            t.add_row(row);
        }
    }
    return t;
}

}  // namespace rtc
