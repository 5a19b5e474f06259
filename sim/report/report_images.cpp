// The pictures of a run: the shaded render, heat maps of cycles and of
// intersection-program calls per pixel for each method on one common scale
// (the paper's figures 1 and 4), the ref/obb ratio map, and sweep plots.
#include "sim/plot/heatmap.h"
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
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
                "\nper pixel: over its warps' rounds; grey: no IS round";
    o.colormap = Colormap::Viridis;
    write_png(render_heatmap(eff, HeatmapScale{0.0, 1.0, ScaleKind::Linear}, o).image,
              path_in(dir, "heat_simt_" + m.method + ".png"));
}

}  // namespace

void write_images(const RunResult& run, const std::string& dir) {
    std::vector<const MethodRun*> traced;
    for (const MethodRun& m : run.methods)
        if (m.runnable && m.frame.width > 0) traced.push_back(&m);
    if (traced.empty()) return;
    const FrameResult& first = traced.front()->frame;
    write_png(tonemap_to_srgb(first.radiance, first.width, first.height), path_in(dir, "render.png"));

    const CostModel& cost = run.costs.front();
    // Under a warp preset a pixel's cycles are its share of its waves'.
    const bool warp = cost.execution.warp();
    std::vector<ScalarField> cycles, calls;
    for (const MethodRun* m : traced) {
        if (warp)
            cycles.push_back({m->frame.width, m->frame.height, m->frame.pixel_warp_cycles});
        else
            cycles.push_back(pixel_field(m->frame, [&](const RayCounts& c) {
                return static_cast<float>(price_cycles(c, cost));
            }));
        calls.push_back(pixel_field(m->frame, [](const RayCounts& c) {
            return static_cast<float>(c[Event::IsCall]);
        }));
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
                    "\n" + spp + ", common scale across methods";
        o.colormap = Colormap::Inferno;
        write_png(render_heatmap(cycles[i], cycle_scale, o).image, path_in(dir, "heat_cycles_" + name + ".png"));
        o.title = name + ": intersection-program calls per pixel";
        o.bar_label = "IS calls / pixel";
        o.colormap = Colormap::Viridis;
        write_png(render_heatmap(calls[i], call_scale, o).image, path_in(dir, "heat_is_calls_" + name + ".png"));
        if (warp) write_simt_map(*traced[i], run, dir);
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
                    "\nred: " + name + " cheaper, blue: " + bname + " cheaper";
        write_png(render_ratio_map(cycles[static_cast<std::size_t>(base_at - traced.begin())], cycles[i], o).image,
                  path_in(dir, "ratio_cycles_" + bname + "_over_" + name + ".png"));
    }
}

