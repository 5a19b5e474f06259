// The `rtcsim._rtcsim` extension: the simulator's runs, results, cost presets,
// scenes and calibration, bound with pybind11. The Python package around it
// (python/rtcsim) gives the documented API; this layer stays close to the C++.
#include "common.h"
#include "interruptible.h"

#include "core/events.h"
#include "sim/app/simulate_main.h"
#include "sim/methods/method.h"
#include "sim/util/version.h"

namespace rtc::py_bind {

py::array record_view(const void* data, std::size_t count, std::size_t itemsize,
                      const std::vector<Field>& fields, const py::handle& base) {
    py::list names, formats, offsets;
    for (const Field& f : fields) {
        names.append(f.name);
        formats.append(f.format);
        offsets.append(f.offset);
    }
    py::dict spec;
    spec["names"] = names;
    spec["formats"] = formats;
    spec["offsets"] = offsets;
    spec["itemsize"] = itemsize;
    const py::dtype dtype = py::module_::import("numpy").attr("dtype")(spec);
    py::array a(dtype, {static_cast<py::ssize_t>(count)}, {static_cast<py::ssize_t>(itemsize)}, data, base);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

namespace {

const char* unit_name(EventUnit u) {
    switch (u) {
        case EventUnit::Shader: return "shader";
        case EventUnit::RtUnit: return "rt_unit";
        case EventUnit::HandOff: return "hand_off";
        case EventUnit::Program: return "program";
        case EventUnit::Lockstep: return "lockstep";
    }
    return "?";
}

}  // namespace

}  // namespace rtc::py_bind

PYBIND11_MODULE(_rtcsim, m) {
    using namespace rtc;
    using namespace rtc::py_bind;
    m.doc() = "rtcsim: a simulator of GPU ray-tracing hardware with a cost model (C++ core)";
    // Bad input: the CLI's one-line message "<file>: <JSON path>: <problem>".
    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
    m.attr("__version__") = kVersion;

    py::tuple names(kEventCount), units(kEventCount);
    for (std::size_t i = 0; i < kEventCount; ++i) {
        names[i] = std::string(kEventNames[i]);
        units[i] = unit_name(kEventUnits[i]);
    }
    m.attr("EVENT_NAMES") = names;  // the order of every per-event array
    m.attr("EVENT_UNITS") = units;  // where each event's work happens (the warp model)

    m.def("method_names", [] {
        std::vector<std::string> out;
        for (const MethodEntry& e : registered_methods()) out.push_back(e.info.name);
        return out;
    }, "The registered methods (sim/methods/registry.cpp).");

    // A stop requested by another thread's Ctrl-C (interrupt.h) reaches a run
    // as Interrupted: Python's name for it.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Interrupted&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        }
    });
    m.def("simulate_main", [](const std::vector<std::string>& args) {
        return run_interruptible([&] { return simulate_main(args); });
    }, py::arg("args"),
          "Runs `simulate ARGS...` exactly as the program does; returns its exit code "
          "(0 done, 2 bad input, 3 other). Ctrl-C raises KeyboardInterrupt.");

    bind_cost(m);
    bind_run(m);
    bind_method(m);
    bind_scene(m);
    bind_calibrate(m);
    bind_break_even(m);
}
