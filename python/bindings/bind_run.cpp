// Runs from Python: a config (file or JSON text) planned exactly as the CLI
// plans it (overrides, sweep, strict parsing), each point traced with the GIL
// released, and the result kept in C++ for NumPy views.
#include "common.h"
#include "interruptible.h"

#include "sim/app/output_dir.h"
#include "sim/app/run_all.h"
#include "sim/config/input_files.h"
#include "sim/report/report.h"
#include "sim/plot/plot_svg.h"  // write_text_file
#include "sim/util/json_file.h"

#include <cmath>
#include <filesystem>
#include <optional>

namespace rtc::py_bind {

namespace {

struct PlanHandle {
    std::shared_ptr<const RunPlan> plan;
};

// The CLI's --max-rays, --max-memory, --force (and the sweep size ceiling).
WorkLimits limits_from(const py::dict& d) {
    WorkLimits l;
    // As the CLI's --max-rays and --max-memory: a finite number >= 1.
    const auto ceiling = [](const std::string& k, const py::handle& value) {
        if (!py::isinstance<py::int_>(value) && !py::isinstance<py::float_>(value))
            throw InputError("limits: " + k + ": expected a finite number >= 1, got " + std::string(py::str(py::repr(value))));
        const double v = value.cast<double>();
        if (!(v >= 1.0) || !std::isfinite(v))
            throw InputError("limits: " + k + ": expected a finite number >= 1, got " + std::string(py::str(py::repr(value))));
        return v;
    };
    for (const auto& [key, value] : d) {
        const std::string k = py::str(key);
        if (k == "max_rays") l.max_rays = ceiling(k, value);
        else if (k == "max_memory") l.max_memory = ceiling(k, value);
        else if (k == "max_sweep_points") l.max_sweep_points = ceiling(k, value);
        else if (k == "max_break_even") l.max_break_even = ceiling(k, value);
        else if (k == "force") {
            if (!py::isinstance<py::bool_>(value))
                throw InputError("limits: force: expected True or False, got " + std::string(py::str(py::repr(value))));
            l.force = value.cast<bool>();
        }
        else throw std::invalid_argument("limits: unknown key " + k +
                                         " (max_rays, max_memory, max_sweep_points, max_break_even, force)");
    }
    return l;
}

PlanHandle make_plan(const std::string& text, const std::string& file, const std::vector<std::string>& sets,
                     const py::dict& limits) {
    return {std::make_shared<const RunPlan>(
        plan_runs(parse_json_text(text, file), file, sets, limits_from(limits), sweep_key_order(text, sets)))};
}

// The outputs the CLI writes for one run: report.json and, unless the config
// turns them off, the render, heat maps, ratio maps and .npy arrays, into a
// directory prepared (empty, locked, marked) by the caller as the CLI's is.
void write_run_files(const RunResult& r, const std::string& dir) {
    if (r.config.output.images) write_images(r, dir);
    if (r.config.output.arrays) (void)write_arrays(r, dir);
    const BreakEvenGrids grids = break_even_grids(r);  // once, for the pictures and the report
    (void)write_break_even_maps(r, grids, dir);
    const nlohmann::ordered_json break_even = break_even_json(r, grids);
    // Last: a report.json beside cut arrays is never left behind.
    write_text_file((std::filesystem::path(dir) / "report.json").string(), report_json(r, &break_even).dump(2) + "\n");
}

// Under the CLI's rules (sim/app/output_dir.h): a missing or empty directory
// (or, with force, one simulate wrote), locked while written, marked complete
// only after its last file.
void write_outputs(const RunResult& r, const std::string& dir, bool force) {
    OutputDir owned(dir, force);
    write_run_files(r, dir);
    owned.finish();
}

RunHandle run_plan_point(const PlanHandle& h, std::size_t i, unsigned threads, bool progress,
                         bool record_warps, bool keep_rays, const std::string& out_dir) {
    if (i >= h.plan->points.size()) throw py::index_error("no sweep point " + std::to_string(i));
    RunContext ctx;
    ctx.threads = threads;
    ctx.quiet = !progress;
    ctx.record_warps = record_warps;
    ctx.keep_rays = keep_rays;
    ctx.out_dir = out_dir;
    auto run = std::make_shared<RunResult>();
    // The directory prepared as the CLI's before tracing (rays.bin is written
    // while tracing): owned until the last file, then marked complete; an
    // error or Ctrl-C leaves it marked unfinished, which the readers refuse.
    std::optional<OutputDir> owned;
    if (!out_dir.empty()) owned.emplace(out_dir, h.plan->limits.force, input_paths(h.plan->parsed, h.plan->file));
    // Tracing runs on `threads` cores without Python, and Ctrl-C stops it.
    run_interruptible([&] {
        *run = run_point(*h.plan, i, ctx);
        throw_if_interrupted();  // nothing written after a late Ctrl-C
        if (owned) write_run_files(*run, out_dir);
    });
    if (owned) owned->finish();
    return {run};
}

std::string summary(const std::vector<RunHandle>& runs, const std::string& format, const std::string& table) {
    std::vector<RunResult> copies;  // the tables read totals only
    for (const RunHandle& h : runs) copies.push_back(*h.run);
    if (table != "summary" && table != "speedups")
        throw std::invalid_argument("table: expected summary or speedups, got " + table);
    const Table t = table == "summary" ? summary_table(copies) : speedup_table(copies);
    if (format == "console") return t.to_console();
    if (format == "csv") return t.to_csv();
    if (format == "markdown") return t.to_markdown();
    throw std::invalid_argument("format: expected console, csv or markdown, got " + format);
}

}  // namespace

void bind_run(py::module_& m) {
    py::class_<PlanHandle>(m, "Plan", "A config's runs, planned and parsed as the CLI does.")
        .def_static("from_file", [](const std::string& path, const std::vector<std::string>& sets,
                                    const py::dict& limits) {
            return make_plan(read_text_file(path), path, sets, limits);
        }, py::arg("path"), py::arg("sets") = std::vector<std::string>{}, py::arg("limits") = py::dict(),
           "limits: max_rays, max_memory (bytes), max_sweep_points, force (the CLI's options).")
        .def_static("from_json", &make_plan, py::arg("text"), py::arg("file"),
                    py::arg("sets") = std::vector<std::string>{}, py::arg("limits") = py::dict(),
                    "`file` names the config in messages; relative paths resolve beside it.")
        .def_property_readonly("estimate", [](const PlanHandle& h) {
            const WorkEstimate& w = h.plan->work;
            py::dict d;
            d["rays"] = w.rays;
            d["primitives"] = w.primitives;
            d["memory_bytes"] = w.memory_bytes;
            d["rays_detail"] = w.rays_detail;
            d["memory_detail"] = w.memory_detail;
            d["break_even"] = w.break_even;
            return d;
        }, "The work estimate the limits were checked against (rays over every method and point).")
        .def("__len__", [](const PlanHandle& h) { return h.plan->points.size(); })
        .def_property_readonly("file", [](const PlanHandle& h) { return h.plan->file; })
        .def_property_readonly("config_json", [](const PlanHandle& h) { return h.plan->config.dump(); },
                               "The config with the overrides applied (still with its sweep block).")
        .def("point_json", [](const PlanHandle& h, std::size_t i) { return h.plan->points.at(i).config.dump(); })
        .def("values_json", [](const PlanHandle& h, std::size_t i) { return h.plan->points.at(i).values.dump(); })
        .def("label", [](const PlanHandle& h, std::size_t i) { return h.plan->points.at(i).label; })
        .def("run", &run_plan_point, py::arg("index"), py::arg("threads") = 0, py::arg("progress") = true,
             py::arg("record_warps") = false, py::arg("keep_rays") = false, py::arg("out_dir") = "",
             "Traces point `index` (GIL released; Ctrl-C raises KeyboardInterrupt and writes nothing more) "
             "under the plan's limits. With out_dir, writes what the CLI writes there.");

    py::class_<RunHandle>(m, "Run", "One traced run (a RunResult).")
        .def("report_json", [](const RunHandle& h, int indent) { return report_json(*h.run).dump(indent); },
             py::arg("indent") = -1, "report.json's text (the CLI writes indent=2 plus a newline).")
        .def("write_outputs", [](const RunHandle& h, const std::string& dir, bool force) {
            py::gil_scoped_release release;
            write_outputs(*h.run, dir, force);
        }, py::arg("dir"), py::arg("force") = false,
           "report.json, the images and break-even maps, as the CLI writes them and under its rules: `dir` "
           "missing or empty (force: or one simulate wrote, emptied first), marked complete when done.")
        .def_property_readonly("name", [](const RunHandle& h) { return h.run->config.name; })
        .def_property_readonly("file", [](const RunHandle& h) { return h.run->config.file; })
        .def_property_readonly("baseline", [](const RunHandle& h) { return h.run->config.baseline; })
        .def_property_readonly("sweep_label", [](const RunHandle& h) { return h.run->sweep_label; })
        .def_property_readonly("sweep_values_json", [](const RunHandle& h) { return h.run->point.values.dump(); })
        .def_property_readonly("effective_config_json", [](const RunHandle& h) {
            return h.run->point.config.dump();
        })
        .def_property_readonly("costs", [](const RunHandle& h) { return h.run->costs; },
                               "The run's cost presets (copies), primary first.")
        .def_property_readonly("warp_preset", [](const RunHandle& h) -> py::object {
            for (std::size_t p = 0; p < h.run->costs.size(); ++p)
                if (h.run->costs[p].execution.warp()) return py::int_(p);
            return py::none();
        }, "Index of the first warp preset (the one per-pixel warp cycles are of), or None.")
        .def_property_readonly("method_names", [](const RunHandle& h) {
            std::vector<std::string> out;
            for (const MethodRun& r : h.run->methods) out.push_back(r.method);
            return out;
        })
        .def("method", [](const RunHandle& h, const std::string& name) {
            for (std::size_t i = 0; i < h.run->methods.size(); ++i)
                if (h.run->methods[i].method == name) return MethodHandle{h.run, i};
            throw py::key_error("no method " + name + " in this run");
        }, py::arg("name"))
        .def("speedup", [](const RunHandle& h, const std::string& method, std::size_t preset) {
            return h.run->speedup(method, preset);
        }, py::arg("method"), py::arg("preset") = 0,
           "cycles(baseline) / cycles(method) under preset `preset`; 0 when not available.")
        .def("memory_overhead_percent", [](const RunHandle& h, const std::string& method) {
            return h.run->memory_overhead_percent(method);
        }, py::arg("method"))
        .def_property_readonly("width", [](const RunHandle& h) { return h.run->camera.width; })
        .def_property_readonly("height", [](const RunHandle& h) { return h.run->camera.height; })
        .def("_free_pixels", [](const RunHandle& h) {
            for (MethodRun& r : h.run->methods) {
                FrameResult& f = r.frame;
                f.pixel_counts = {};
                f.radiance = {};
                for (PresetWarp& w : f.warp) w.pixel_cycles = {};
                f.pixel_simt_active = {};
                f.pixel_simt_slots = {};
            }
        }, "Drops the per-pixel data (as the CLI does for finished sweep points). Only before any "
           "array viewing them was handed out: rtcsim.sweep calls it right after tracing.");

    m.def("summary_table", &summary, py::arg("runs"), py::arg("format") = "console", py::arg("table") = "summary",
          "The CLI's tables over runs: summary (summary.*, the terminal) or speedups (speedups.*, every "
          "method under every preset); format console, csv or markdown.");
}

}  // namespace rtc::py_bind