std::vector<std::string> write_sweep_plots(const std::vector<RunResult>& runs, const std::string& dir) {
    std::vector<std::string> written;
    if (runs.size() < 2) return written;
    // Numeric sweep axes with more than one value.
    std::map<std::string, std::set<double>> axes;
    for (const RunResult& r : runs)
        for (const auto& [k, v] : r.sweep_values.items())
            if (v.is_number()) axes[k].insert(v.get<double>());
    const std::string& bname = runs.front().config.baseline;
    std::vector<std::string> others;  // every non-baseline method, first-seen order
    for (const RunResult& r : runs)
        for (const MethodRun& m : r.methods)
            if (m.method != bname && std::find(others.begin(), others.end(), m.method) == others.end())
                others.push_back(m.method);
    const bool one = others.size() == 1;
    const std::string who = one ? others.front() : "each method";
    for (const auto& [axis, values] : axes) {
        if (values.size() < 2) continue;
        // One series per method and combination of the other sweep values.
        std::map<std::string, PlotSeries> series;
        for (const std::string& method : others) {
            for (const RunResult& r : runs) {
                if (!r.sweep_values.contains(axis) || !r.sweep_values[axis].is_number()) continue;
                const double s = r.speedup(method);
                std::string key = one ? "" : method;
                for (const auto& [k, v] : r.sweep_values.items())
                    if (k != axis) key += (key.empty() ? "" : ", ") + k + "=" + (v.is_string() ? v.get<std::string>() : v.dump());
                PlotSeries& ps = series[key];
                ps.name = key.empty() ? method : key;
                ps.x.push_back(r.sweep_values[axis].get<double>());
                ps.y.push_back(s > 0 ? s : std::numeric_limits<double>::quiet_NaN());
            }
        }
        LinePlot plot;
        plot.axes.title = "speedup of " + who + " over " + bname + " vs " + axis;
        plot.axes.x_label = axis;
        plot.axes.y_label = one ? "speedup (" + bname + " cycles / " + who + " cycles)"
                                : "speedup (" + bname + " cycles / method cycles)";
        for (auto& [k, s] : series) plot.series.push_back(std::move(s));
        std::string file = "speedup_vs_" + axis + ".svg";
        for (char& ch : file) if (ch == '/' ) ch = '_';
        write_text_file(path_in(dir, file), line_plot_svg(plot));
        written.push_back(file);
    }
    // The Pareto view: speedup against memory overhead, one line per method
    // and combination of the string-valued sweep values (scene, kind, ...),
    // its points in sweep order (e.g. a cluster size sweep).
    std::map<std::string, std::set<std::string>> strings;  // string-valued axes and their values
    for (const RunResult& r : runs)
        for (const auto& [k, v] : r.sweep_values.items())
            if (v.is_string()) strings[k].insert(v.get<std::string>());
    std::map<std::string, PlotSeries> pareto;
    for (const std::string& method : others) {
        for (const RunResult& r : runs) {
            const double s = r.speedup(method), o = r.memory_overhead_percent(method);
            if (!(s > 0) || std::isnan(o)) continue;
            std::string key = one ? "" : method;
            for (const auto& [k, v] : r.sweep_values.items()) {
                if (!v.is_string() || strings[k].size() < 2) continue;
                // "scene.name" reads "scene", "cluster.strategy" reads "strategy".
                const std::size_t dot = k.rfind('.');
                const std::string name = k.ends_with(".name") ? k.substr(0, dot)
                                         : dot == std::string::npos ? k : k.substr(dot + 1);
                key += (key.empty() ? "" : ", ") + name + "=" + v.get<std::string>();
            }
            if (key.empty()) key = method;
            PlotSeries& ps = pareto[key];
            ps.name = key;
            ps.x.push_back(o);
            ps.y.push_back(s);
        }
    }
    if (std::any_of(pareto.begin(), pareto.end(), [](const auto& p) { return p.second.x.size() > 1; })) {
        LinePlot plot;
        plot.axes.title = "speedup over " + bname + " vs memory overhead (Pareto)";
        plot.axes.x_label = "total memory over " + bname + " (%)";
        plot.axes.y_label = "speedup (" + bname + " cycles / method cycles)";
        plot.axes.height = 480;
        for (auto& [k, s] : pareto) plot.series.push_back(std::move(s));
        write_text_file(path_in(dir, "speedup_vs_memory.svg"), line_plot_svg(plot));
        written.push_back("speedup_vs_memory.svg");
    }
    // Speedup against the surface-area ratio over every run (figure 9's metric).
    for (const std::string& method : others) {
        ScatterPlot scatter;
        scatter.axes.title = "speedup vs AABB/OBB surface-area ratio";
        scatter.axes.x_label = "sum AABB area / sum OBB area (paper OBBs)";
        scatter.axes.y_label = "speedup of " + method + " over " + bname;
        for (const RunResult& r : runs) {
            const double s = r.speedup(method);
            if (s > 0) scatter.points.push_back({r.areas.ratio_paper(), s, ""});
        }
        if (scatter.points.size() < 2) continue;
        scatter.guide = ScatterGuide::LeastSquares;
        const std::string file = one ? "speedup_vs_area_ratio.svg" : "speedup_vs_area_ratio_" + method + ".svg";
        write_text_file(path_in(dir, file), scatter_plot_svg(scatter));
        written.push_back(file);
    }
    return written;
}

}  // namespace rtc
