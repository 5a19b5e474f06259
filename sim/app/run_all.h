// Runs a config from the command line: overrides, sweep expansion, each point
// through run_simulation, then the reports, pictures and summary tables.
#pragma once

#include "sim/app/cli.h"

namespace rtc {

// Returns the process exit code. Throws InputError on bad input.
int run_all(const CliOptions& cli);

}  // namespace rtc
