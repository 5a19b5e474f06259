// libFuzzer harness: `simulate`'s command line (sim/app/cli.cpp). Each input
// line is one argument after "simulate" (at most 32): the options, --set
// specs, --shard I/N, --shards, limits, `merge DIR...`. The --set specs then
// go through apply_set on a small config and the sweep planning, and a shard
// spec through the unit plan of a run with 1-16 sweep points (the first
// byte picks how many), as simulate does before loading anything. Every line
// is also parsed as a shard spec on its own. fuzz_config covers --set lines
// over a config, this harness the parser in front of them.
#include "fuzz_common.h"
#include "sim/app/cli.h"
#include "sim/app/run_all.h"
#include "sim/config/sweep.h"
#include "sim/util/json_file.h"

#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> args;  // after the program name, as parse_cli takes them
    std::size_t at = 0;
    while (at < text.size() && args.size() < 32) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        args.push_back(text.substr(at, end - at));
        at = end + 1;
    }
    for (std::size_t i = 0; i < args.size(); ++i) {
        try {
            (void)rtc::parse_shard_spec(args[i], "--shard");
        } catch (const rtc::InputError&) {
        }
    }
    try {
        const rtc::CliOptions cli = rtc::parse_cli(args);
        if (cli.shard) {
            const std::size_t points = size > 0 ? 1 + data[0] % 16 : 1;
            (void)rtc::units_of_shard(points, *cli.shard);
        }
        nlohmann::json config = rtc::parse_json_text(rtc::fuzz::kTinyConfig, "base.json");
        for (const std::string& s : cli.sets) rtc::apply_set(config, s, "--set");
        rtc::WorkLimits limits = cli.limits;
        limits.max_rays = std::min(limits.max_rays, 1e6);
        if (!(limits.max_memory > 0.0 && limits.max_memory < 16.0 * 1024 * 1024))  // 0: the machine's
            limits.max_memory = 16.0 * 1024 * 1024;
        limits.max_sweep_points = std::min(limits.max_sweep_points, 16.0);
        limits.force = false;
        (void)rtc::plan_runs(config, "base.json", {}, limits);
    } catch (const rtc::InputError&) {
    }
    return 0;
}
