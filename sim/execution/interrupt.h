// Stopping a run early (Ctrl-C, or SIGTERM: what Slurm sends at a time
// limit). A signal is delivered to the process, not to a run, so the request
// is one process-wide value, the signal's number: the CLI's SIGINT and
// SIGTERM handler sets it (async-signal-safe: a lock-free atomic store), and so does
// the Python module when the interpreter has a pending KeyboardInterrupt.
// Long phases poll it where stopping is cheap (between image rows or tiles,
// between methods, between sweep points) and throw Interrupted, which unwinds
// through the output writers: temporaries are removed and the output
// directory's mark keeps saying `state: running` (sim/app/output_dir.h), so
// nothing finished-looking is left behind; a request that comes after the
// last check still keeps the mark from saying complete (OutputDir::finish),
// so the exit code (128 + the signal) and the mark agree.
#pragma once

#include <atomic>
#include <stdexcept>

namespace rtc {

// Thrown by throw_if_interrupted(); not an InputError (exit 130, not 2).
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted") {}
};

// The request (0: none, else the signal): lock-free, so a signal handler
// may store to it. One per program (an inline variable), shared by its libraries.
inline std::atomic<int> g_interrupt_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

inline constexpr int kSigInt = 2, kSigTerm = 15;  // POSIX numbers, without <csignal> here

// Asks every running run to stop at its next check. Async-signal-safe.
inline void request_interrupt(int signal = kSigInt) noexcept {
    g_interrupt_signal.store(signal, std::memory_order_relaxed);
}
// Forgets a request (after the interrupted run has unwound).
inline void clear_interrupt() noexcept { g_interrupt_signal.store(0, std::memory_order_relaxed); }
[[nodiscard]] inline bool interrupt_requested() noexcept {
    return g_interrupt_signal.load(std::memory_order_relaxed) != 0;
}
// Throws Interrupted when a stop was requested. Cheap: one relaxed load.
inline void throw_if_interrupted() {
    if (interrupt_requested()) throw Interrupted();
}

// The exit status of a program stopped by a signal: 128 + its number, as a
// shell reports a process killed by it (130 for Ctrl-C, 143 for SIGTERM).
[[nodiscard]] inline int interrupted_exit_code() noexcept {
    const int signal = g_interrupt_signal.load(std::memory_order_relaxed);
    return 128 + (signal > 0 ? signal : kSigInt);
}

}  // namespace rtc
