// Plots over a sweep (SVG): speedup against each sweep axis, the Pareto view
// (speedup against memory overhead) and speedup against the AABB/OBB area
// ratio. An axis is one sweep key: a number (log x when it spans more than two
// decades), a string, or an object (a paired axis such as {count, radius}:
// one axis named "count, radius", ticks "1000, 0.002", at its first numeric
// key when that tells the values apart, else in sweep order).
#include "sim/plot/plot_svg.h"
#include "sim/report/report.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>

namespace rtc {

namespace {

using nlohmann::json;

// "../hw/memory-dxr.json" reads "memory-dxr"; other strings as they are.
std::string short_text(const json& v) {
    if (v.is_string()) {
        const std::string s = v.get<std::string>();
        if (s.ends_with(".json") || s.find('/') != std::string::npos) return std::filesystem::path(s).stem().string();
        return s;
    }
    if (v.is_number_float()) {  // as written in the config (0.1, not 0.100), unless long
        char buf[32];
        const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v.get<double>());
        const std::string shortest = ec == std::errc() ? std::string(buf, end) : "";
        return !shortest.empty() && shortest.size() <= 8 ? shortest : format_sig(v.get<double>(), 3);
    }
    return v.dump();
}

// The last part of a dotted key: "scene.tilt_deg" reads "tilt_deg".
std::string last_part(const std::string& key) {
    const std::size_t dot = key.rfind('.');
    return dot == std::string::npos ? key : key.substr(dot + 1);
}

// The distinct values of `keys` (a JSON array per run, null where missing).
std::vector<json> tuples(const std::vector<RunResult>& runs, const std::vector<std::string>& keys) {
    std::vector<json> out;
    for (const RunResult& r : runs) {
        json t = json::array();
        for (const std::string& k : keys) t.push_back(r.point.values.contains(k) ? r.point.values[k] : json());
        if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(std::move(t));
    }
    return out;
}

// One sweep axis: the keys of one sweep list. A paired list of objects
// records one key per member ("scene.count", "scene.radius"), which vary
// together: in a cartesian sweep, two groups of keys from different lists
// take every combination, keys of one list do not.
struct SweepAxis {
    std::vector<std::string> keys;  // its sweep-value keys
    std::string key;                // file-name key: the members' common prefix ("scene") or the one key
    std::string name;               // axis label ("count, radius", "scene.tilt_deg", "scene")
    std::vector<json> values;       // distinct tuples over `keys`, first-seen order
    std::vector<double> x;          // per value
    std::vector<std::string> tick, legend;  // per value: "1000, 0.002" and "count=1000, radius=0.002"
    bool numeric = false, log = false;
    std::size_t changes = 0;        // value changes between consecutive runs (the slowest axis has fewest)

