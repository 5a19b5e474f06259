// report.json's "provenance": what produced a run, so a result can be
// reproduced and compared: the rtcsim version and git commit, the effective
// config with every default filled in, the contents of every preset used, the
// threads, the date (UTC) and the command line. Everything that changes from
// one identical run to the next (date, threads, command line) is inside this
// object (and the report's wall_seconds), so comparisons drop these two keys.
#pragma once

#include "sim/run/simulation.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

// `threads` as requested (0: all cores); `command_line` empty when the run
// did not come from the command line (the Python module).
[[nodiscard]] nlohmann::ordered_json provenance_json(const RunResult& run, unsigned threads,
                                                     const std::vector<std::string>& command_line);

// The current time, UTC, ISO 8601 ("2026-11-22T17:36:15Z").
[[nodiscard]] std::string utc_now_iso8601();

}  // namespace rtc
