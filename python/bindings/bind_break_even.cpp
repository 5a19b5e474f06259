// Break-even maps of a live run, computed by the CLI's code
// (break_even_grid, sim/report/break_even_maps.cpp): under a warp preset the
// recorded waves' effective counts, costs made of others (sum_of) following
// the axes, and the band over the run's cost draws. Python draws the cells;
// it prices none of them itself, so its map of a run is the CLI's.
#include "common.h"
#include "interruptible.h"

#include "sim/report/report.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <memory>

namespace rtc::py_bind {

namespace {

// (ny, nx) array of `v` (row 0 the lowest y), owning a copy.
template <class T>
py::array_t<T> grid_array(const std::vector<T>& v, int ny, int nx) {
    py::array_t<T> a({static_cast<py::ssize_t>(ny), static_cast<py::ssize_t>(nx)});
    if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(T));
    return a;
}

py::dict cell_dict(const BreakEvenCell& c, const BreakEvenGrid& g) {
    py::dict d;
    d["winner"] = c.winner >= 0 ? py::object(py::str(g.methods.at(static_cast<std::size_t>(c.winner)))) : py::none();
    d["lead"] = c.margin;
    d["lead_interval"] = g.draws > 0 ? py::object(py::make_tuple(c.band[0], c.band[1])) : py::none();
    return d;
}

py::dict grid_dict(const BreakEvenGrid& g) {
    py::dict d;
    d["methods"] = g.methods;
    d["nx"] = g.nx;
    d["ny"] = g.ny;
    d["x"] = py::dict(py::arg("label") = g.x_label, py::arg("lo") = g.x_lo, py::arg("hi") = g.x_hi);
    d["y"] = py::dict(py::arg("label") = g.y_label, py::arg("lo") = g.y_lo, py::arg("hi") = g.y_hi);
    d["winner"] = grid_array(g.winner, g.ny, g.nx);
    d["margin"] = grid_array(g.margin, g.ny, g.nx);
    d["draws"] = g.draws;
    d["band_low"] = g.band_lo.empty() ? py::object(py::none()) : py::object(grid_array(g.band_lo, g.ny, g.nx));
    d["band_high"] = g.band_hi.empty() ? py::object(py::none()) : py::object(grid_array(g.band_hi, g.ny, g.nx));
    std::vector<bool> doubt(g.winner.size());
    for (std::size_t i = 0; i < doubt.size(); ++i) doubt[i] = g.uncertain(i);
    py::array_t<bool> in_doubt({static_cast<py::ssize_t>(g.ny), static_cast<py::ssize_t>(g.nx)});
    std::copy(doubt.begin(), doubt.end(), in_doubt.mutable_data());
    d["in_doubt"] = in_doubt;
    py::dict mark = cell_dict(g.at_mark, g);
    mark["x"] = g.mark_x;
    mark["y"] = g.mark_y;
    mark["label"] = g.mark_label;
    d["mark"] = mark;
    d["caption"] = g.caption;
    return d;
}

}  // namespace

void bind_break_even(py::module_& m) {
    m.def("break_even_grid", [](const RunHandle& h, const std::string& map_json, const std::string& file) {
        // The map parsed and checked as a config's break_even entry is.
        const nlohmann::json map = nlohmann::json::parse(map_json);
        const BreakEvenSpec spec = parse_break_even_spec(map, file, "/break_even", h.run->config.methods);
        std::vector<const CostModel*> costs;
        for (const CostModel& c : h.run->costs) costs.push_back(&c);
        check_break_even_preset(spec, costs, file);
        // A large map with many draws takes seconds: Ctrl-C stops it (it polls between rows).
        return grid_dict(run_interruptible([&] { return break_even_grid(*h.run, spec); }));
    }, py::arg("run"), py::arg("map_json"), py::arg("file") = "<python>",
          "One break-even map of a traced run, as the CLI computes it: `map_json` is a config's break_even "
          "entry (name, preset, x, y, cells, methods). A dict of the cells ((ny, nx) arrays, row 0 the lowest "
          "y): winner (index into methods, -1 none), margin (runner-up / winner cycles), band_low/band_high "
          "and in_doubt over the run's cost draws, the mark (the preset's own costs) and the caption.");
}

}  // namespace rtc::py_bind
