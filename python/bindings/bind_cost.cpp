// Cost presets, priced runs and pricing without tracing: cycles are a pure
// function of the counts (sim/hardware/cost_model.h), so Python can re-price
// a traced run under any preset, or under costs it edits itself.
#include "common.h"
#include "priced.h"

#include "sim/util/json_file.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace rtc::py_bind {

namespace {

py::array_t<double> to_array(const std::array<double, kEventCount>& a) {
    py::array_t<double> out(static_cast<py::ssize_t>(kEventCount));
    std::copy(a.begin(), a.end(), out.mutable_data());
    return out;
}

py::dict execution_dict(const ExecutionModel& e) {
    py::dict d;
    d["model"] = execution_name(e.kind);
    d["warp_width"] = e.warp_width;
    d["tile"] = py::make_tuple(e.tile_width, e.tile_height);
    d["rt_parallel_lanes"] = e.rt_parallel_lanes;
    return d;
}

py::dict warp_dict(const WarpTotals& w, int width, const Roofline& roof) {
    py::dict d;
    const FrameTerms t = w.terms(roof);
    d["cycles"] = t.cycles;
    d["bound"] = bound_name(t.bound);
    if (roof.enabled) {
        d["resident_warps"] = roof.warps;
        d["sm_latency"] = t.latency;
        d["sm_issue"] = t.issue;
        d["sm_rt_unit"] = t.rt_unit;
    }
    d["shader"] = w.shader;
    d["rt_unit"] = w.rt;
    d["hand_off"] = w.handoff;
    d["programs"] = w.programs;
    d["rt_lane_sum"] = w.rt_lane_sum;
    d["waves"] = w.waves;
    d["lanes"] = w.lanes;
    d["rounds"] = w.rounds;
    d["active_lane_rounds"] = w.active_lane_rounds;
    d["simt_efficiency"] = w.simt_efficiency(width);
    d["rt_simt_efficiency"] = w.rt_efficiency(width);
    d["occupancy"] = w.occupancy(width);
    return d;
}

EventTotals totals_from(const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& a) {
    if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != kEventCount)
        throw std::invalid_argument("expected one count per event (" + std::to_string(kEventCount) +
                                    " values in EVENT_NAMES order)");
    EventTotals t;
    std::copy(a.data(), a.data() + kEventCount, t.n.begin());
    return t;
}

// Cycles of each row of `counts` (..., events) under the per-ray model:
// `price_row` prices one row of `Counts`. Returns the (...) array.
template <class Counts, class Scalar, int Flags, class PriceRow>
py::array_t<double> price_rows(const py::array_t<Scalar, Flags>& counts, PriceRow price_row) {
    if (counts.ndim() < 1 || static_cast<std::size_t>(counts.shape(counts.ndim() - 1)) != kEventCount)
        throw std::invalid_argument("expected a last axis of one count per event (" + std::to_string(kEventCount) +
                                    " values in EVENT_NAMES order)");
    const std::vector<py::ssize_t> shape(counts.shape(), counts.shape() + counts.ndim() - 1);
    py::array_t<double> out(shape);
    const auto rows = static_cast<std::size_t>(out.size());
    const Scalar* in = counts.data();
    double* cycles = out.mutable_data();
    py::gil_scoped_release release;
    Counts row;
    for (std::size_t r = 0; r < rows; ++r) {
        std::copy(in + r * kEventCount, in + (r + 1) * kEventCount, row.n.begin());
        cycles[r] = price_row(row);
    }
    return out;
}

}  // namespace

