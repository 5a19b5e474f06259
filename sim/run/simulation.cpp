#include "sim/run/simulation.h"

#include "sim/execution/interrupt.h"
#include "sim/workload/ray_file.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <climits>
#include <cstdint>
#include <limits>

namespace rtc {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

RayWorkload make_frame(const WorkloadDesc& w, const Aabb& bounds) {
    RayWorkload f;
    if (w.type == WorkloadType::Rays) {
        f.from_camera = false;
        f.rays = read_ray_file(w.rays_file);  // resolved when the config was parsed
        return f;
    }
    f.camera = make_camera(w, bounds);
    f.path = path_options(w);
    return f;
}

// The config's cost and memory presets (loaded and checked when it was
// parsed) into `r`, and its warp presets, in order. The warp presets group
// rays alike (parse_run_config checked it): the first one's grouping serves
// them all.
void take_presets(RunResult& r, const RunConfig& c, std::vector<const CostModel*>& warp_presets) {
    r.costs.clear();
    for (const auto& cost : c.costs) r.costs.push_back(*cost);
    r.memory = *c.memory;
    r.warp_grouping.reset();
    for (const CostModel& cost : r.costs) {
        if (!cost.execution.warp()) continue;
        if (!r.warp_grouping) r.warp_grouping = cost.execution;
        warp_presets.push_back(&cost);
    }
}

// The cost models drawn from each preset's uncertainty block (run
// intervals); a warp preset's are priced per wave as the frame runs
// (FrameOptions::warp_draws) and kept with its totals (PresetWarp::draws).
struct Draws {
    std::vector<std::vector<CostModel>> models;  // per preset
    std::vector<DrawSet> warp_sets;              // FrameOptions::warp_draws
};

Draws make_draws(const std::vector<CostModel>& costs, const UncertaintyOptions& u) {
    Draws d;
    for (const CostModel& cost : costs) d.models.push_back(draw_cost_models(cost, static_cast<std::size_t>(u.draws), u.seed));
    for (std::size_t k = 0; k < costs.size(); ++k) {
        if (!costs[k].execution.warp() || d.models[k].empty()) continue;
        d.warp_sets.push_back({&costs[k], {}});
        for (const CostModel& m : d.models[k]) d.warp_sets.back().draws.push_back(&m);
    }
    return d;
}

// Prices a traced method under every cost preset of `r` and its structures
// under r's memory preset. A warp preset's totals, draws and per-pixel
// cycles are the frame's of the same name (FrameResult::warp_of).
void price_method(MethodRun& m, const RunResult& r, const MethodEntry& method, const Draws& draws) {
    m.priced.clear();
    m.warp.clear();
    m.roof.clear();
    const std::uint32_t k = r.sample ? r.sample->k() : 1;
    std::vector<const PresetWarp*> warp(r.costs.size(), nullptr);
    for (std::size_t p = 0; p < r.costs.size(); ++p) {
        if (r.costs[p].execution.warp()) warp[p] = m.frame.warp_of(r.costs[p].name);
        PresetPrice priced = price_preset(m.frame.totals, r.costs[p], warp[p] ? &warp[p]->totals : nullptr,
                                          r.config, method.info.needs, k);
        m.priced.push_back(std::move(priced.run));
        m.warp.push_back(priced.warp);
        m.roof.push_back(priced.roof);
    }
    // The draws of each preset's uncertainty block, on the same roofline.
    m.draw_cycles.assign(r.costs.size(), {});
    for (std::size_t p = 0; p < r.costs.size(); ++p)
        for (std::size_t d = 0; d < draws.models[p].size(); ++d)
            m.draw_cycles[p].push_back(k * (warp[p] ? warp[p]->draws.at(d).cycles(m.roof[p])
                                                    : price(m.frame.totals, draws.models[p][d]).total_cycles));
    m.memory = price_memory(m.structures, r.memory, r.config.kind, r.primitives, r.mesh_vertices, r.mesh_triangles);
    m.sampled.reset();
    if (!r.sample) return;
    // A sampled frame: its interval from the traced tiles (a warp preset's
    // per-pixel cycles; per-ray presets from the counts).
    std::vector<const std::vector<float>*> warp_pixels(r.costs.size(), nullptr);
    std::vector<double> totals;
    for (std::size_t p = 0; p < r.costs.size(); ++p) {
        totals.push_back(m.priced[p].total_cycles);
        if (warp[p] && !warp[p]->pixel_cycles.empty()) warp_pixels[p] = &warp[p]->pixel_cycles;
    }
    m.sampled = estimate_sampled(m.frame, *r.sample, r.costs, warp_pixels, totals);
}

}  // namespace

