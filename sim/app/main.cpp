// `simulate`: the command-line front end; everything lives in the sim
// libraries (sim/app/simulate_main.cpp sequences it).
#include "sim/app/simulate_main.h"
#include "sim/util/process_memory.h"

#include <csignal>
#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
    rtc::keep_freed_memory();
    // Past a file-size limit (ulimit -f) a write fails with EFBIG, which the
    // output writers report naming the file (exit 2), instead of the signal
    // killing the run.
    std::signal(SIGXFSZ, SIG_IGN);
    if (!rtc::set_huge_pages_from_environment("simulate")) return 2;
    return rtc::simulate_main(std::vector<std::string>(argv + 1, argv + argc));
}
