// `sampling_coverage`: validates sampled simulation (docs/sampling.md). Runs
// each sweep point of a config in full once, then for seeds 1..N draws the
// tile sample a `--sample F --sample-seed s` run would trace and computes
// that run's speedup estimate and 95 % interval from the full run's
// per-pixel values of those tiles (a sampled run traces exactly them: the
// same counts and cycles per pixel, tests/sim/test_sampling.cpp), and counts
// how often the full run's speedup lies inside. `--verify K` also runs the
// first K seeds as real sampled runs and checks that their intervals are the
// ones computed here, and times them against the full run.
#include "core/input_error.h"
#include "sim/config/config_json.h"
#include "sim/config/sweep.h"
#include "sim/run/simulation.h"
#include "sim/util/json_file.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace rtc;

constexpr const char* kHelp =
    "usage: sampling_coverage CONFIG.json [options]\n"
    "  --set key=value  a config override (as simulate's), repeatable\n"
    "  --seeds N        seeds 1..N (default 100)\n"
    "  --fraction F     the sampled fraction (default 0.0625)\n"
    "  --points LIST    only these sweep points (comma-separated indices; default all)\n"
    "  --threads N      threads of the full and the verifying runs (default: all cores)\n"
    "  --verify K       also run seeds 1..K as real sampled runs: same intervals, and their time\n";

struct Options {
    std::string config;
    std::vector<std::string> sets;
    int seeds = 100;
    double fraction = 0.0625;
    std::vector<std::size_t> points;
    unsigned threads = 0;
    int verify = 0;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw InputError("sampling_coverage: " + a + " needs a value");
            return argv[++i];
        };
        if (a == "--help" || a == "-h") {
            std::fputs(kHelp, stdout);
            std::exit(0);
        } else if (a == "--set") {
            o.sets.push_back(value());
        } else if (a == "--seeds") {
            o.seeds = std::stoi(value());
        } else if (a == "--fraction") {
            o.fraction = std::stod(value());
        } else if (a == "--threads") {
            o.threads = static_cast<unsigned>(std::stoul(value()));
        } else if (a == "--verify") {
            o.verify = std::stoi(value());
        } else if (a == "--points") {
            const std::string list = value();
            for (std::size_t p = 0; p <= list.size();) {
                const std::size_t q = std::min(list.find(',', p), list.size());
                o.points.push_back(std::stoul(list.substr(p, q - p)));
                p = q + 1;
            }
        } else if (!a.empty() && a[0] != '-' && o.config.empty()) {
            o.config = a;
        } else {
            throw InputError("sampling_coverage: unknown argument " + a + "\n" + kHelp);
        }
    }
    if (o.config.empty()) throw InputError(std::string("sampling_coverage: no config\n") + kHelp);
    return o;
}

// Per cost preset of r: its per-pixel warp cycles in method m's frame (warp
// presets), or null (per-ray presets, priced from the counts).
std::vector<const std::vector<float>*> warp_pixels(const RunResult& r, const MethodRun& m) {
    std::vector<const std::vector<float>*> out(r.costs.size(), nullptr);
    for (std::size_t p = 0; p < r.costs.size(); ++p) {
        if (!r.costs[p].execution.warp()) continue;
        const PresetWarp* w = m.frame.warp_of(r.costs[p].name);
        if (w && !w->pixel_cycles.empty()) out[p] = &w->pixel_cycles;
    }
    return out;
}

struct Cell {  // one (method, preset) of a point, over the seeds
    std::string method, preset;
    double full = 0.0;
    int covered = 0, seeds = 0;
    double sum_error = 0.0, sum_abs_error = 0.0, max_abs_error = 0.0, sum_half_width = 0.0;
    std::vector<std::array<double, 2>> intervals;  // per seed (for --verify)
};