Roofline method_roofline(const CostModel& cost, const RunConfig& r, const std::vector<std::string>& needs) {
    const bool runs_programs = std::find(needs.begin(), needs.end(), "custom_primitives") != needs.end();
    try {
        return roofline(cost.execution.sm, pipeline_program(r.kind, r.trace.phantom.program, runs_programs),
                        cost.execution.warp_width);
    } catch (const std::invalid_argument& e) {
        throw InputError("cost preset " + cost.name + ": " + e.what());
    }
}

PresetPrice price_preset(const EventTotals& totals, const CostModel& cost, const WarpTotals* warp,
                         const RunConfig& config, const std::vector<std::string>& needs, std::uint32_t sample_k) {
    PresetPrice p;
    p.roof = method_roofline(cost, config, needs);
    p.run = price(totals, cost);
    p.run.execution = cost.execution.kind;
    if (warp) {
        p.warp = *warp;
        p.run.total_cycles = p.warp.cycles(p.roof);
    }
    p.run.missing_feature = cost.missing_feature(needs);
    p.run.supported = p.run.missing_feature.empty();
    scale_priced(p.run, sample_k);
    scale_warp(p.warp, sample_k);
    return p;
}

const MethodRun* RunResult::find(std::string_view name) const {
    for (const MethodRun& r : methods)
        if (r.method == name) return &r;
    return nullptr;
}

double RunResult::speedup(std::string_view name, std::size_t preset) const {
    const MethodRun* base = baseline();
    const MethodRun* other = find(name);
    if (!base || !other || !base->runnable || !other->runnable || preset >= base->priced.size() ||
        preset >= other->priced.size() || !base->priced[preset].supported ||
        !other->priced[preset].supported || other->priced[preset].total_cycles <= 0.0)
        return 0.0;
    return base->priced[preset].total_cycles / other->priced[preset].total_cycles;
}

std::optional<std::array<double, 2>> RunResult::speedup_interval(std::string_view name, std::size_t preset) const {
    const double point = speedup(name, preset);
    const MethodRun* base = baseline();
    const MethodRun* other = find(name);
    if (point <= 0.0 || preset >= base->draw_cycles.size() || preset >= other->draw_cycles.size() ||
        base->draw_cycles[preset].empty() || base->draw_cycles[preset].size() != other->draw_cycles[preset].size())
        return std::nullopt;
    std::vector<double> s;  // draw d prices both methods with the same costs
    for (std::size_t d = 0; d < base->draw_cycles[preset].size(); ++d)
        s.push_back(base->draw_cycles[preset][d] / other->draw_cycles[preset][d]);
    return interval_90(std::move(s), point);
}

std::optional<SampledEstimate> RunResult::sampled_speedup(std::string_view name, std::size_t preset) const {
    const double point = speedup(name, preset);
    const MethodRun* base = baseline();
    const MethodRun* other = find(name);
    if (!sample || point <= 0.0 || !base->sampled || !other->sampled || preset >= base->sampled->tile_cycles.size() ||
        preset >= other->sampled->tile_cycles.size() || base->sampled->tile_cycles[preset].empty() ||
        other->sampled->tile_cycles[preset].empty())
        return std::nullopt;
    return centred(estimate_ratio(base->sampled->tile_cycles[preset], other->sampled->tile_cycles[preset], sample->k()),
                   point);
}

