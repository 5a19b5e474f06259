// What a run tells its reader: report.json (everything), one summary row per
// run / sweep point (summary.csv, summary.md, the terminal table), heat maps
// and the render (PNG), and plots over a sweep's numeric axes (SVG).
#pragma once

#include "sim/run/simulation.h"
#include "sim/util/table.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace rtc {

[[nodiscard]] nlohmann::ordered_json report_json(const RunResult& run);

// Summary table over runs (one row each): the columns shared by the CSV, the
// Markdown file and the terminal table.
[[nodiscard]] Table summary_table(const std::vector<RunResult>& runs);

// Speedup of every method over the baseline under every cost preset, one row
// per run and method (speedups.csv, speedups.md).
[[nodiscard]] Table speedup_table(const std::vector<RunResult>& runs);

// Render, per-method heat maps of cycles and IS calls per pixel on common
// scales, and the ref/obb ratio map, into `dir`. No-op for ray-file workloads.
void write_images(const RunResult& run, const std::string& dir);

// The config's break-even maps for this run (break_even_<name>.png in `dir`):
// per cell of two swept costs, the cheapest method and its margin. Returns
// the files written.
std::vector<std::string> write_break_even_maps(const RunResult& run, const std::string& dir);

// For each numeric sweep axis: speedup of every non-ref method against it, one
// line per value of the other axes (e.g. speedup vs tilt, one line per N);
// speedup against memory overhead (speedup_vs_memory.svg, the Pareto view);
// speedup against the AABB/OBB area ratio. Returns the files written.
std::vector<std::string> write_sweep_plots(const std::vector<RunResult>& runs,
                                           const std::string& dir);

}  // namespace rtc
