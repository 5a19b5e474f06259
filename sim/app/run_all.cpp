#include "sim/app/run_all.h"

#include "sim/app/calibrate_runs.h"
#include "sim/app/output_dir.h"
#include "sim/app/provenance.h"
#include "sim/calibrate/calibrate_report.h"
#include "sim/execution/interrupt.h"
#include "sim/util/json_file.h"
#include "sim/util/paths.h"
#include "sim/config/input_files.h"
#include "sim/config/run_config.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"
#include "sim/config/sweep.h"
#include "sim/config/work_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <iostream>

namespace rtc {

namespace {

std::string sanitize(const std::string& label) {
    std::string s;
    for (const char c : label) {
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' || c == '=')
            s += c;
        else if (!s.empty() && s.back() != '_')
            s += '_';
    }
    // Directory names stay well under file-system limits (255 bytes).
    if (s.size() > 96) s.resize(96);
    return s.empty() ? "run" : s;
}

// `simulate calibrate`: fit the config's chosen costs to its target speedups
// by re-pricing the counts each run recorded (no tracing again).
void calibrate_runs(std::vector<RunResult>& runs, const CalibratePlan& plan, const std::string& out, bool quiet,
                    bool force) {
    std::vector<RunResult*> pointers;
    for (RunResult& r : runs) pointers.push_back(&r);
    // The runs are done with their waves: move them into the fit.
    const CalibrationOutcome fit = calibrate_results(pointers, plan, [](RunResult&, MethodRun& m) {
        return std::make_shared<const WarpTrace>(std::move(m.frame.warp_trace));
    });
    const std::string report = calibration_report_markdown(fit.result);
    write_text_file((std::filesystem::path(out) / "calibration.md").string(), report);
    const std::string preset = calibrated_preset_json(fit.result);
    write_text_file((std::filesystem::path(out) / "calibrated_preset.json").string(), preset);
    if (!fit.desc.output.empty()) {
        const std::string path = calibrate_output_path(plan, force);
        write_text_file(path, preset);
        if (!quiet) std::cerr << "fitted preset written to " << path << "\n";
    }
    std::cout << "\n" << report;
    if (!fit.skipped.empty() && !quiet)
        std::cerr << fit.skipped.size() << " run(s) without a target were not fitted\n";
}

}  // namespace

RunResult run_point(const RunPlan& plan, std::size_t i, RunContext context) {
    context.limits = plan.limits;
    RunResult r = run_simulation(plan.parsed.at(i), context);
    r.point.config = plan.points[i].config;
    r.point.values = plan.points[i].values;
    r.sweep_label = plan.points[i].label;
    r.point.provenance = provenance_json(r, context.threads, plan.command_line);
    return r;
}

std::optional<RunResult> reprice_point(const RunPlan& plan, std::size_t i, const RunResult& traced,
                                       unsigned threads) {
    std::optional<RunResult> r = reprice_run(traced, plan.parsed.at(i));
    if (!r) return r;
    r->point.config = plan.points[i].config;
    r->point.values = plan.points[i].values;
    r->sweep_label = plan.points[i].label;
    r->point.provenance = provenance_json(*r, threads, plan.command_line);
    return r;
}

int run_all(const CliOptions& cli) {
    RunPlan plan = plan_config_text(cli.config, read_text_file(cli.config), cli.sets, cli.limits);
    plan.command_line = cli.command_line;
    // Before any work: a calibrate output that would overwrite a file.
    if (cli.calibrate) {
        if (!plan.calibrate)
            throw InputError(cli.config + ": /calibrate: missing (simulate calibrate needs a calibrate block)");
        (void)calibrate_output_path(*plan.calibrate, cli.limits.force);
    }
    const std::string out = cli.out ? *cli.out : default_output_dir(plan.parsed.front().name, "", cli.config);
    OutputDir owned(out, cli.limits.force, input_paths(plan.parsed, plan.file));  // locked until the run ends
    const int status = run_planned(plan, cli, out, nullptr);
    owned.finish();
    return status;
}

int run_planned(const RunPlan& plan, const CliOptions& cli, const std::string& out, const PointFrames* frames) {
    const nlohmann::json& config = plan.config;
    const std::vector<SweepPoint>& points = plan.points;
    const std::vector<RunConfig>& parsed = plan.parsed;
    const WorkEstimate& work = plan.work;
    if (!cli.quiet) {
        std::cerr << "simulate " << plan.file << " -> " << out << "\n";
        if (cli.show_config) std::cerr << "effective configuration:\n" << config.dump(2) << "\n";
        if (points.size() > 1) std::cerr << points.size() << " sweep points\n";
        std::cerr << "estimate: " << count_text(work.rays) << " rays, "
                  << (work.primitives > 0 ? count_text(work.primitives) + " primitives, " : std::string())
                  << format_estimate_bytes(work.memory_bytes) << " of memory"
                  << (work.break_even > 0 ? ", " + count_text(work.break_even) + " break-even cell prices" : std::string())
                  << "\n";
    }
    std::vector<RunResult> runs;
    // The last point in full (per-pixel data too) while the next point has
    // the same trace: it is re-priced from it instead of traced again.
    std::optional<RunResult> traced;
    std::vector<std::string> point_dirs;  // relative to `out`; "" for a single run
    std::vector<nlohmann::ordered_json> break_even;  // per point: report.json's "break_even"
    for (std::size_t i = 0; i < points.size(); ++i) {
        throw_if_interrupted();  // Ctrl-C between sweep points (sim/execution/interrupt.h)
        const std::string dir = points.size() == 1
                                    ? out
                                    : (std::filesystem::path(out) /
                                       (std::to_string(i) + "_" + sanitize(points[i].label))).string();
        make_dir(dir);
        if (!cli.quiet && points.size() > 1)
            std::cerr << "[" << i + 1 << "/" << points.size() << "] " << points[i].label << "\n";
        std::optional<RunResult> repriced;
        if (traced) repriced = reprice_point(plan, i, *traced, cli.threads);
        if (repriced && !cli.quiet) std::cerr << "same trace as the previous point: re-priced, not traced\n";
        RunContext ctx;
        ctx.threads = cli.threads;
        ctx.quiet = cli.quiet;
        ctx.record_warps = cli.calibrate;
        ctx.out_dir = dir;
        if (frames) ctx.frame_source = [frames, i](const std::string& method) { return (*frames)(i, method); };
        RunResult r = repriced ? std::move(*repriced) : run_point(plan, i, ctx);
        throw_if_interrupted();  // not written: an interrupted run leaves no report.json
        {
            // The arrays (140 MB on the head frame, mostly the kernel's copy
            // into the page cache) are written while the pictures are
            // encoded; an error of either is reported, the pictures' first.
            std::future<void> arrays;
            if (parsed[i].output.arrays && cli.threads != 1)
                arrays = std::async(std::launch::async, [&] { (void)write_arrays(r, dir); });
            else if (parsed[i].output.arrays)
                (void)write_arrays(r, dir);
            if (parsed[i].output.images) write_images(r, dir, cli.threads);
            if (arrays.valid()) arrays.get();
        }
        // The maps' grids once per point, for the pictures and the reports.
        const BreakEvenGrids grids = break_even_grids(r);
        (void)write_break_even_maps(r, grids, dir);
        break_even.push_back(break_even_json(r, grids));
        // Last of the point's files (the directory's mark says when the run is complete).
        write_text_file((std::filesystem::path(dir) / "report.json").string(),
                        report_json(r, &break_even.back()).dump(2) + "\n");
        traced.reset();
        // (Ray and hit files are written while tracing: such points trace.)
        // (A preset may choose the BVH width: execution.bvh_width.)
        if (i + 1 < points.size() && same_trace(points[i].config, points[i + 1].config) &&
            parsed[i].build.tlas.width == parsed[i + 1].build.tlas.width &&
            !parsed[i + 1].output.write_rays && !parsed[i + 1].output.write_hits)
            traced = r;
        // Free the per-pixel data of finished points: sweeps keep only totals.
        for (MethodRun& m : r.methods) {
            m.frame.pixel_counts = {};
            m.frame.ray_counts = {};
            for (std::size_t w = 1; w < m.frame.warp.size(); ++w) m.frame.warp[w].pixel_cycles = {};
            m.frame.radiance = {};
        }
        runs.push_back(std::move(r));
        point_dirs.push_back(points.size() == 1 ? "" : std::filesystem::path(dir).filename().string());
        write_sweep_outputs(runs, point_dirs, out, &break_even);
    }
    write_sweep_plots(runs, out);
    if (cli.calibrate) calibrate_runs(runs, *plan.calibrate, out, cli.quiet, cli.limits.force);
    std::cout << summary_table(runs).to_console();
    if (!cli.quiet) {
        std::vector<std::string> notes;  // each preset's once (report.json: resolution_notes)
        for (const RunResult& r : runs)
            for (auto& [preset, n] : resolution_notes(r))
                if (std::find(notes.begin(), notes.end(), n) == notes.end()) notes.push_back(std::move(n));
        for (const std::string& n : notes) std::cerr << "note: " << n << "\n";
        if (!runs.empty() && runs.front().sample) {
            const TileSample& s = *runs.front().sample;
            std::cerr << "note: sampled: " << s.traced_tiles() << " of " << s.tiles() << " tiles traced (1/" << s.k()
                      << ", seed " << s.seed() << "), totals scaled by " << s.k()
                      << "; each speedup's 95 % sampling interval is in results.csv (sampling_low, sampling_high) "
                         "and report.json (docs/sampling.md)\n";
        }
        std::cerr << "outputs in " << out << "/\n";
    }
    return 0;
}

namespace {

// The pilot's k: 1/64 of the tiles, or fewer strata's worth on a small
// frame so that the pilot still draws about 30 strata (60 tiles).
std::uint32_t pilot_k(const RunConfig& c) {
    const auto tiles = static_cast<std::uint64_t>((c.workload.width + 7) / 8) * static_cast<std::uint64_t>((c.workload.height + 3) / 4);
    return static_cast<std::uint32_t>(std::clamp<std::uint64_t>(tiles / 60, 1, 64));
}

}  // namespace

int print_sampling_estimate(const CliOptions& cli) {
    const double target = *cli.target_error;
    std::vector<std::string> sets = cli.sets;
    RunPlan plan = plan_config_text(cli.config, read_text_file(cli.config), sets, cli.limits);
    const bool given = sample_k(plan.parsed.front().sampling.fraction) > 1;
    if (!given) {  // the pilot's fraction, from the first point's frame
        const std::uint32_t k0 = pilot_k(plan.parsed.front());
        sets.push_back("sampling.fraction=" + nlohmann::json(1.0 / k0).dump());
        plan = plan_config_text(cli.config, read_text_file(cli.config), sets, cli.limits);
    }
    plan.command_line = cli.command_line;
    std::uint32_t k_all = UINT32_MAX;
    for (std::size_t i = 0; i < plan.points.size(); ++i) {
        RunContext ctx;
        ctx.threads = cli.threads;
        ctx.quiet = cli.quiet;
        const RunResult r = run_point(plan, i, ctx);
        const std::uint32_t k0 = r.sample ? r.sample->k() : 1;
        nlohmann::ordered_json line;
        line["point"] = i;
        if (!r.sweep_label.empty()) line["label"] = r.sweep_label;
        line["pilot_fraction"] = 1.0 / k0;
        // The widest relative half-width over the speedups of every method and preset.
        double worst = 0.0;
        nlohmann::ordered_json where;
        for (const MethodRun& m : r.methods) {
            if (m.method == r.config.baseline || !m.runnable) continue;
            for (std::size_t p = 0; p < r.costs.size(); ++p) {
                const auto e = r.sampled_speedup(m.method, p);
                if (!e || !(e->value > 0.0)) continue;
                const double rel = (e->interval[1] - e->interval[0]) / 2.0 / e->value;
                if (rel < worst && !where.empty()) continue;
                worst = rel;
                where = {{"method", m.method}, {"preset", r.costs[p].name}, {"speedup", e->value},
                         {"interval", e->interval}, {"relative_half_width", rel}};
            }
        }
        double trace = 0.0, build = 0.0;
        for (const MethodRun& m : r.methods) {
            trace += m.frame.trace_seconds;
            build += m.build_seconds;
        }
        const std::uint32_t k = r.sample ? suggested_k(k0, worst, target) : 1;
        line["widest"] = where;
        line["suggested_fraction"] = 1.0 / k;
        line["pilot_trace_seconds"] = trace;
        line["build_seconds"] = build;
        line["estimated_trace_seconds"] = trace * k0 / k;
        std::cout << line.dump() << std::endl;
        k_all = std::min(k_all, k);
    }
    if (k_all == UINT32_MAX) k_all = 1;
    nlohmann::ordered_json last = {{"target_error", target},
                                   {"suggested_fraction", 1.0 / k_all},
                                   {"option", k_all > 1 ? "--sample " + nlohmann::json(1.0 / k_all).dump()
                                                        : std::string("(no sampling: trace every tile)")},
                                   {"rule", "(1 - f) / f = (1 - f0) / f0 x (target / pilot half-width)^2, f = 1/k "
                                            "rounded down; docs/sampling.md"}};
    std::cout << last.dump() << std::endl;
    return 0;
}

}  // namespace rtc