std::string RunResult::no_interval_reason(std::size_t preset) const {
    if (preset >= costs.size()) return "no such preset";
    if (!costs[preset].uncertainty) return "no covariance in the preset (a guess): no interval";
    if (config.uncertainty.draws == 0) return "uncertainty.draws is 0: no interval";
    return "";
}

double RunResult::memory_overhead_percent(std::string_view name) const {
    const MethodRun* base = baseline();
    const MethodRun* other = find(name);
    if (!base || !other || !base->runnable || !other->runnable || base->memory.total() <= 0.0)
        return std::numeric_limits<double>::quiet_NaN();
    return 100.0 * (other->memory.total() - base->memory.total()) / base->memory.total();
}

RunResult run_simulation(const RunConfig& c, const RunContext& ctx) {
    const auto t_start = std::chrono::steady_clock::now();
    RunResult r;
    r.config = c;
    std::vector<const CostModel*> warp_presets;
    take_presets(r, c, warp_presets);
    const Draws draws = make_draws(r.costs, c.uncertainty);

    const auto t_load = std::chrono::steady_clock::now();
    const Scene scene = load_scene(c.scene);
    r.load_seconds = seconds_since(t_load);
    throw_if_interrupted();  // Ctrl-C: between phases (sim/execution/interrupt.h)
    check_work(estimate_scene_work(c, scene), ctx.limits, c.file);
    const auto t_convert = std::chrono::steady_clock::now();
    const Geometry geometry = make_geometry(scene, c.kind, c.subdivision);
    r.primitives = geometry.primitive_count();
    r.scene = compute_stats(scene);
    r.scene_notes = scene.notes;
    for (const std::string& note : scene.notes)  // warnings, printed under --quiet too
        std::fprintf(stderr, "warning: %s (report.json: scene.notes)\n", note.c_str());
    if (r.scene.thin_segments > 0)  // a warning, printed under --quiet too
        std::fprintf(stderr,
                     "warning: %s: %zu of %zu segments are thinner than %g float ulps of their position "
                     "(radius below %g x their largest coordinate): their bounds, and so the counts, "
                     "depend on where the scene sits (report.json: scene.thin_segments)\n",
                     c.file.c_str(), r.scene.thin_segments, r.scene.segments, kThinUlps, kThinUlps * 0x1p-23);
    r.areas = area_stats(geometry.prims, ctx.threads);
    r.mesh_vertices = scene.mesh.vertices.size();
    r.mesh_triangles = scene.mesh.triangles.size();
    r.convert_seconds = seconds_since(t_convert);

    RayWorkload frame = make_frame(c.workload, geometry_bounds(geometry));
    r.camera = frame.camera;
    // The sample's tiles are the warp presets' tiles (8 x 4 without one):
    // the same for every method, thread count and band.
    if (frame.from_camera)
        r.sample = TileSample::make(frame.camera.width, frame.camera.height,
                                    r.warp_grouping ? r.warp_grouping->tile_width : 8,
                                    r.warp_grouping ? r.warp_grouping->tile_height : 4, c.sampling);
    bool rays_written = false;
    // Approximate methods (dots) are compared with the baseline on a sample of
    // the rays the baseline traced (hit_agreement.h), which it records for
    // that. Not in sharded runs: a band's rays are not the frame's.
    const bool compare_hits =
        !ctx.frame_source && ctx.bands == 0 &&
        std::find(c.methods.begin(), c.methods.end(), c.baseline) != c.methods.end() &&
        std::any_of(c.methods.begin(), c.methods.end(),
                    [](const std::string& name) { return find_method(name)->info.approximate; });
    std::optional<AgreementSample> baseline_sample;
    // Approximate methods traced before the baseline, kept built until its sample exists.
    std::vector<std::pair<std::size_t, std::unique_ptr<BuiltMethod>>> awaiting_sample;
    const auto compare_with_baseline = [&](MethodRun& m, const BuiltMethod& built) {
        m.agreement = measure_hit_agreement(built, geometry, c.trace, *baseline_sample, c.baseline, ctx.threads);
        if (!ctx.quiet)
            std::fprintf(stderr, "%s: hits agree with %s's on %.4f of %llu of its rays\n", m.method.c_str(),
                         c.baseline.c_str(), m.agreement->fraction(),
                         static_cast<unsigned long long>(m.agreement->rays));
    };
    for (const std::string& name : c.methods) {
        throw_if_interrupted();
        const MethodEntry& method = *find_method(name);  // names were checked when parsing
        MethodRun m;
        m.method = name;
        m.reason = not_applicable_reason(method, geometry);
        if (!m.reason.empty()) {
            m.runnable = false;
            r.methods.push_back(std::move(m));
            continue;
        }
        MethodOptions build = c.build;
        build.custom_blas.threads = build.triangle_blas.threads = build.tlas.threads = ctx.threads;
        m.instances = method.instance_count(geometry, build);
        if (m.instances > r.memory.instance_limit) {
            m.runnable = false;
            m.reason = std::to_string(m.instances) + " instances exceed the instance limit of " +
                       std::to_string(r.memory.instance_limit) + " (" + r.memory.name + ")";
            r.methods.push_back(std::move(m));
            continue;
        }
        const auto t_build = std::chrono::steady_clock::now();
        if (!ctx.quiet) std::fprintf(stderr, "build %s: %llu instances...", name.c_str(),
                                     static_cast<unsigned long long>(m.instances));
        std::unique_ptr<BuiltMethod> built = method.build(geometry, build);
        m.build_seconds = seconds_since(t_build);
        if (!ctx.quiet) std::fprintf(stderr, " done in %.2f s\n", m.build_seconds);
        throw_if_interrupted();  // a build is not interruptible inside: core knows nothing of signals
        m.structures = built->structures();
        m.simulator_bytes = built->simulator_bytes();
        FrameOptions fo;
        fo.threads = ctx.threads;
        fo.progress = !ctx.quiet;
        fo.label = "trace " + name;
        const bool sample_baseline = compare_hits && name == c.baseline;
        const bool write_rays_file = c.output.write_rays && !rays_written;
        fo.record_hits = c.output.write_hits || sample_baseline;
        fo.record_rays = write_rays_file || sample_baseline;
        fo.warp = r.warp_grouping ? &*r.warp_grouping : nullptr;
        fo.warp_presets = warp_presets;
        fo.warp_draws = draws.warp_sets;
        // Break-even maps re-price the recorded waves (their effective counts).
        fo.record_warps = (ctx.record_warps || !c.break_even.empty()) && r.warp_grouping.has_value();
        fo.band = ctx.band;
        fo.bands = ctx.bands;
        fo.sample = r.sample ? &*r.sample : nullptr;
        m.frame = ctx.frame_source ? ctx.frame_source(name) : built->run(geometry, frame, c.trace, fo);
        if (!ctx.out_dir.empty() && write_rays_file) {
            write_ray_file((std::filesystem::path(ctx.out_dir) / "rays.bin").string(), m.frame.rays);
            rays_written = true;
        }
        if (!ctx.out_dir.empty() && c.output.write_hits) {
            HitFileWriter w((std::filesystem::path(ctx.out_dir) / ("hits_" + name + ".bin")).string());
            w.append(std::span<const TraceHit>(m.frame.hits));
            w.close();
        }
        if (sample_baseline) baseline_sample = agreement_sample(m.frame.rays, m.frame.hits);
        // Kept for the caller only where the config asked for them.
        if (!ctx.keep_rays || !write_rays_file) {
            m.frame.rays.clear();
            m.frame.rays.shrink_to_fit();
        }
        if (!ctx.keep_rays || !c.output.write_hits) {
            m.frame.hits.clear();
            m.frame.hits.shrink_to_fit();
        }
        price_method(m, r, method, draws);
        if (compare_hits && method.info.approximate) {
            if (baseline_sample) compare_with_baseline(m, *built);
            else awaiting_sample.emplace_back(r.methods.size(), std::move(built));
        }
        r.methods.push_back(std::move(m));
    }
    for (auto& [index, built] : awaiting_sample)
        if (baseline_sample) compare_with_baseline(r.methods[index], *built);
    r.total_seconds = seconds_since(t_start);
    return r;
}

