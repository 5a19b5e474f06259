// Scale-out without a scheduler of our own (docs/scale-out.md):
//   simulate CONFIG --shard I/N --out DIR    run shard I's units (sim/shard)
//   simulate merge DIR... --out OUT          the single run's outputs
//   simulate CONFIG --estimate [--shards N]  each shard's work, one JSON line each
#pragma once

#include "sim/app/cli.h"

namespace rtc {

// Each returns the process exit code; bad input throws InputError.
int run_shard(const CliOptions& cli);
int run_merge(const CliOptions& cli);
int print_shard_estimates(const CliOptions& cli);

}  // namespace rtc
