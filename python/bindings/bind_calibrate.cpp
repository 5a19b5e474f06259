// Calibration from Python: the `calibrate` block of a config (the same
// schema and errors as `simulate calibrate`) fitted on runs already traced,
// by re-pricing their counts, or their recorded waves under a warp preset
// (shared with the runs, not copied).
#include "common.h"

#include "sim/app/calibrate_runs.h"
#include "sim/calibrate/calibrate_report.h"
#include "sim/util/json_file.h"

#include <cmath>
#include <map>

namespace rtc::py_bind {

namespace {

py::object number(double x) { return std::isnan(x) ? py::object(py::none()) : py::object(py::float_(x)); }

py::list run_fits(const CalibrationResult& r) {
    py::list out;
    for (const RunFit& f : r.runs) {
        py::dict d;
        d["label"] = f.label;
        d["target"] = f.target;
        d["start"] = f.start;
        d["fitted"] = f.fitted;
        d["rel_error"] = f.rel_error;
        out.append(d);
    }
    return out;
}

py::list parameter_fits(const CalibrationResult& r) {
    py::list out;
    for (const ParameterFit& p : r.parameters) {
        py::dict d;
        py::list events;
        for (const Event e : p.events) events.append(std::string(event_name(e)));
        d["events"] = events;
        d["tie"] = p.tie == Tie::Scale ? "scale" : "value";
        d["min"] = p.lo;
        d["max"] = p.hi;
        d["start"] = p.start;
        d["fitted"] = p.fitted;
        d["std_error"] = number(p.std_error);
        d["sensitivity"] = p.sensitivity;
        d["at_lower"] = p.at_lower;
        d["at_upper"] = p.at_upper;
        d["unidentifiable"] = p.unidentifiable;
        d["note"] = p.note;
        out.append(d);
    }
    return out;
}

}  // namespace

void bind_calibrate(py::module_& m) {
    py::class_<CalibrationOutcome>(m, "Calibration", "A fitted cost preset and how well it fits.")
        .def_property_readonly("model", [](const CalibrationOutcome& c) { return c.result.model; },
                               "The start preset with the fitted costs and their provenance.")
        .def_property_readonly("runs", [](const CalibrationOutcome& c) { return run_fits(c.result); },
                               "Per run: label, target, start and fitted speedups, relative error.")
        .def_property_readonly("parameters", [](const CalibrationOutcome& c) { return parameter_fits(c.result); })
        .def_property_readonly("skipped", [](const CalibrationOutcome& c) { return c.skipped; },
                               "Runs without a target.")
        .def_property_readonly("rms_log_error_start", [](const CalibrationOutcome& c) {
            return c.result.rms_log_error_start;
        })
        .def_property_readonly("rms_log_error", [](const CalibrationOutcome& c) { return c.result.rms_log_error; })
        .def_property_readonly("degrees_of_freedom", [](const CalibrationOutcome& c) {
            return c.result.degrees_of_freedom;
        })
        .def_property_readonly("iterations", [](const CalibrationOutcome& c) { return c.result.iterations; })
        .def_property_readonly("converged", [](const CalibrationOutcome& c) { return c.result.converged; })
        .def_property_readonly("output", [](const CalibrationOutcome& c) { return c.desc.output; },
                               "The block's output path (not written by Python unless asked).")
        .def("report_markdown", [](const CalibrationOutcome& c) { return calibration_report_markdown(c.result); },
             "calibration.md, as simulate calibrate writes it.")
        .def("preset_json", [](const CalibrationOutcome& c) { return calibrated_preset_json(c.result); },
             "The fitted preset in the configs/hw format.");

    m.def("calibrate", [](const std::vector<RunHandle>& runs, const std::string& config_text,
                          const std::string& file) {
        if (runs.empty()) throw std::invalid_argument("calibrate: no runs");
        const nlohmann::json config = parse_json_text(config_text, file);
        std::vector<RunResult*> pointers;
        std::map<const RunResult*, std::shared_ptr<RunResult>> owners;
        for (const RunHandle& h : runs) {
            pointers.push_back(h.run.get());
            owners[h.run.get()] = h.run;
        }
        py::gil_scoped_release release;
        // The waves stay in the runs: the fit shares them (aliasing pointers).
        return calibrate_results(pointers, plan_calibrate(config, file), [&](RunResult& r, MethodRun& method) {
            return std::shared_ptr<const WarpTrace>(owners.at(&r), &method.frame.warp_trace);
        });
    }, py::arg("runs"), py::arg("config"), py::arg("file"),
          "Fits the `calibrate` block of `config` (JSON text) on traced runs; errors name `file`.");
}

}  // namespace rtc::py_bind
