// Shared pieces of the pybind11 module: NumPy views onto C++ vectors (no
// copy: the array keeps the vector's owner alive), the run and scene handles,
// and the bind_* functions of each file.
//
// The C++ side speaks JSON text for configs and reports; the Python package
// (python/rtcsim) turns it into dicts, so every field report_json writes,
// now or later, reaches Python without a binding of its own.
#pragma once

#include "core/input_error.h"
#include "sim/run/simulation.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

namespace rtc::py_bind {

namespace py = pybind11;

// A capsule that owns a copy of `owner`: the base of arrays viewing its data.
template <class T>
py::capsule keep_alive(std::shared_ptr<T> owner) {
    return py::capsule(new std::shared_ptr<T>(std::move(owner)),
                       [](void* p) { delete static_cast<std::shared_ptr<T>*>(p); });
}

// A read-only view of `count` records of `Scalar`s with `shape` (leading
// dimensions first), living as long as `base`.
template <class Scalar>
py::array view(const void* data, std::vector<py::ssize_t> shape, const py::handle& base) {
    py::array a(py::dtype::of<Scalar>(), std::move(shape), {}, static_cast<const Scalar*>(data), base);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

// A read-only view of records of a structured NumPy dtype (fields: name,
// format such as "<f4" or ("<f4", 3), byte offset).
struct Field {
    const char* name;
    py::object format;
    std::size_t offset;
};
py::array record_view(const void* data, std::size_t count, std::size_t itemsize,
                      const std::vector<Field>& fields, const py::handle& base);

// One traced run, shared by its Python object, its methods' objects and
// every array viewing it.
struct RunHandle {
    std::shared_ptr<RunResult> run;
};

// One method of a run (index into run->methods).
struct MethodHandle {
    std::shared_ptr<RunResult> run;
    std::size_t index = 0;
    [[nodiscard]] MethodRun& method() const { return run->methods.at(index); }
};

void bind_cost(py::module_& m);
void bind_run(py::module_& m);
void bind_method(py::module_& m);
void bind_scene(py::module_& m);
void bind_calibrate(py::module_& m);
void bind_break_even(py::module_& m);

}  // namespace rtc::py_bind
