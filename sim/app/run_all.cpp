#include "sim/app/run_all.h"

#include "sim/calibrate/calibrate.h"
#include "sim/calibrate/calibrate_config.h"
#include "sim/calibrate/calibrate_report.h"
#include "sim/util/json_file.h"
#include "sim/util/json_reader.h"
#include "sim/config/run_config.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"
#include "sim/config/sweep.h"
#include "sim/run/work_estimate.h"

#include <cstdio>
#include <filesystem>
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

void make_dir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw InputError(dir + ": cannot create output directory" + (ec ? " (" + ec.message() + ")" : ""));
    const std::string probe = (std::filesystem::path(dir) / ".write_test").string();
    std::FILE* f = std::fopen(probe.c_str(), "wb");
    if (!f) throw InputError(dir + ": output directory is not writable");
    std::fclose(f);
    std::filesystem::remove(probe, ec);
}

// `simulate calibrate`: fit the config's chosen costs to its target speedups
// by re-pricing the counts each run recorded (no tracing again).
void calibrate_runs(std::vector<RunResult>& runs, const nlohmann::json& config,
                    const std::string& file, const std::string& out, bool quiet) {
    if (!config.contains("calibrate"))
        throw InputError(file + ": /calibrate: missing (simulate calibrate needs a calibrate block)");
    const CalibrateDesc desc = parse_calibrate(JsonReader(config, file).child("calibrate"));
    std::vector<CalibrationRun> fit_runs;
    std::vector<std::string> skipped;
    for (RunResult& r : runs) {
        const std::string label = r.sweep_label.empty() ? r.config.name : r.sweep_label;
        const CalibrationTarget* target = find_target(desc, r.sweep_values, label);
        MethodRun* ref = const_cast<MethodRun*>(r.baseline());
        MethodRun* obb = const_cast<MethodRun*>(r.find(desc.method));
        if (!target || !ref || !obb || !ref->runnable || !obb->runnable) {
            skipped.push_back(label);
            continue;
        }
        CalibrationRun run{label, ref->frame.totals, obb->frame.totals, nullptr, nullptr, target->speedup,
                           target->weight};
        if (ref->frame.warp_trace.waves() > 0 && obb->frame.warp_trace.waves() > 0) {
            run.ref_warps = std::make_shared<WarpTrace>(std::move(ref->frame.warp_trace));
            run.obb_warps = std::make_shared<WarpTrace>(std::move(obb->frame.warp_trace));
        }
        fit_runs.push_back(std::move(run));
    }
    std::vector<nlohmann::json> values;
    std::vector<std::string> labels;
    for (const RunResult& r : runs) {
        values.push_back(r.sweep_values);
        labels.push_back(r.sweep_label.empty() ? r.config.name : r.sweep_label);
    }
    const auto unmatched = unmatched_targets(desc, values, labels);
    if (!unmatched.empty())
        throw InputError(file + ": /calibrate/targets: no run matches " + unmatched.front());
    if (fit_runs.empty()) throw InputError(file + ": /calibrate/targets: no run has a target");
    CalibrationResult result;
    try {
        // Start from the named preset (so refitting does not start from its own
        // previous output), else from the run's primary cost preset.
        const CostModel start = desc.start.empty()
                                    ? runs.front().costs.front()
                                    : load_cost_model(resolve_config_path(desc.start, file));
        result = calibrate(fit_runs, start, desc.parameters, calibration_options(desc));
    } catch (const std::invalid_argument& e) {
        throw InputError(file + ": /calibrate: " + e.what());
    }
    const std::string report = calibration_report_markdown(result);
    write_text_file((std::filesystem::path(out) / "calibration.md").string(), report);
    const std::string preset = calibrated_preset_json(result);
    write_text_file((std::filesystem::path(out) / "calibrated_preset.json").string(), preset);
    if (!desc.output.empty()) {
        write_text_file(desc.output, preset);
        if (!quiet) std::cerr << "fitted preset written to " << desc.output << "\n";
    }
    std::cout << "\n" << report;
    if (!skipped.empty() && !quiet)
        std::cerr << skipped.size() << " run(s) without a target were not fitted\n";
}

}  // namespace

int run_all(const CliOptions& cli) {
    nlohmann::json config = parse_json_text(read_text_file(cli.config), cli.config);
    if (!config.is_object()) throw InputError(cli.config + ": /: expected a JSON object");
    for (const std::string& s : cli.sets) apply_set(config, s, cli.config);
    (void)sweep_point_count(config, cli.config, cli.limits);  // before expanding it
    const std::vector<SweepPoint> points = expand_sweep(config, cli.config);
    // Parse every point before any work, so a bad value fails in a second.
    std::vector<RunConfig> parsed;
    std::vector<WorkEstimate> estimates;
    for (const SweepPoint& p : points) {
        parsed.push_back(parse_run_config(p.config, cli.config));
        estimates.push_back(estimate_config_work(parsed.back()));
    }
    const WorkEstimate work = combine_work(estimates);
    check_work(work, cli.limits, cli.config);
    const std::string out = cli.out ? *cli.out : "out/" + parsed.front().name;
    make_dir(out);
    if (!cli.quiet) {
        std::cerr << "simulate " << cli.config << " -> " << out << "\neffective configuration:\n"
                  << config.dump(2) << "\n";
        if (points.size() > 1) std::cerr << points.size() << " sweep points\n";
        std::cerr << "estimate: " << count_text(work.rays) << " rays, "
                  << (work.primitives > 0 ? count_text(work.primitives) + " primitives, " : std::string())
                  << format_bytes(work.memory_bytes) << " of memory\n";
    }
    std::vector<RunResult> runs;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const std::string dir = points.size() == 1
                                    ? out
                                    : (std::filesystem::path(out) /
                                       (std::to_string(i) + "_" + sanitize(points[i].label))).string();
        make_dir(dir);
        if (!cli.quiet && points.size() > 1)
            std::cerr << "[" << i + 1 << "/" << points.size() << "] " << points[i].label << "\n";
        RunContext ctx;
        ctx.threads = cli.threads;
        ctx.quiet = cli.quiet;
        ctx.record_warps = cli.calibrate;
        ctx.out_dir = dir;
        ctx.limits = cli.limits;
        RunResult r = run_simulation(parsed[i], points[i].config, ctx);
        r.sweep_values = points[i].values;
        r.sweep_label = points[i].label;
        write_text_file((std::filesystem::path(dir) / "report.json").string(), report_json(r).dump(2) + "\n");
        if (parsed[i].output.images) write_images(r, dir);
        (void)write_break_even_maps(r, dir);
        // Free the per-pixel data of finished points: sweeps keep only totals.
        for (MethodRun& m : r.methods) {
            m.frame.pixel_counts = {};
            m.frame.radiance = {};
        }
        runs.push_back(std::move(r));
        const Table t = summary_table(runs);
        write_text_file((std::filesystem::path(out) / "summary.csv").string(), t.to_csv());
        write_text_file((std::filesystem::path(out) / "summary.md").string(), t.to_markdown());
        const Table st = speedup_table(runs);
        write_text_file((std::filesystem::path(out) / "speedups.csv").string(), st.to_csv());
        write_text_file((std::filesystem::path(out) / "speedups.md").string(), st.to_markdown());
    }
    write_sweep_plots(runs, out);
    if (cli.calibrate) calibrate_runs(runs, config, cli.config, out, cli.quiet);
    std::cout << summary_table(runs).to_console();
    if (!cli.quiet) std::cerr << "outputs in " << out << "/\n";
    return 0;
}

}  // namespace rtc
