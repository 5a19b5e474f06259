// Stopping a run early (Ctrl-C). A signal is delivered to the process, not
// to a run, so the request is one process-wide flag: the CLI's SIGINT
// handler sets it (async-signal-safe: a lock-free atomic store), and so does
// the Python module when the interpreter has a pending KeyboardInterrupt.
// Long phases poll it where stopping is cheap (between image rows or tiles,
// between methods, between sweep points) and throw Interrupted, which unwinds
// through the output writers: temporaries are removed and the output
// directory's mark keeps saying `state: running` (sim/app/output_dir.h), so
// nothing finished-looking is left behind.
#pragma once

#include <atomic>
#include <stdexcept>

namespace rtc {

// Thrown by throw_if_interrupted(); not an InputError (exit 130, not 2).
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted") {}
};

// The request: lock-free, so a signal handler may store to it. One per
// program (an inline variable), shared by its libraries.
inline std::atomic<bool> g_interrupt_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// Asks every running run to stop at its next check. Async-signal-safe.
inline void request_interrupt() noexcept { g_interrupt_requested.store(true, std::memory_order_relaxed); }
// Forgets a request (after the interrupted run has unwound).
inline void clear_interrupt() noexcept { g_interrupt_requested.store(false, std::memory_order_relaxed); }
[[nodiscard]] inline bool interrupt_requested() noexcept {
    return g_interrupt_requested.load(std::memory_order_relaxed);
}
// Throws Interrupted when a stop was requested. Cheap: one relaxed load.
inline void throw_if_interrupted() {
    if (interrupt_requested()) throw Interrupted();
}

// The exit status of a program stopped by Ctrl-C (128 + SIGINT, as a shell
// reports a process killed by it).
inline constexpr int kInterruptedExitCode = 130;

}  // namespace rtc