    std::size_t index_of(const RunResult& r) const {
        json t = json::array();
        for (const std::string& k : keys) t.push_back(r.point.values.contains(k) ? r.point.values[k] : json());
        return static_cast<std::size_t>(std::find(values.begin(), values.end(), t) - values.begin());
    }
};

SweepAxis make_axis(std::vector<std::string> keys, const std::vector<RunResult>& runs) {
    SweepAxis a;
    a.keys = std::move(keys);
    a.values = tuples(runs, a.keys);
    const std::size_t n = a.values.size();
    a.x.resize(n), a.tick.resize(n), a.legend.resize(n);
    for (std::size_t i = 0; i < n; ++i) a.x[i] = static_cast<double>(i);  // sweep order unless numeric
    // Members that vary, by their last name; "name" alone when there is one.
    std::vector<std::size_t> varying;
    for (std::size_t k = 0; k < a.keys.size(); ++k)
        if (std::any_of(a.values.begin(), a.values.end(), [&](const json& t) { return t[k] != a.values[0][k]; }) &&
            std::all_of(a.values.begin(), a.values.end(), [&](const json& t) { return t[k].is_primitive(); }))
            varying.push_back(k);
    if (a.keys.size() == 1) {
        a.key = a.name = a.keys[0];
    } else {
        a.key = a.keys[0];  // the longest common dotted prefix
        for (const std::string& k : a.keys)
            while (!a.key.empty() && k != a.key && k.rfind(a.key + ".", 0) != 0) {
                const std::size_t dot = a.key.rfind('.');
                a.key = dot == std::string::npos ? "" : a.key.substr(0, dot);
            }
        const auto name_at = std::find_if(varying.begin(), varying.end(),
                                          [&](std::size_t k) { return last_part(a.keys[k]) == "name"; });
        if (name_at != varying.end()) varying = {*name_at};
        const bool named = varying.size() == 1 && last_part(a.keys[varying[0]]) == "name";
        for (std::size_t k : varying) a.name += (a.name.empty() ? "" : ", ") + (named ? a.key : last_part(a.keys[k]));
        if (a.key.empty()) a.key = a.name;
    }
    if (a.name.empty()) a.name = a.key;
    const bool single = a.keys.size() == 1;
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k : varying) {
            if (a.values[i][k].is_null()) continue;
            const std::string t = short_text(a.values[i][k]);
            const bool named = last_part(a.keys[k]) == "name";
            a.tick[i] += (a.tick[i].empty() ? "" : ", ") + t;
            a.legend[i] += (a.legend[i].empty() ? "" : ", ") + (single ? a.keys[k] : named ? a.key : last_part(a.keys[k])) + "=" + t;
        }
        if (a.tick[i].empty()) a.tick[i] = a.legend[i] = "#" + std::to_string(i);
    }
    // Placed at the first numeric member that tells every value apart.
    for (std::size_t k : varying) {
        std::vector<double> xs;
        for (const json& t : a.values)
            if (t[k].is_number()) xs.push_back(t[k].get<double>());
        std::vector<double> sorted = xs;
        std::sort(sorted.begin(), sorted.end());
        if (xs.size() == n && std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) {
            a.x = xs, a.numeric = true;
            break;
        }
    }
    a.log = a.numeric && spans_decades(a.x, 2.0);
    for (std::size_t i = 1; i < runs.size(); ++i) a.changes += a.index_of(runs[i]) != a.index_of(runs[i - 1]);
    return a;
}

// The sweep's axes, slowest first: keys grouped while two groups do not take
// every combination of their values (then they come from one list).
std::vector<SweepAxis> sweep_axes(const std::vector<RunResult>& runs) {
    std::vector<std::vector<std::string>> groups;
    for (const RunResult& r : runs)
        for (const auto& item : r.point.values.items()) {
            const std::string key = item.key();  // (clang 14 cannot capture a structured binding)
            if (std::none_of(groups.begin(), groups.end(), [&](const auto& g) { return g[0] == key; }))
                groups.push_back({key});
        }
    std::erase_if(groups, [&](const auto& g) { return tuples(runs, g).size() < 2; });  // constant keys
    for (bool merged = true; merged;) {
        merged = false;
        for (std::size_t i = 0; i < groups.size() && !merged; ++i)
            for (std::size_t j = i + 1; j < groups.size() && !merged; ++j) {
                std::vector<std::string> both = groups[i];
                both.insert(both.end(), groups[j].begin(), groups[j].end());
                if (tuples(runs, both).size() < tuples(runs, groups[i]).size() * tuples(runs, groups[j]).size()) {
                    groups[i] = std::move(both);
                    groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(j));
                    merged = true;
                }
            }
    }
    std::vector<SweepAxis> axes;
    for (std::vector<std::string>& g : groups) axes.push_back(make_axis(std::move(g), runs));
    std::stable_sort(axes.begin(), axes.end(), [](const SweepAxis& a, const SweepAxis& b) { return a.changes < b.changes; });
    return axes;
}

