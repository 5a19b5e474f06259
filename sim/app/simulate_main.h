// The whole `simulate` program as a function, so tests (and tools that add
// their own methods with register_method) run exactly what the binary runs.
#pragma once

#include <string>
#include <vector>

namespace rtc {

// Runs `simulate ARGS...` (without the program name) and returns the exit
// code: 0 done, 2 bad input (one line on stderr naming file and key), 3 other,
// 130 stopped by an interrupt request (sim/execution/interrupt.h; Ctrl-C).
int simulate_main(const std::vector<std::string>& args);

}  // namespace rtc
