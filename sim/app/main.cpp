// `simulate`: the command-line front end; everything lives in the sim
// libraries (sim/app/simulate_main.cpp sequences it).
#include "sim/app/simulate_main.h"
#include "sim/execution/interrupt.h"
#include "sim/util/process_memory.h"

#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

static_assert(SIGINT == rtc::kSigInt && SIGTERM == rtc::kSigTerm, "interrupt.h numbers the signals as POSIX does");

namespace {

// The first Ctrl-C or SIGTERM (Slurm's at a time limit) asks the run to
// stop at its next check (an image row, a method, a sweep point) and
// unwind, so temporaries are removed; the handler then resets itself, so a
// second signal (during a long build, which is not checked inside) kills at
// once. Either way the output directory's mark still says running, and
// readers refuse it; the exit code is 128 + the signal.
void on_interrupt(int signal) {
    rtc::request_interrupt(signal);
    constexpr char kInt[] = "\nsimulate: stopping at the next check (Ctrl-C again to kill)\n";
    constexpr char kTerm[] = "\nsimulate: SIGTERM: stopping at the next check\n";
    if (signal == SIGTERM)
        (void)!write(STDERR_FILENO, kTerm, sizeof kTerm - 1);
    else
        (void)!write(STDERR_FILENO, kInt, sizeof kInt - 1);
}

}  // namespace

int main(int argc, char** argv) {
    rtc::keep_freed_memory();
    // Past a file-size limit (ulimit -f) a write fails with EFBIG, which the
    // output writers report naming the file (exit 2), instead of the signal
    // killing the run.
    std::signal(SIGXFSZ, SIG_IGN);
    struct sigaction interrupt = {};
    interrupt.sa_handler = on_interrupt;
    interrupt.sa_flags = SA_RESETHAND;
    sigemptyset(&interrupt.sa_mask);
    sigaction(SIGINT, &interrupt, nullptr);
    sigaction(SIGTERM, &interrupt, nullptr);
    if (!rtc::set_huge_pages_from_environment("simulate")) return 2;
    return rtc::simulate_main(std::vector<std::string>(argv + 1, argv + argc));
}
