#include "sim/run_all.h"

#include "sim/json_file.h"
#include "sim/plot_svg.h"
#include "sim/report.h"
#include "sim/sweep.h"

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

}  // namespace

int run_all(const CliOptions& cli) {
    nlohmann::json config = parse_json_text(read_text_file(cli.config), cli.config);
    if (!config.is_object()) throw InputError(cli.config + ": /: expected a JSON object");
    for (const std::string& s : cli.sets) apply_set(config, s, cli.config);
    const std::vector<SweepPoint> points = expand_sweep(config, cli.config);
    // Parse every point before any work, so a bad value fails in a second.
    std::vector<RunConfig> parsed;
    for (const SweepPoint& p : points) parsed.push_back(parse_run_config(p.config, cli.config));
    const std::string out = cli.out ? *cli.out : "out/" + parsed.front().name;
    make_dir(out);
    if (!cli.quiet) {
        std::cerr << "simulate " << cli.config << " -> " << out << "\neffective configuration:\n"
                  << config.dump(2) << "\n";
        if (points.size() > 1) std::cerr << points.size() << " sweep points\n";
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
        RunContext ctx{cli.threads, cli.quiet, dir};
        RunResult r = run_simulation(parsed[i], points[i].config, ctx);
        r.sweep_values = points[i].values;
        r.sweep_label = points[i].label;
        write_text_file((std::filesystem::path(dir) / "report.json").string(), report_json(r).dump(2) + "\n");
        if (parsed[i].output.images) write_images(r, dir);
        // Free the per-pixel data of finished points: sweeps keep only totals.
        for (MethodRun& m : r.methods) {
            m.frame.pixel_counts = {};
            m.frame.radiance = {};
        }
        runs.push_back(std::move(r));
        const Table t = summary_table(runs);
        write_text_file((std::filesystem::path(out) / "summary.csv").string(), t.to_csv());
        write_text_file((std::filesystem::path(out) / "summary.md").string(), t.to_markdown());
    }
    write_sweep_plots(runs, out);
    std::cout << summary_table(runs).to_console();
    if (!cli.quiet) std::cerr << "outputs in " << out << "/\n";
    return 0;
}

}  // namespace rtc