int run(const Options& o) {
    nlohmann::json config = parse_json_text(read_text_file(o.config), o.config);
    for (const std::string& s : o.sets) apply_set(config, s, o.config);
    apply_set(config, "sampling.fraction=1", o.config);  // the full run
    const std::vector<SweepPoint> points = expand_sweep(config, o.config, sweep_key_order(read_text_file(o.config), o.sets));
    int covered_all = 0, cells_all = 0;
    double full_seconds = 0.0, sampled_seconds = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!o.points.empty() && std::find(o.points.begin(), o.points.end(), i) == o.points.end()) continue;
        const RunConfig c = parse_run_config(points[i].config, o.config);
        RunContext ctx;
        ctx.threads = o.threads;
        ctx.quiet = true;
        const auto t0 = std::chrono::steady_clock::now();
        const RunResult full = run_simulation(c, ctx);
        const double t_full = seconds_since(t0);
        full_seconds += t_full;
        const ExecutionModel tile = full.warp_grouping ? *full.warp_grouping : ExecutionModel{};
        std::vector<Cell> cells;
        for (const MethodRun& m : full.methods) {
            if (m.method == c.baseline || !m.runnable) continue;
            for (std::size_t p = 0; p < full.costs.size(); ++p)
                if (full.speedup(m.method, p) > 0.0)
                    cells.push_back({m.method, full.costs[p].name, full.speedup(m.method, p), 0, 0, 0, 0, 0, 0, {}});
        }
        const MethodRun* base = full.baseline();
        for (int seed = 1; seed <= o.seeds; ++seed) {
            const auto sample = TileSample::make(full.camera.width, full.camera.height, full.warp_grouping ? tile.tile_width : 8,
                                                 full.warp_grouping ? tile.tile_height : 4,
                                                 {o.fraction, static_cast<std::uint64_t>(seed)});
            if (!sample) throw InputError("sampling_coverage: --fraction " + std::to_string(o.fraction) + " traces every tile");
            const SampledMethod b = estimate_sampled(base->frame, *sample, full.costs, warp_pixels(full, *base), {});
            for (Cell& cell : cells) {
                const MethodRun& m = *full.find(cell.method);
                const SampledMethod s = estimate_sampled(m.frame, *sample, full.costs, warp_pixels(full, m), {});
                std::size_t p = 0;
                while (full.costs[p].name != cell.preset) ++p;
                const SampledEstimate e = estimate_ratio(b.tile_cycles[p], s.tile_cycles[p], sample->k());
                const double signed_err = e.value / cell.full - 1.0, err = std::abs(signed_err);
                cell.sum_error += signed_err;
                cell.covered += e.interval[0] <= cell.full && cell.full <= e.interval[1];
                ++cell.seeds;
                cell.sum_abs_error += err;
                cell.max_abs_error = std::max(cell.max_abs_error, err);
                cell.sum_half_width += (e.interval[1] - e.interval[0]) / 2.0 / e.value;
                cell.intervals.push_back(e.interval);
            }
        }
        // Real sampled runs of the first seeds: the same intervals, and their time.
        double t_sampled = 0.0, worst_mismatch = 0.0;
        for (int seed = 1; seed <= o.verify; ++seed) {
            nlohmann::json pc = points[i].config;
            apply_set(pc, "sampling.fraction=" + nlohmann::json(o.fraction).dump(), o.config);
            apply_set(pc, "sampling.seed=" + std::to_string(seed), o.config);
            const auto t1 = std::chrono::steady_clock::now();
            const RunResult sampled = run_simulation(parse_run_config(pc, o.config), ctx);
            t_sampled += seconds_since(t1);
            for (Cell& cell : cells) {
                std::size_t p = 0;
                while (full.costs[p].name != cell.preset) ++p;
                const auto e = sampled.sampled_speedup(cell.method, p);
                if (!e) throw InputError("sampling_coverage: the sampled run has no interval for " + cell.method);
                const auto& mine = cell.intervals[static_cast<std::size_t>(seed - 1)];
                for (int k = 0; k < 2; ++k)
                    worst_mismatch = std::max(worst_mismatch, std::abs(e->interval[k] / mine[k] - 1.0));
            }
        }
        if (o.verify > 0) sampled_seconds += t_sampled / o.verify;
        std::printf("point %zu %s: full run %.2f s", i, points[i].label.c_str(), t_full);
        if (o.verify > 0)
            std::printf(", sampled run %.2f s (%.1f%% of full), %d verified seeds' intervals within %.1e of these",
                        t_sampled / o.verify, 100.0 * t_sampled / o.verify / t_full, o.verify, worst_mismatch);
        std::printf("\n");
        for (const Cell& cell : cells) {
            std::printf("  %-6s %-28s full %.4fx  covered %3d/%d  mean err %+.2f%%  mean |err| %.2f%%  max |err| %.2f%%  "
                        "mean half-width %.2f%%\n",
                        cell.method.c_str(), cell.preset.c_str(), cell.full, cell.covered, cell.seeds,
                        100.0 * cell.sum_error / cell.seeds, 100.0 * cell.sum_abs_error / cell.seeds, 100.0 * cell.max_abs_error,
                        100.0 * cell.sum_half_width / cell.seeds);
            covered_all += cell.covered;
            cells_all += cell.seeds;
        }
        std::fflush(stdout);
    }
    std::printf("all: %d of %d intervals cover the full run's speedup (%.1f%%); full runs %.1f s",
                covered_all, cells_all, cells_all ? 100.0 * covered_all / cells_all : 0.0, full_seconds);
    if (o.verify > 0) std::printf(", one sampled run of each point %.1f s", sampled_seconds);
    std::printf("\n");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(parse(argc, argv));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
}
