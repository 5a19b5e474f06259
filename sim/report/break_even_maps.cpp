// Break-even maps of a run: re-price its recorded event counts on a grid of
// two swept costs (no tracing again: pricing is linear in the costs) and draw
// which method wins where (sim/plot/break_even.h). The run's cost draws of
// the preset are re-priced the same way, so a cell also says whether the
// calibration's 90 % band leaves its winner in doubt.
#include "sim/plot/break_even.h"
#include "sim/report/report.h"

#include "sim/execution/interrupt.h"
#include "sim/hardware/uncertainty/cost_uncertainty.h"
#include "sim/plot/plot_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

namespace rtc {

namespace {

std::string axis_label(const BreakEvenAxis& a) {
    std::string s;
    if (a.scale) {  // a factor: name the first and last of a long list
        const std::string first(event_name(a.events.front())), last(event_name(a.events.back()));
        s = a.events.size() == 1 ? first : first + (a.events.size() == 2 ? ", " : " .. ") + last;
        return "factor on " + s + " (1 = the preset)";
    }
    for (const Event e : a.events) s += (s.empty() ? "" : " = ") + std::string(event_name(e));
    return s + " [cycles]";
}

std::string number4(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

double axis_value(const BreakEvenAxis& a, int i, int n) {
    return a.min * std::pow(a.max / a.min, (i + 0.5) / n);  // cell centres on a log axis
}

}  // namespace

std::array<double, kEventCount> break_even_counts(const MethodRun& m, const CostModel* warp_preset,
                                                  const Roofline& roof) {
    std::array<double, kEventCount> c{};
    if (warp_preset) {
        // On the SM of the method's pipeline, as the run priced it.
        (void)m.frame.warp_trace.price(*warp_preset, roof, c);
    } else {
        for (std::size_t i = 0; i < kEventCount; ++i) c[i] = static_cast<double>(m.frame.totals.n[i]);
    }
    return c;
}

BreakEvenGrid break_even_grid(const RunResult& run, const BreakEvenSpec& spec) {
    const CostModel* base = nullptr;
    for (const CostModel& c : run.costs)
        if (c.name == spec.preset) base = &c;
    // parse_run_config checked the preset is the run's and prices every axis event.
    if (!base) throw std::logic_error("break-even map \"" + spec.name + "\": its preset was not checked");
    BreakEvenGrid g;
    g.nx = g.ny = spec.cells;
    g.x_lo = spec.x.min, g.x_hi = spec.x.max, g.y_lo = spec.y.min, g.y_hi = spec.y.max;
    g.x_label = axis_label(spec.x);
    g.y_label = axis_label(spec.y);
    const std::string label = run.sweep_label.empty() ? run.config.name : run.sweep_label;
    g.title = "fastest method: " + spec.name;
    g.caption = label + "\nother costs: " + base->name + "; a method the preset cannot run is left out";
    // Every method of the map keeps its colour in every map; those that
    // cannot run here are listed as n/a and never win.
    std::vector<const MethodRun*> methods;
    for (const MethodRun& m : run.methods) {
        if (!spec.methods.empty() && std::find(spec.methods.begin(), spec.methods.end(), m.method) == spec.methods.end())
            continue;
        const MethodEntry* e = find_method(m.method);
        const bool runs = m.runnable && e && base->missing_feature(e->info.needs).empty();
        methods.push_back(runs ? &m : nullptr);
        g.methods.push_back(runs ? m.method : m.method + " (n/a)");
    }
    // Each method's cycles as a linear function of the costs. Under a warp
    // preset, the effective counts of its recorded waves at the preset's
    // own costs: exact at the mark, first order around it (the lanes and
    // calls that win each max are the mark's). Else the per-ray counts.
    // (A map mixes no models: if one method's waves are missing, all use totals.)
    bool warp = base->execution.warp();
    for (const MethodRun* m : methods) warp = warp && (!m || m->frame.warp_trace.waves() > 0);
    std::vector<EffectiveCounts> linear(methods.size(), EffectiveCounts{});
    for (std::size_t k = 0; k < methods.size(); ++k)
        if (methods[k]) {
            const auto p = static_cast<std::size_t>(base - run.costs.data());
            linear[k] = break_even_counts(*methods[k], warp ? base : nullptr,
                                          p < methods[k]->roof.size() ? methods[k]->roof[p] : Roofline{});
        }
    g.caption += warp ? "\ncycles: warp model, first order around the mark (exact there)" : "\ncycles: per-ray sum of every ray's events";
    g.has_mark = true;
    g.mark_x = spec.x.scale ? 1.0 : (*base)[spec.x.events.front()];
    g.mark_y = spec.y.scale ? 1.0 : (*base)[spec.y.events.front()];
    g.mark_label = base->name;
    // An axis sets its events' costs; a cost made of others (sum_of)
    // follows its terms, unless an axis sets it itself. The same for the
    // run's draws of the preset (the ones its speedup intervals come from).
    const auto free_axes = [&](CostModel& m) {
        std::erase_if(m.composed, [&](const ComposedCost& c) {
            return std::count(spec.x.events.begin(), spec.x.events.end(), c.target) +
                   std::count(spec.y.events.begin(), spec.y.events.end(), c.target);
        });
    };
    CostModel model = *base;
    free_axes(model);
    const std::vector<CostModel> draws =
        draw_cost_models(*base, static_cast<std::size_t>(std::max(run.config.uncertainty.draws, 0)), run.config.uncertainty.seed);
    std::vector<CostModel> drawn = draws;
    for (CostModel& m : drawn) free_axes(m);
    g.draws = static_cast<int>(draws.size());
    // One point of the map: set the axes (a factor scales each model's own
    // cost, so a draw keeps its deviation from the preset), price every method.
    const auto set_axes = [&](CostModel& m, const CostModel& from, double xv, double yv) {
        for (const Event e : spec.y.events) m[e] = yv * (spec.y.scale ? from[e] : 1.0);
        for (const Event e : spec.x.events) m[e] = xv * (spec.x.scale ? from[e] : 1.0);
        m.settle();
    };
    const auto price = [&](std::size_t k, const CostModel& m) {
        double c = 0.0;
        for (std::size_t i = 0; i < kEventCount; ++i) c += linear[k][i] * m.cycles[i];
        return c;
    };
    std::vector<double> leads(draws.size());
    const auto cell = [&](double xv, double yv) {
        BreakEvenCell out;
        set_axes(model, *base, xv, yv);
        double best = std::numeric_limits<double>::infinity(), second = best;
        for (std::size_t k = 0; k < methods.size(); ++k) {
            if (!methods[k]) continue;
            const double c = price(k, model);
            if (c < best) second = best, best = c, out.winner = static_cast<int>(k);
            else if (c < second) second = c;
        }
        out.margin = out.winner >= 0 && best > 0 ? second / best : 1.0;
        out.band = {out.margin, out.margin};
        if (out.winner < 0 || draws.empty() || !std::isfinite(out.margin)) return out;
        // The winner's lead under each draw: the best other method's cycles
        // over the winner's (below 1: another method wins that draw).
        const auto w = static_cast<std::size_t>(out.winner);
        for (std::size_t d = 0; d < drawn.size(); ++d) {
            set_axes(drawn[d], draws[d], xv, yv);
            const double cw = price(w, drawn[d]);
            double other = std::numeric_limits<double>::infinity();
            for (std::size_t k = 0; k < methods.size(); ++k)
                if (methods[k] && k != w) other = std::min(other, price(k, drawn[d]));
            leads[d] = cw > 0 ? other / cw : 1.0;
        }
        out.band = interval_90(leads, out.margin);
        return out;
    };
    for (int iy = 0; iy < g.ny; ++iy) {
        throw_if_interrupted();  // a large map with many draws takes minutes
        for (int ix = 0; ix < g.nx; ++ix) {
            const BreakEvenCell c = cell(axis_value(spec.x, ix, g.nx), axis_value(spec.y, iy, g.ny));
            g.winner.push_back(c.winner);
            g.margin.push_back(c.margin);
            if (!draws.empty()) g.band_lo.push_back(c.band[0]), g.band_hi.push_back(c.band[1]);
        }
    }
    g.at_mark = cell(g.mark_x, g.mark_y);
    return g;
}

BreakEvenGrids break_even_grids(const RunResult& run) {
    BreakEvenGrids grids;
    for (const BreakEvenSpec& spec : run.config.break_even) grids.push_back(break_even_grid(run, spec));
    return grids;
}

std::vector<std::string> write_break_even_maps(const RunResult& run, const std::string& dir) {
    return write_break_even_maps(run, break_even_grids(run), dir);
}

std::vector<std::string> write_break_even_maps(const RunResult& run, const BreakEvenGrids& grids,
                                               const std::string& dir) {
    std::vector<std::string> written;
    for (std::size_t i = 0; i < run.config.break_even.size() && i < grids.size(); ++i) {
        const BreakEvenSpec& spec = run.config.break_even[i];
        const BreakEvenGrid& g = grids[i];
        const std::string path = (std::filesystem::path(dir) / ("break_even_" + spec.name + ".png")).string();
        BreakEvenOptions options;
        options.scale = 2;  // readable text
        write_png(render_break_even(g, options), path);
        written.push_back(path);
        // The cells' numbers, for scripts (report.json keeps the summary).
        const std::string cells = (std::filesystem::path(dir) / ("break_even_" + spec.name + ".json")).string();
        write_text_file(cells, break_even_cells_json(g).dump() + "\n");
        written.push_back(cells);
    }
    return written;
}

nlohmann::ordered_json break_even_cells_json(const BreakEvenGrid& g) {
    nlohmann::ordered_json j;
    j["methods"] = g.methods;
    j["nx"] = g.nx;
    j["ny"] = g.ny;
    j["x"] = {{"label", g.x_label}, {"lo", g.x_lo}, {"hi", g.x_hi}};
    j["y"] = {{"label", g.y_label}, {"lo", g.y_lo}, {"hi", g.y_hi}};
    j["draws"] = g.draws;
    j["winner"] = g.winner;  // row 0 = bottom (lowest y), left to right
    const auto rounded = [](const std::vector<double>& v) {  // 4 digits: a picture's numbers, not a fit's
        nlohmann::ordered_json a = nlohmann::ordered_json::array();
        for (const double x : v) a.push_back(std::isfinite(x) ? nlohmann::ordered_json(std::stod(number4(x))) : nlohmann::ordered_json(nullptr));
        return a;
    };
    j["margin"] = rounded(g.margin);
    j["band_low"] = rounded(g.band_lo);
    j["band_high"] = rounded(g.band_hi);
    return j;
}

nlohmann::ordered_json break_even_json(const RunResult& run) { return break_even_json(run, break_even_grids(run)); }

nlohmann::ordered_json break_even_json(const RunResult& run, const BreakEvenGrids& grids) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < run.config.break_even.size() && i < grids.size(); ++i) {
        const BreakEvenSpec& spec = run.config.break_even[i];
        const BreakEvenGrid& g = grids[i];
        nlohmann::ordered_json j;
        j["name"] = spec.name;
        j["preset"] = spec.preset;
        j["picture"] = "break_even_" + spec.name + ".png";
        j["cells"] = "break_even_" + spec.name + ".json";
        j["draws"] = g.draws;
        const auto name = [&](int w) { return w >= 0 ? nlohmann::ordered_json(g.methods[static_cast<std::size_t>(w)]) : nlohmann::ordered_json(nullptr); };
        std::map<std::string, double> share;  // of the cells each method wins
        int uncertain = 0;
        for (std::size_t i = 0; i < g.winner.size(); ++i) {
            if (g.winner[i] >= 0) share[g.methods[static_cast<std::size_t>(g.winner[i])]] += 1.0 / static_cast<double>(g.winner.size());
            uncertain += g.uncertain(i);
        }
        j["winner_share"] = share;
        // Where the 90 % band of the winner's lead contains 1.0: no winner the draws agree on.
        j["uncertain_share"] = g.band_lo.empty() ? nlohmann::ordered_json(nullptr)
                                                 : nlohmann::ordered_json(uncertain / static_cast<double>(g.winner.size()));
        j["mark"] = {{"x", g.mark_x}, {"y", g.mark_y}, {"winner", name(g.at_mark.winner)}, {"lead", g.at_mark.margin},
                     {"lead_interval", g.draws > 0 ? nlohmann::ordered_json(g.at_mark.band) : nlohmann::ordered_json(nullptr)}};
        list.push_back(j);
    }
    return list;
}

}  // namespace rtc