// The legend text of a run's values on every axis in `use` but `skip`.
std::string values_text(const RunResult& r, const std::vector<SweepAxis>& axes, std::size_t skip,
                        const std::vector<bool>& use) {
    std::string s;
    for (std::size_t a = 0; a < axes.size(); ++a) {
        if (a == skip || axes[a].values.size() < 2 || !use[a]) continue;
        const std::size_t i = axes[a].index_of(r);
        if (i < axes[a].values.size()) s += (s.empty() ? "" : ", ") + axes[a].legend[i];
    }
    return s;
}

PlotSeries& series_named(std::vector<PlotSeries>& list, const std::string& name) {
    for (PlotSeries& s : list)
        if (s.name == name) return s;
    list.push_back({name, {}, {}, {}, {}});
    return list.back();
}

std::string path_in(const std::string& dir, const std::string& file) {
    return (std::filesystem::path(dir) / file).string();
}

}  // namespace

std::vector<std::string> write_sweep_plots(const std::vector<RunResult>& runs, const std::string& dir) {
    std::vector<std::string> written;
    if (runs.size() < 2) return written;
    const std::string& bname = runs.front().config.baseline;
    std::vector<std::string> others;  // every non-baseline method, first-seen order
    for (const RunResult& r : runs)
        for (const MethodRun& m : r.methods)
            if (m.method != bname && std::find(others.begin(), others.end(), m.method) == others.end())
                others.push_back(m.method);
    const bool one = others.size() == 1;
    const std::string who = one ? others.front() : "each method";
    const CostModel* preset = runs.front().costs.empty() ? nullptr : &runs.front().costs.front();
    const std::string preset_text =
        preset ? "cost preset " + preset->name + (preset->execution.warp() ? " (warp model)" : " (per-ray model)") : "";
    const std::string y_label = one ? "speedup (" + bname + " cycles / " + who + " cycles)"
                                    : "speedup (" + bname + " cycles / method cycles)";
    const std::vector<SweepAxis> axes = sweep_axes(runs);
    const auto nan = std::numeric_limits<double>::quiet_NaN();

    // Per axis: `value(run, method)` of each method against it, one series per
    // method and combination of the other axes' values; no plot when no
    // series changes by more than `flat` (relative) along the axis.
    struct Quantity {
        std::string file, title, y_label, subtitle;
        const std::vector<std::string>* methods;
        std::function<double(const RunResult&, const std::string&)> value;
        double flat;
        bool log_y_beyond_decade;
        // The value's 90 % interval (a band around the curve), when it has one.
        std::function<std::optional<std::array<double, 2>>(const RunResult&, const std::string&)> interval;
    };
    const bool memory_swept = std::any_of(runs.begin(), runs.end(), [&](const RunResult& r) {
        return r.memory.name != runs.front().memory.name;
    });
    const std::string memory_text = memory_swept ? "memory preset as named per series or axis"
                                                 : "memory preset " + runs.front().memory.name;
    std::vector<std::string> all = others;
    all.insert(all.begin(), bname);
    const Quantity quantities[] = {
        {"speedup_vs_", "speedup of " + who + " over " + bname + " vs ", y_label, preset_text, &others,
         [](const RunResult& r, const std::string& m) { return r.speedup(m); }, 1e-9, false,
         [](const RunResult& r, const std::string& m) { return r.speedup_interval(m); }},
        {"memory_vs_", "total memory of each method vs ", "memory (MiB)", memory_text,
         &all, [](const RunResult& r, const std::string& m) {
             const MethodRun* run = r.find(m);
             return run && run->runnable ? run->memory.total() / (1024.0 * 1024.0) : 0.0;
         }, 0.01, true, nullptr}};
    for (const Quantity& q : quantities) {
        const bool single = q.methods->size() == 1;
        // Series over axis `ai`, split by the other axes in `use` (a point
        // already there for its series and x is not repeated).
        const auto build = [&](std::size_t ai, const std::vector<bool>& use) {
            const SweepAxis& axis = axes[ai];
            std::vector<PlotSeries> series;
            for (const std::string& method : *q.methods)
                for (const RunResult& r : runs) {
                    const std::string rest = values_text(r, axes, ai, use);
                    const std::string name = single ? (rest.empty() ? method : rest) : method + (rest.empty() ? "" : ", " + rest);
                    PlotSeries& ps = series_named(series, name);
                    const double x = axis.x[axis.index_of(r)], v = q.value(r, method);
                    if (std::find(ps.x.begin(), ps.x.end(), x) != ps.x.end()) continue;
                    ps.x.push_back(x);
                    ps.y.push_back(v > 0 ? v : nan);
                    const auto i = q.interval && v > 0 ? q.interval(r, method) : std::nullopt;
                    ps.y_low.push_back(i ? (*i)[0] : nan);
                    ps.y_high.push_back(i ? (*i)[1] : nan);
                }
            return series;
        };
        const auto flat = [&](const std::vector<PlotSeries>& series) {
            return std::all_of(series.begin(), series.end(), [&](const PlotSeries& s) {
                double lo = INFINITY, hi = -INFINITY;
                for (double y : s.y)
                    if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
                return !(hi - lo > q.flat * std::abs(hi));
            });
        };
        // Axes that change the quantity; the others neither get a plot nor split series.
        std::vector<bool> matters(axes.size());
        for (std::size_t ai = 0; ai < axes.size(); ++ai) matters[ai] = !flat(build(ai, std::vector<bool>(axes.size(), true)));
        for (std::size_t ai = 0; ai < axes.size(); ++ai) {
            if (!matters[ai]) continue;
            const SweepAxis& axis = axes[ai];
            std::vector<PlotSeries> series = build(ai, matters);
            std::vector<double> ys;
            for (const PlotSeries& ps : series) ys.insert(ys.end(), ps.y.begin(), ps.y.end());
            LinePlot plot;
            plot.axes.title = q.title + axis.name;
            plot.axes.subtitle = q.subtitle;
            plot.axes.x_label = axis.name + (axis.log ? " (log scale)" : "");
            plot.axes.y_label = q.y_label;
            plot.axes.log_x = axis.log;
            plot.axes.log_y = q.log_y_beyond_decade && spans_decades(ys, 1.0);
            if (plot.axes.log_y) plot.axes.y_label += " (log scale)";
            plot.lines = axis.numeric;  // categories in sweep order are not joined
            for (std::size_t i = 0; i < axis.values.size(); ++i) plot.axes.x_ticks.push_back({axis.x[i], axis.tick[i]});
            for (PlotSeries& s : series)
                if (axis.numeric) {  // left to right
                    std::vector<std::size_t> order(s.x.size());
                    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
                    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s.x[a] < s.x[b]; });
                    PlotSeries sorted{s.name, {}, {}, {}, {}};
                    for (std::size_t i : order)
                        sorted.x.push_back(s.x[i]), sorted.y.push_back(s.y[i]), sorted.y_low.push_back(s.y_low[i]),
                            sorted.y_high.push_back(s.y_high[i]);
                    s = std::move(sorted);
                }
            plot.series = std::move(series);
            std::string file = q.file + axis.key + ".svg";
            if (file == "speedup_vs_memory.svg" || file == "memory_vs_memory.svg")  // the Pareto plot's name
                file = q.file + "memory_preset.svg";
            for (char& ch : file) if (ch == '/') ch = '_';
            write_text_file(path_in(dir, file), line_plot_svg(plot));
            written.push_back(file);
        }
    }

    // The Pareto view: speedup against memory overhead, one line per method
    // and value of the first (slowest) axis when there are several, its
    // points in sweep order.
    std::vector<PlotSeries> pareto;
    std::vector<std::vector<std::string>> pareto_labels;  // per series, per point
    for (const std::string& method : others)
        for (const RunResult& r : runs) {
            const double s = r.speedup(method), o = r.memory_overhead_percent(method);
            if (!(s > 0) || std::isnan(o)) continue;
            std::string rest;
            if (axes.size() > 1) rest = axes[0].legend[axes[0].index_of(r)];  // else one line through every point
            PlotSeries& ps = series_named(pareto, one ? (rest.empty() ? method : rest) : method + (rest.empty() ? "" : ", " + rest));
            ps.x.push_back(o);
            ps.y.push_back(s);
            std::string along;  // the point's values on the other axes
            for (std::size_t a = axes.size() > 1 ? 1 : 0; a < axes.size(); ++a)
                along += (along.empty() ? "" : " / ") + axes[a].tick[axes[a].index_of(r)];
            pareto_labels.resize(pareto.size());
            pareto_labels[static_cast<std::size_t>(&ps - pareto.data())].push_back(along);
        }
    if (std::any_of(pareto.begin(), pareto.end(), [](const PlotSeries& p) { return p.x.size() > 1; })) {
        LinePlot plot;
        plot.axes.title = "speedup over " + bname + " vs memory overhead (Pareto)";
        std::string along;
        for (std::size_t a = axes.size() > 1 ? 1 : 0; a < axes.size(); ++a) along += (along.empty() ? "" : " / ") + axes[a].name;
        plot.axes.subtitle = preset_text + (along.empty() ? "" : "; points labelled by " + along);
        plot.axes.x_label = "total memory over " + bname + " (%)";
        plot.axes.y_label = "speedup (" + bname + " cycles / method cycles)";
        plot.axes.height = 480;
        // Lines only along numeric axes (cluster size, tilt); categories have no order to follow.
        plot.lines = std::all_of(axes.begin() + (axes.size() > 1 ? 1 : 0), axes.end(), [](const SweepAxis& a) { return a.numeric; });
        plot.series = std::move(pareto);
        plot.point_labels = std::move(pareto_labels);
        write_text_file(path_in(dir, "speedup_vs_memory.svg"), line_plot_svg(plot));
        written.push_back("speedup_vs_memory.svg");
    }

    // Speedup against the surface-area ratio over every run (figure 9's metric),
    // each point labelled with its sweep values.
    std::string label_keys;
    for (const SweepAxis& a : axes) label_keys += (label_keys.empty() ? "" : " / ") + a.name;
    for (const std::string& method : others) {
        ScatterPlot scatter;
        scatter.axes.title = "speedup of " + method + " vs AABB/OBB surface-area ratio";
        scatter.axes.subtitle = preset_text + (runs.size() <= 40 && !label_keys.empty() ? "; labels: " + label_keys : "");
        scatter.axes.x_label = "sum AABB area / sum OBB area (paper OBBs)";
        scatter.axes.y_label = "speedup of " + method + " over " + bname;
        for (const RunResult& r : runs) {
            const double s = r.speedup(method);
            if (!(s > 0)) continue;
            std::string label;
            if (runs.size() <= 40)
                for (const SweepAxis& a : axes)
                    label += (label.empty() ? "" : " / ") + a.tick[a.index_of(r)];
            scatter.points.push_back({r.areas.ratio_paper(), s, label});
        }
        if (scatter.points.size() < 2) continue;
        std::vector<double> xs;
        for (const ScatterPoint& p : scatter.points) xs.push_back(p.x);
        scatter.axes.log_x = spans_decades(xs, 1.0);  // a ratio: log once it spans a decade
        scatter.guide = ScatterGuide::LeastSquares;
        const std::string file = one ? "speedup_vs_area_ratio.svg" : "speedup_vs_area_ratio_" + method + ".svg";
        write_text_file(path_in(dir, file), scatter_plot_svg(scatter));
        written.push_back(file);
    }
    return written;
}

}  // namespace rtc