void bind_cost(py::module_& m) {
    py::class_<CostModel>(m, "CostModel", "A hardware cost preset (configs/hw/*.json): cycles per event.")
        .def_static("load", &load_cost_model, py::arg("path"), "Reads a preset file (strict, as the CLI).")
        .def_static("from_json", &parse_cost_model, py::arg("text"), py::arg("file") = "<python>",
                    "Parses preset JSON text; errors name `file` and the JSON path.")
        .def("to_json", &cost_model_to_json, "The preset in the configs/hw format.")
        .def_readwrite("name", &CostModel::name)
        .def_readwrite("description", &CostModel::description)
        .def_readwrite("features", &CostModel::features)
        .def_property("cycles", [](const CostModel& c) { return to_array(c.cycles); },
                      [](CostModel& c, const py::array_t<double, py::array::forcecast>& v) {
                          if (v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != kEventCount)
                              throw std::invalid_argument("expected one cost per event");
                          for (std::size_t i = 0; i < kEventCount; ++i)
                              if (!std::isfinite(v.at(i)) || v.at(i) < 0.0)
                                  throw std::invalid_argument("cost of " + std::string(kEventNames[i]) +
                                                              " must be finite and >= 0");
                          // As a break-even axis: a cost made of others (sum_of)
                          // that is set to another value is that value from now
                          // on; the other sums follow their terms' new costs.
                          std::erase_if(c.composed, [&](const ComposedCost& k) {
                              const auto i = static_cast<std::size_t>(k.target);
                              return v.at(i) != c.cycles[i];
                          });
                          for (std::size_t i = 0; i < kEventCount; ++i) c.cycles[i] = v.at(i);
                          c.settle();
                      },
                      "Cycles per event, in EVENT_NAMES order (a copy; assign a whole array to change). A "
                      "cost defined as a sum of others (sum_of) follows its terms unless assigned a new value.")
        .def_property_readonly("sources", [](const CostModel& c) {
            return std::vector<std::string>(c.source.begin(), c.source.end());
        }, "Provenance of each cost, in EVENT_NAMES order.")
        .def("set_source", [](CostModel& c, std::size_t event, std::string s) {
            c.source.at(event) = std::move(s);
        }, py::arg("event"), py::arg("source"))
        .def_property_readonly("execution", [](const CostModel& c) { return execution_dict(c.execution); },
                               "The execution model: per_ray or warp (width, tile, rt_parallel_lanes).")
        .def_property_readonly("is_warp", [](const CostModel& c) { return c.execution.warp(); })
        .def("copy", [](const CostModel& c) { return c; })
        .def("__copy__", [](const CostModel& c) { return c; })
        .def("__deepcopy__", [](const CostModel& c, py::dict) { return c; })
        .def("__repr__", [](const CostModel& c) {
            return "<CostModel " + c.name + " (" + execution_name(c.execution.kind) + ")>";
        });

    py::class_<Priced>(m, "PricedRun", "Cycles of one run's counts under one preset.")
        .def_property_readonly("supported", [](const Priced& p) { return p.run.supported; },
                               "False: the preset's hardware lacks a feature the method needs.")
        .def_property_readonly("missing_feature", [](const Priced& p) { return p.run.missing_feature; })
        .def_property_readonly("execution", [](const Priced& p) { return execution_name(p.run.execution); })
        .def_property_readonly("total_cycles", [](const Priced& p) { return p.run.total_cycles; },
                               "Under the preset's execution model.")
        .def_property_readonly("per_ray_cycles", [](const Priced& p) { return p.run.per_ray_cycles; },
                               "The per-ray sum, whatever the model.")
        .def_property_readonly("by_event", [](const Priced& p) { return to_array(p.run.by_event); },
                               "Per-ray-model cycles of each event, in EVENT_NAMES order.")
        .def_property_readonly("warp", [](const Priced& p) -> py::object {
            if (!p.warp) return py::none();
            return warp_dict(*p.warp, p.warp_width, p.roof);
        }, "The warp model's figures (waves, rounds, SIMT efficiency, cycles by unit), or None.")
        .def("__repr__", [](const Priced& p) {
            return "<PricedRun " + std::to_string(p.run.total_cycles) + " cycles (" +
                   execution_name(p.run.execution) + ")>";
        });

    m.def("price_totals", [](const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& counts,
                             const CostModel& model) {
        Priced p;
        p.run = price(totals_from(counts), model);
        return p;
    }, py::arg("counts"), py::arg("model"),
          "Per-ray model: cycles = sum(count[e] * cost[e]) of event totals (EVENT_NAMES order).");

    // Per pixel (or per ray), the per-ray model by the CLI's own call: the
    // cycles of its heat maps and cycles_<method>_<preset>.npy arrays.
    m.def("price_pixels", [](const py::array_t<std::uint32_t, py::array::c_style>& counts, const CostModel& model) {
        return price_rows<RayCounts>(counts, [&](const RayCounts& c) { return price_cycles(c, model); });
    }, py::arg("counts"), py::arg("model"));
    // Counts of other types (a sum of pixels may not fit 32 bits): the same
    // products summed in the same order (price(), as for a frame's totals).
    m.def("price_pixels", [](const py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>& counts,
                             const CostModel& model) {
        return price_rows<EventTotals>(counts, [&](const EventTotals& t) { return price(t, model).total_cycles; });
    }, py::arg("counts"), py::arg("model"),
          "Per-ray model: the cycles of each row of counts (..., events), e.g. per-pixel counts (H, W, events): "
          "an (H, W) float64 array, as the CLI's per-pixel cycles.");
}

}  // namespace rtc::py_bind