std::optional<RunResult> reprice_run(const RunResult& traced, const RunConfig& c) {
    const auto t_start = std::chrono::steady_clock::now();
    RunResult r = traced;
    r.config = c;
    r.point = {};  // the app sets the point's own
    r.repriced = true;
    r.load_seconds = r.convert_seconds = 0.0;  // nothing loaded or converted: total_seconds is the pricing
    std::vector<const CostModel*> warp_presets;
    take_presets(r, c, warp_presets);
    if (r.warp_grouping && traced.warp_grouping && !r.warp_grouping->same_grouping(*traced.warp_grouping))
        return std::nullopt;
    const Draws draws = make_draws(r.costs, c.uncertainty);
    // The traced run's preset loaded from the same file as preset k, or null.
    const auto traced_preset = [&](std::size_t k) -> const CostModel* {
        for (std::size_t j = 0; j < traced.costs.size(); ++j)
            if (traced.config.cost_presets[j] == c.cost_presets[k]) return &traced.costs[j];
        return nullptr;
    };
    for (MethodRun& m : r.methods) {
        const MethodEntry& method = *find_method(m.method);
        const MethodRun& old = *traced.find(m.method);
        if (!old.runnable) {
            // Not traced: not applicable to the scene (no instances counted),
            // or stopped by the instance limit, which the memory preset sets.
            if (old.instances == 0) continue;
            if (old.instances <= r.memory.instance_limit) return std::nullopt;
            m.reason = std::to_string(m.instances) + " instances exceed the instance limit of " +
                       std::to_string(r.memory.instance_limit) + " (" + r.memory.name + ")";
            continue;
        }
        if (m.instances > r.memory.instance_limit) {
            m = MethodRun{};
            m.method = old.method;
            m.instances = old.instances;
            m.runnable = false;
            m.reason = std::to_string(m.instances) + " instances exceed the instance limit of " +
                       std::to_string(r.memory.instance_limit) + " (" + r.memory.name + ")";
            continue;
        }
        // Each warp preset's results: the traced ones (moved out of this
        // copy of the traced frame) when the traced run had the preset, else
        // re-priced from the recorded waves; its draws likewise (the
        // uncertainty options are part of the trace: same_trace). A
        // re-priced preset has no per-pixel cycles, so no sampling interval.
        std::vector<PresetWarp> traced_warp = std::move(m.frame.warp);
        m.frame.warp.clear();
        for (std::size_t k = 0; k < r.costs.size(); ++k) {
            if (!r.costs[k].execution.warp()) continue;
            PresetWarp w;
            bool traced_totals = false;
            if (const CostModel* before = traced_preset(k))
                for (PresetWarp& t : traced_warp)
                    if (t.preset == before->name) w = std::move(t), traced_totals = true;
            w.preset = r.costs[k].name;
            if (!traced_totals) {
                if (old.frame.warp_trace.waves() == 0) return std::nullopt;
                w.totals = old.frame.warp_trace.price(r.costs[k]);
            }
            if (w.draws.size() != draws.models[k].size()) {
                if (!draws.models[k].empty() && old.frame.warp_trace.waves() == 0) return std::nullopt;
                w.draws.clear();
                for (const CostModel& d : draws.models[k]) w.draws.push_back(old.frame.warp_trace.price(d));
            }
            m.frame.warp.push_back(std::move(w));
        }
        price_method(m, r, method, draws);
    }
    r.total_seconds = seconds_since(t_start);
    return r;
}

}  // namespace rtc
