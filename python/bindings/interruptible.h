// Long C++ work from Python that Ctrl-C stops. Python only runs its SIGINT
// handler (which raises KeyboardInterrupt) when the main thread returns to
// the interpreter, so a run that holds the main thread in C++ for minutes
// ignored Ctrl-C. Here the work runs on its own thread while the calling
// thread waits with the GIL released and, every 50 ms, takes the GIL and
// asks the interpreter for pending signals (PyErr_CheckSignals). When a
// handler raised, the run is asked to stop (sim/execution/interrupt.h: it polls
// between image rows, methods and sweep points), joined, and the handler's
// exception (KeyboardInterrupt) propagates. What the work wrote is what an
// interrupted CLI run leaves: report.json is written last, never by an
// interrupted run.
#pragma once

#include "sim/execution/interrupt.h"

#include <pybind11/pybind11.h>

#include <chrono>
#include <future>
#include <thread>
#include <utility>

namespace rtc::py_bind {

// Calls work() (which must not touch Python objects) and returns its result;
// work's exceptions are rethrown here. Called with the GIL held.
template <class F>
auto run_interruptible(F&& work) -> decltype(work()) {
    namespace py = pybind11;
    using Result = decltype(work());
    std::packaged_task<Result()> task(std::forward<F>(work));
    std::future<Result> done = task.get_future();
    std::thread worker(std::move(task));
    // Joined on every way out, with the GIL released (the work may be
    // finishing a row).
    struct Join {
        std::thread& t;
        ~Join() {
            py::gil_scoped_release release;
            t.join();
        }
    } join{worker};
    for (;;) {
        {
            py::gil_scoped_release release;
            if (done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready) break;
        }
        if (PyErr_CheckSignals() != 0) {
            request_interrupt();
            {
                py::gil_scoped_release release;
                done.wait();  // unwinds at its next check; its Interrupted is dropped
            }
            clear_interrupt();
            throw py::error_already_set();  // the handler's exception, set by PyErr_CheckSignals
        }
    }
    return done.get();
}

}  // namespace rtc::py_bind
