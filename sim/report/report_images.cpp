// The pictures of a run: the shaded render, heat maps of cycles and of
// intersection-program calls per pixel for each method on one common scale
// (the paper's figures 1 and 4), the ref/obb ratio map (sweep plots:
// sweep_plots.cpp).
#include "core/parallel.h"
#include "sim/plot/heatmap.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <set>

namespace rtc {

namespace {

ScalarField pixel_field(const FrameResult& f, const auto& value_of) {
    ScalarField field{f.width, f.height, {}};
    field.values.resize(f.pixel_counts.size());
    for (std::size_t i = 0; i < f.pixel_counts.size(); ++i) field.values[i] = value_of(f.pixel_counts[i]);
    return field;
}

std::string path_in(const std::string& dir, const std::string& file) {
    return (std::filesystem::path(dir) / file).string();
}

// SIMT efficiency of the intersection-program rounds of each pixel's warps:
// active lanes per round over the warp width (1: every lane had a candidate).
void write_simt_map(const MethodRun& m, const RunResult& run, const std::string& dir) {
    const FrameResult& f = m.frame;
    ScalarField eff{f.width, f.height, std::vector<float>(f.pixel_simt_slots.size())};
    for (std::size_t i = 0; i < eff.values.size(); ++i)
        eff.values[i] = f.pixel_simt_slots[i] > 0.0f ? f.pixel_simt_active[i] / f.pixel_simt_slots[i]
                                                     : std::numeric_limits<float>::quiet_NaN();
    HeatmapOptions o;
    o.title = m.method + ": SIMT efficiency of IS rounds";
    o.bar_label = "active lanes / W";
    o.caption = run.config.name + (run.sweep_label.empty() ? "" : "  " + run.sweep_label) +
                "\nper pixel: over its warps' rounds; grey: no IS round" +
                (run.sample ? std::string(" or not traced (sampled run)") : std::string());
    o.colormap = Colormap::Viridis;
    write_png(render_heatmap(eff, HeatmapScale{0.0, 1.0, ScaleKind::Linear}, o).image,
              path_in(dir, "heat_simt_" + m.method + ".png"));
}

// Runs the jobs on `threads` threads; the error of the first failed job (in
// job order, whatever the scheduling) is rethrown once all have finished.
void run_jobs(const std::vector<std::function<void()>>& jobs, unsigned threads) {
    std::vector<std::exception_ptr> errors(jobs.size());
    parallel_for(jobs.size(), threads, [&](std::size_t i, unsigned) {
        try {
            jobs[i]();
        } catch (...) {
            errors[i] = std::current_exception();
        }
    }, 1);
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
}

}  // namespace

// Each picture is a job (its rendering and PNG encoding take about 0.05 s at
// 800 x 800, eight pictures for two methods): they run on all the run's
// threads, on data that is only read.
void write_images(const RunResult& run, const std::string& dir, unsigned threads) {
    std::vector<const MethodRun*> traced;
    for (const MethodRun& m : run.methods)
        if (m.runnable && m.frame.width > 0) traced.push_back(&m);
    if (traced.empty()) return;
    std::vector<std::function<void()>> jobs;
    const FrameResult& first = traced.front()->frame;
    jobs.push_back([&] {
        write_png(tonemap_to_srgb(first.radiance, first.width, first.height), path_in(dir, "render.png"));
    });

    const CostModel& cost = run.costs.front();
    // Under a warp preset a pixel's cycles are its share of its waves'.
    const bool warp = cost.execution.warp();
    std::vector<ScalarField> cycles, calls;
    for (const MethodRun* m : traced) {
        if (warp)
            cycles.push_back({m->frame.width, m->frame.height, m->frame.warp_of(cost.name)->pixel_cycles});
        else
            cycles.push_back(pixel_field(m->frame, [&](const RayCounts& c) {
                return static_cast<float>(price_cycles(c, cost));
            }));
        calls.push_back(pixel_field(m->frame, [](const RayCounts& c) {
            return static_cast<float>(c[Event::IsCall]);
        }));
    }
    // A sampled run traced some tiles only: the others are grey (no data),
    // not zero, and every caption says so.
    std::string sampled;
    if (run.sample) {
        const TileSample& s = *run.sample;
        for (std::vector<ScalarField>* fields : {&cycles, &calls})
            for (ScalarField& f : *fields)
                for (int y = 0; y < f.height; ++y)
                    for (int x = 0; x < f.width; ++x)
                        if (!s.traced_pixel(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y)))
                            f.values[static_cast<std::size_t>(y) * static_cast<std::size_t>(f.width) +
                                     static_cast<std::size_t>(x)] = std::numeric_limits<float>::quiet_NaN();
        sampled = "\nsampled: " + std::to_string(s.traced_tiles()) + " of " + std::to_string(s.tiles()) +
                  " tiles traced (1/" + std::to_string(s.k()) + ", seed " + std::to_string(s.seed()) + "); grey: not traced";
    }
    const auto pointers = [](const std::vector<ScalarField>& v) {
        std::vector<const ScalarField*> p;
        for (const auto& f : v) p.push_back(&f);
        return p;
    };
    const HeatmapScale cycle_scale = common_scale(pointers(cycles));
    const HeatmapScale call_scale = common_scale(pointers(calls));
    const std::string spp = std::to_string(run.config.workload.spp) + " samples/pixel";
    for (std::size_t i = 0; i < traced.size(); ++i) {
        const std::string& name = traced[i]->method;
        HeatmapOptions o;
        o.title = name + ": cycles per pixel (" + cost.name + (warp ? ", warp model)" : ")");
        o.bar_label = "cycles / pixel";
        o.caption = run.config.name + (run.sweep_label.empty() ? "" : "  " + run.sweep_label) +
                    "\n" + spp + ", common scale across methods" + sampled;
        o.colormap = Colormap::Inferno;
        jobs.push_back([&, i, o, name] {
            write_png(render_heatmap(cycles[i], cycle_scale, o).image, path_in(dir, "heat_cycles_" + name + ".png"));
        });
        o.title = name + ": intersection-program calls per pixel";
        o.bar_label = "IS calls / pixel";
        o.colormap = Colormap::Viridis;
        jobs.push_back([&, i, o, name] {
            write_png(render_heatmap(calls[i], call_scale, o).image, path_in(dir, "heat_is_calls_" + name + ".png"));
        });
        if (warp) jobs.push_back([&, i] { write_simt_map(*traced[i], run, dir); });
    }
    // One ratio map per method against the baseline.
    const MethodRun* base = run.baseline();
    const std::string& bname = run.config.baseline;
    const auto base_at = std::find(traced.begin(), traced.end(), base);
    for (std::size_t i = 0; i < traced.size(); ++i) {
        if (base_at == traced.end() || traced[i] == base) continue;
        const std::string& name = traced[i]->method;
        RatioMapOptions o;
        o.title = "cycles per pixel, " + bname + " / " + name;
        o.ratio_label = bname + "/" + name;
        o.caption = run.config.name + (run.sweep_label.empty() ? "" : "  " + run.sweep_label) +
                    "\nred: " + name + " cheaper, blue: " + bname + " cheaper" + sampled;
        jobs.push_back([&, i, o, name] {
            write_png(render_ratio_map(cycles[static_cast<std::size_t>(base_at - traced.begin())], cycles[i], o).image,
                      path_in(dir, "ratio_cycles_" + bname + "_over_" + name + ".png"));
        });
    }
    run_jobs(jobs, threads);
}

}  // namespace rtc
