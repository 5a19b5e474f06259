// Command-line parsing for `simulate` (kept apart from main so it is tested).
#pragma once

#include "sim/config/work_estimate.h"
#include "sim/shard/shard_plan.h"

#include <optional>
#include <string>
#include <vector>

namespace rtc {

struct CliOptions {
    bool help = false;
    bool version = false;
    bool calibrate = false;          // `simulate calibrate CONFIG.json`
    std::string config;
    std::optional<std::string> out;  // default out/<config name>/
    std::optional<std::string> data; // --data DIR: the data root ("data:" paths, sim/util/paths.h)
    unsigned threads = 0;            // 0: all cores
    std::vector<std::string> sets;   // key.path=value overrides, in order
    bool quiet = false;
    bool show_config = false;        // --show-config: echo the effective config first
    WorkLimits limits;               // --max-rays, --max-memory, --force
    // --force also empties an output directory an earlier run wrote and lets
    // calibrate overwrite an existing preset file: one flag for "I know, go on".
    std::vector<std::string> command_line;  // "simulate" and the arguments (provenance)
    // Scale-out (docs/scale-out.md):
    std::optional<ShardSpec> shard;          // --shard I/N
    bool merge = false;                      // `simulate merge DIR...`
    std::vector<std::string> merge_dirs;
    bool estimate = false;                   // --estimate: per-shard work, no run
    std::uint32_t estimate_shards = 1;       // --shards N (with --estimate)
    // Sampled simulation (docs/sampling.md): --sample F and --sample-seed S
    // are added to `sets` as sampling.fraction and sampling.seed (after the
    // --set overrides: they win); --estimate --target-error E suggests a
    // fraction from a pilot sample.
    std::optional<double> target_error;
};

// Throws InputError with a one-line message on bad arguments.
[[nodiscard]] CliOptions parse_cli(const std::vector<std::string>& args);

[[nodiscard]] std::string cli_help();

}  // namespace rtc
