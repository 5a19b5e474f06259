// Break-even maps of a run: re-price its recorded event counts on a grid of
// two swept costs (no tracing again: pricing is linear in the costs) and draw
// which method wins where (sim/plot/break_even.h).
#include "sim/plot/break_even.h"
#include "sim/report/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
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

double axis_value(const BreakEvenAxis& a, int i, int n) {
    return a.min * std::pow(a.max / a.min, (i + 0.5) / n);  // cell centres on a log axis
}

}  // namespace

std::array<double, kEventCount> break_even_counts(const MethodRun& m, const CostModel* warp_preset) {
    std::array<double, kEventCount> c{};
    if (warp_preset) {
        (void)m.frame.warp_trace.price(*warp_preset, &c);
    } else {
        for (std::size_t i = 0; i < kEventCount; ++i) c[i] = static_cast<double>(m.frame.totals.n[i]);
    }
    return c;
}

std::vector<std::string> write_break_even_maps(const RunResult& run, const std::string& dir) {
    std::vector<std::string> written;
    for (const BreakEvenSpec& spec : run.config.break_even) {
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
            if (methods[k]) linear[k] = break_even_counts(*methods[k], warp ? base : nullptr);
        g.caption += warp ? "\ncycles: warp model, first order around the mark (exact there)" : "\ncycles: per-ray sum of every ray's events";
        g.has_mark = true;
        g.mark_x = spec.x.scale ? 1.0 : (*base)[spec.x.events.front()];
        g.mark_y = spec.y.scale ? 1.0 : (*base)[spec.y.events.front()];
        g.mark_label = base->name;
        // An axis sets its events' costs; a cost made of others (sum_of)
        // follows its terms, unless an axis sets it itself.
        CostModel model = *base;
        std::erase_if(model.composed, [&](const ComposedCost& c) {
            return std::count(spec.x.events.begin(), spec.x.events.end(), c.target) +
                   std::count(spec.y.events.begin(), spec.y.events.end(), c.target);
        });
        for (int iy = 0; iy < g.ny; ++iy) {
            for (const Event e : spec.y.events) model[e] = axis_value(spec.y, iy, g.ny) * (spec.y.scale ? (*base)[e] : 1.0);
            for (int ix = 0; ix < g.nx; ++ix) {
                for (const Event e : spec.x.events) model[e] = axis_value(spec.x, ix, g.nx) * (spec.x.scale ? (*base)[e] : 1.0);
                model.settle();
                double best = std::numeric_limits<double>::infinity(), second = best;
                int winner = -1;
                for (std::size_t k = 0; k < methods.size(); ++k) {
                    if (!methods[k]) continue;
                    double c = 0.0;
                    for (std::size_t i = 0; i < kEventCount; ++i) c += linear[k][i] * model.cycles[i];
                    if (c < best) second = best, best = c, winner = static_cast<int>(k);
                    else if (c < second) second = c;
                }
                g.winner.push_back(winner);
                g.margin.push_back(winner >= 0 && best > 0 ? second / best : 1.0);
            }
        }
        const std::string path = (std::filesystem::path(dir) / ("break_even_" + spec.name + ".png")).string();
        BreakEvenOptions options;
        options.scale = 2;  // readable text
        write_png(render_break_even(g, options), path);
        written.push_back(path);
    }
    return written;
}

}  // namespace rtc
