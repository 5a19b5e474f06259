#include "sim/app/cli.h"

#include "core/input_error.h"
#include "sim/methods/method.h"

#include <CLI/CLI.hpp>

#include <algorithm>

#include <charconv>
#include <cmath>

namespace rtc {

namespace {

// The registered methods (sim/methods/registry.cpp), one line each.
std::string methods_help() {
    std::string s = "methods (config key \"methods\"; speedups are against \"baseline\", default ref):\n";
    for (const MethodEntry& m : registered_methods()) {
        std::string name = "  " + m.info.name;
        name.resize(std::max<std::size_t>(name.size() + 1, 16), ' ');
        s += name + m.info.summary + "\n";
    }
    return s;
}

}  // namespace

std::string cli_help() {
    return R"(simulate - an RT-core simulator with a cost model (rtcsim)

Traces a workload through simulated ray-tracing hardware with two ways of
handling long, thin primitives (Wald et al. 2020): `ref` (custom-primitive
AABBs, one context switch per box hit) and `obb` (one instance per primitive
masquerading its OBB), counts every hardware event, prices the counts with a
cost preset and reports cycles, speedups, memory, heat maps and plots.

usage:
  simulate CONFIG.json [options]            run a config (or each point of its sweep)
  simulate calibrate CONFIG.json [options]  fit cost parameters to target speedups
  simulate CONFIG.json --shard I/N [options]  run shard I of N (docs/scale-out.md)
  simulate merge DIR... [--out OUT]         merge the N shards' directories into
                                            the outputs of a single run
  simulate CONFIG.json --estimate [--shards N]  each shard's rays and memory, one
                                            JSON line per shard, no run
  simulate --help | --version

options (--opt value or --opt=value):
  --out DIR             output directory (default: out/<config name>/); it must be
                        missing or empty, see --force
  --data DIR            the data root that "data:..." paths in configs name
                        (default: $RTCSIM_DATA, else the repository's data/,
                        filled by scripts/fetch-data; docs/data.md)
  --threads N           worker threads (default and 0: all cores; results do not depend on it)
  --set key.path=value  override any config key by its path, e.g.
                        --set workload.spp=1 --set scene.tilt_deg=30
                        --set 'methods=["obb"]'  (value parsed as JSON, else a string);
                        a list's element by its index: --set sweep.scene.0.radius=1e-5;
                        paths set this way are relative to the config file, like
                        every path in it
  --quiet, -q           no progress bars or notes on stderr
  --show-config         print the effective configuration (overrides and defaults
                        applied) before running; it is always in report.json
  --max-rays N          refuse runs estimated to trace more than N rays in all
                        (every method and sweep point; default 1e10)
  --max-memory SIZE     refuse runs estimated to need more memory, e.g. 8G or
                        512M (default: 3/4 of physical memory)
  --max-break-even N    refuse break-even maps of more than N cell prices in all
                        (cells x cost models x methods, every map and point;
                        default 2e8, about 40 s)
  --force               go on anyway: run above those ceilings (and sweeps above
                        10,000 points), empty an output directory an earlier run
                        of simulate wrote, let calibrate overwrite its `output`
  --shard I/N           run only shard I (0 .. N-1) of N: sweep points round robin,
                        or bands of a frame's rows when there are fewer points
                        than shards; writes frames/ and shard.json into --out
  --estimate            print each shard's estimated work and exit (with --shards N)
  --sample F            trace a stratified sample of about F of the warp tiles (F = 1/k,
                        e.g. 0.0625) and scale the totals; every total and speedup gets
                        a 95 % sampling interval (sets sampling.fraction; docs/sampling.md)
  --sample-seed S       which tiles are sampled (sets sampling.seed; default 1)
  --estimate --target-error E
                        trace a pilot sample (--sample, default 1/64) of every sweep point
                        and suggest the fraction whose sampling intervals on every speedup
                        are within +/-E (relative, e.g. 0.02); one JSON line per point, then
                        the suggestion

paths and presets:
  Every path in a config is relative to that config file, except "data:..."
  paths, which are relative to the data root (--data). Presets are named by
  name ("cost": ["turing-calibrated"], "memory": "memory-optix7") and found in
  $RTCSIM_PRESET_DIR, else <bin>/../share/rtcsim/hw (installed), else the
  install prefix's share/rtcsim/hw, else the source tree's configs/hw; or by
  a path (with a '/' or ending in .json). A config without "cost" is priced
  under turing-calibrated, the preset fitted to the paper (the best evidence
  there is). Details: configs/README.md.

memory:
  RTCSIM_HUGE_PAGES=auto|on|off (default auto): huge pages for arrays of 4 MB
  or more. auto times faulting fresh memory both ways once and takes huge
  pages where they are clearly faster; report.json's provenance says what it
  chose. Speed only: counts and reports do not depend on it.

examples (from the source tree; installed configs are in <prefix>/share/rtcsim/runs):
  simulate configs/runs/quickstart.json
  simulate configs/runs/quickstart.json --out=out/quick-1spp --set workload.spp=1 --threads=2
  simulate configs/runs/fig3_bundles.json --set workload.width=200 --set workload.height=200
  simulate calibrate configs/runs/fig3_bundles.json --out out/fig3-fit
  simulate configs/runs/quickstart.json --shard 0/2 --out out/quick-s0 --set workload.spp=1
  simulate configs/runs/quickstart.json --shard 1/2 --out out/quick-s1 --set workload.spp=1
  simulate merge out/quick-s0 out/quick-s1 --out out/quick-merged

configs: configs/runs/*.json, keys documented in configs/README.md
outputs: report.json (with provenance: version, commit, effective config,
         presets, threads, date, command line), summary.csv, summary.md,
         *.png heat maps, *.svg plots

)" + methods_help();
}

namespace {

// CLI11 (2.1) takes the next argument as an option's value even when it is
// another option (`--out --quiet` would write into ./--quiet): refuse values
// that start with "--" or are one of our short flags.
void require_value(const std::string& value, const char* option) {
    if (value.rfind("--", 0) == 0 || value == "-q" || value == "-h")
        throw InputError(std::string("simulate: ") + option + " needs a value (got the option " + value +
                         "; see --help)");
}

// CLI11's messages, reworded to name the option in the program's style.
[[noreturn]] void rethrow(const CLI::ParseError& e) {
    std::string what = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr) {
        const auto colon = what.rfind(": ");
        const std::string extra = colon == std::string::npos ? what : what.substr(colon + 2);
        if (!extra.empty() && extra[0] == '-') throw InputError("simulate: unknown option " + extra + " (see --help)");
        throw InputError("simulate: unexpected argument " + extra + " (see --help)");
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&e) != nullptr) {
        const auto colon = what.find(':');
        throw InputError("simulate: " + what.substr(0, colon) + " needs a value (see --help)");
    }
    throw InputError("simulate: " + what + " (see --help)");
}

}  // namespace

CliOptions parse_cli(const std::vector<std::string>& args) {
    CliOptions o;
    o.command_line.push_back("simulate");
    o.command_line.insert(o.command_line.end(), args.begin(), args.end());
    CLI::App app{"simulate"};
    app.set_help_flag();  // cli_help() is the help text
    std::string out, data, threads, max_rays, max_memory, max_break_even, shard, shards, sample, sample_seed,
        target_error;
    std::vector<std::string> positional;
    app.add_flag("-h,--help", o.help);
    app.add_flag("--version", o.version);
    app.add_flag("-q,--quiet", o.quiet);
    app.add_flag("--show-config", o.show_config);
    app.add_flag("--force", o.limits.force);
    app.add_flag("--estimate", o.estimate);
    // Given twice, the last value wins (as with --set, later overrides earlier).
    for (const auto& [name, value] : {std::pair{"--out", &out}, {"--data", &data}, {"--threads", &threads},
                                      {"--max-rays", &max_rays}, {"--max-memory", &max_memory},
                                      {"--max-break-even", &max_break_even}, {"--shard", &shard}, {"--shards", &shards},
                                      {"--sample", &sample}, {"--sample-seed", &sample_seed},
                                      {"--target-error", &target_error}})
        app.add_option(name, *value)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    // One value per --set (a vector option would swallow the config name).
    app.add_option("--set", o.sets)
        ->expected(1)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false);
    app.add_option("args", positional);  // [calibrate] CONFIG.json
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 pops from the back
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        rethrow(e);
    }
    const auto given = [&](const char* name) { return app.count(name) > 0; };
    if (given("--out")) {
        require_value(out, "--out");
        if (out.empty()) throw InputError("simulate: --out needs a value (see --help)");
        o.out = out;
    }
    if (given("--data")) {
        require_value(data, "--data");
        if (data.empty()) throw InputError("simulate: --data needs a value (see --help)");
        o.data = data;
    }
    for (const std::string& s : o.sets) require_value(s, "--set");
    if (given("--threads")) {
        require_value(threads, "--threads");
        unsigned n = 0;
        const auto [p, ec] = std::from_chars(threads.data(), threads.data() + threads.size(), n);
        if (ec != std::errc() || p != threads.data() + threads.size() || n > 1024)
            throw InputError("simulate: --threads: expected 0 (all cores) or a positive integer up to 1024, got \"" +
                             threads + "\"");
        o.threads = n;
    }
    const auto count_option = [&](const char* name, const std::string& text) {
        require_value(text, name);
        double n = 0.0;
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (ec != std::errc() || p != text.data() + text.size() || !(n >= 1.0) || !std::isfinite(n))
            throw InputError(std::string("simulate: ") + name + ": expected a number >= 1 such as 1e9, got \"" + text +
                             "\"");
        return n;
    };
    if (given("--max-rays")) o.limits.max_rays = count_option("--max-rays", max_rays);
    if (given("--max-break-even")) o.limits.max_break_even = count_option("--max-break-even", max_break_even);
    if (given("--max-memory")) {
        require_value(max_memory, "--max-memory");
        const std::optional<double> n = parse_byte_size(max_memory);
        if (!n) throw InputError("simulate: --max-memory: expected a size such as 8G or 512M, got \"" + max_memory + "\"");
        o.limits.max_memory = *n;
    }
    if (given("--shard")) {
        require_value(shard, "--shard");
        o.shard = parse_shard_spec(shard, "simulate: --shard");
    }
    if (given("--shards")) {
        require_value(shards, "--shards");
        if (!o.estimate) throw InputError("simulate: --shards goes with --estimate (a run takes --shard I/N)");
        o.estimate_shards = parse_shard_spec("0/" + shards, "simulate: --shards").count;
    }
    if (given("--sample")) {
        require_value(sample, "--sample");
        double f = 0.0;
        const auto [p, ec] = std::from_chars(sample.data(), sample.data() + sample.size(), f);
        if (ec != std::errc() || p != sample.data() + sample.size() || !(f > 0.0 && f <= 1.0))
            throw InputError("simulate: --sample: expected a fraction in (0, 1] such as 0.0625, got \"" + sample + "\"");
        o.sets.push_back("sampling.fraction=" + sample);
    }
    if (given("--sample-seed")) {
        require_value(sample_seed, "--sample-seed");
        std::uint64_t seed = 0;
        const auto [p, ec] = std::from_chars(sample_seed.data(), sample_seed.data() + sample_seed.size(), seed);
        if (ec != std::errc() || p != sample_seed.data() + sample_seed.size() || seed > (1ull << 53))
            throw InputError("simulate: --sample-seed: expected an integer from 0 to 2^53, got \"" + sample_seed + "\"");
        o.sets.push_back("sampling.seed=" + sample_seed);
    }
    if (given("--target-error")) {
        require_value(target_error, "--target-error");
        double e = 0.0;
        const auto [p, ec] = std::from_chars(target_error.data(), target_error.data() + target_error.size(), e);
        if (ec != std::errc() || p != target_error.data() + target_error.size() || !(e > 0.0 && e < 1.0))
            throw InputError("simulate: --target-error: expected a relative error in (0, 1) such as 0.02, got \"" +
                             target_error + "\"");
        if (!o.estimate) throw InputError("simulate: --target-error goes with --estimate");
        o.target_error = e;
    }
    if (!positional.empty() && positional.front() == "merge") {
        o.merge = true;
        o.merge_dirs.assign(positional.begin() + 1, positional.end());
        if (o.merge_dirs.empty())
            throw InputError("simulate: merge needs the shards' directories (simulate merge DIR... --out OUT)");
        if (o.shard || o.estimate || !o.sets.empty())
            throw InputError("simulate: merge takes no --shard, --estimate or --set (the shards carry their config)");
        return o;
    }
    if (!positional.empty() && positional.front() == "calibrate") {
        o.calibrate = true;
        positional.erase(positional.begin());
    }
    if (positional.size() > 1)
        throw InputError("simulate: more than one config given (" + positional[0] + ", " + positional[1] + ")");
    if (!positional.empty()) o.config = positional.front();
    if (!o.help && !o.version && o.config.empty())
        throw InputError("simulate: no config given (usage: simulate CONFIG.json [options]; see --help)");
    return o;
}

}  // namespace rtc
