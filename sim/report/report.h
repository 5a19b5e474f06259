// What a run tells its reader: report.json (everything), one summary row per
// run / sweep point (summary.csv, summary.md, the terminal table), heat maps
// and the render (PNG), and plots over a sweep's numeric axes (SVG).
#pragma once

#include "sim/plot/break_even.h"
#include "sim/run/simulation.h"
#include "sim/util/table.h"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace rtc {

// `break_even`: the run's break_even_json when already computed (a map's
// grid costs as much as its cells x draws; compute it once per run), else
// it is computed here.
[[nodiscard]] nlohmann::ordered_json report_json(const RunResult& run,
                                                 const nlohmann::ordered_json* break_even = nullptr);

// Per cost preset of a camera run, the note when the run's pixel count is
// more than 4x off the one the preset was fitted on (resolution_note):
// {preset name, note}, only presets with a note. report.json's
// resolution_notes and simulate's stderr notes.
[[nodiscard]] std::vector<std::pair<std::string, std::string>> resolution_notes(const RunResult& run);

// Summary table over runs (one row each): the columns shared by the CSV, the
// Markdown file and the terminal table.
[[nodiscard]] Table summary_table(const std::vector<RunResult>& runs);

// Speedup of every method over the baseline under every cost preset, one row
// per run and method (speedups.csv, speedups.md).
[[nodiscard]] Table speedup_table(const std::vector<RunResult>& runs);

// results.csv: one row per run (sweep point) x method x cost preset, raw
// numbers (empty where n/a, with a reason), one column per sweep value (an
// object value gives one column per inner key: "scene.count", "scene.radius").
[[nodiscard]] std::string results_csv(const std::vector<RunResult>& runs);
// The sweep-value columns of results.csv, in first-seen order.
[[nodiscard]] std::vector<std::string> sweep_columns(const std::vector<RunResult>& runs);

// A sweep's report.json: its axes and its points (index, label, values, the
// point's directory relative to the sweep's, and the point's report_json).
// `break_even`: each run's break_even_json, computed once (report_json).
[[nodiscard]] nlohmann::ordered_json sweep_report_json(const std::vector<RunResult>& runs,
                                                       const std::vector<std::string>& point_dirs,
                                                       const std::vector<nlohmann::ordered_json>* break_even = nullptr);

// Into `dir`: results.csv, summary.csv/.md, speedups.csv/.md, and when the
// runs are sweep points (non-empty point_dirs, relative to `dir`) the
// combined report.json.
void write_sweep_outputs(const std::vector<RunResult>& runs, const std::vector<std::string>& point_dirs,
                         const std::string& dir, const std::vector<nlohmann::ordered_json>* break_even = nullptr);

// Per method: counts_<method>.npy (H x W x E uint32 per pixel, or R x E per
// ray for ray lists) and cycles_<method>_<preset>.npy (H x W float64, or R
// for per-ray presets on ray lists), plus arrays.json (event names in order,
// shapes, totals). Call before the per-pixel data are freed. Returns the files.
std::vector<std::string> write_arrays(const RunResult& run, const std::string& dir);

// Render, per-method heat maps of cycles and IS calls per pixel on common
// scales, and the ref/obb ratio map, into `dir`, on `threads` threads (0: all
// cores). No-op for ray-file workloads.
void write_images(const RunResult& run, const std::string& dir, unsigned threads = 0);

// The config's break-even maps for this run (break_even_<name>.png and
// break_even_<name>.json in `dir`): per cell of two swept costs, the cheapest
// method, its margin and whether the draws leave it in doubt. Returns the
// files written.
std::vector<std::string> write_break_even_maps(const RunResult& run, const std::string& dir);
// Every map's grid of a run (break_even_grid per map of its config), computed
// once for the pictures and report.json; polls the stop request (Ctrl-C,
// SIGTERM) between rows of cells.
using BreakEvenGrids = std::vector<BreakEvenGrid>;
[[nodiscard]] BreakEvenGrids break_even_grids(const RunResult& run);
std::vector<std::string> write_break_even_maps(const RunResult& run, const BreakEvenGrids& grids,
                                               const std::string& dir);
// A method's cycles as a linear function of the costs, as the maps price
// it: given a warp preset (whose waves the run recorded), the effective
// counts of the method's waves at that preset's own costs (exact there,
// first order around it); given none, its event totals (the per-ray sum).
// On the SM of `roof` (the method's pipeline under the preset, MethodRun::roof).
[[nodiscard]] std::array<double, kEventCount> break_even_counts(const MethodRun& m, const CostModel* warp_preset,
                                                              const Roofline& roof);
// One map's cells (what write_break_even_maps draws): per cell the cheapest
// method, its lead, and the lead's 90 % band over the run's draws of the
// preset (uncertainty.draws, same seed as the speedup intervals), each draw
// with the axes set on it (a factor axis scales the draw's own cost).
[[nodiscard]] BreakEvenGrid break_even_grid(const RunResult& run, const BreakEvenSpec& spec);
// The cells as break_even_<name>.json (rounded to 4 digits), and report.json's
// "break_even": per map, each method's share of the cells, the share whose
// winner the draws leave in doubt, and the winner and lead interval at the mark.
[[nodiscard]] nlohmann::ordered_json break_even_cells_json(const BreakEvenGrid& g);
[[nodiscard]] nlohmann::ordered_json break_even_json(const RunResult& run);
[[nodiscard]] nlohmann::ordered_json break_even_json(const RunResult& run, const BreakEvenGrids& grids);

// For each numeric sweep axis: speedup of every non-ref method against it, one
// line per value of the other axes (e.g. speedup vs tilt, one line per N);
// speedup against memory overhead (speedup_vs_memory.svg, the Pareto view);
// speedup against the AABB/OBB area ratio. Returns the files written.
std::vector<std::string> write_sweep_plots(const std::vector<RunResult>& runs,
                                           const std::string& dir);

}  // namespace rtc
