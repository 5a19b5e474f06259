#include "sim/app/cli.h"

#include "core/input_error.h"
#include "sim/methods/method.h"

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
  simulate --help | --version

options:
  --out DIR             output directory (default: out/<config name>/)
  --threads N           worker threads (default: all cores; results do not depend on it)
  --set key.path=value  override any config key by its path, e.g.
                        --set workload.spp=1 --set scene.tilt_deg=30
                        --set 'methods=["obb"]'  (value parsed as JSON, else a string)
  --quiet               no effective-config echo, no progress bars
  --max-rays N          refuse runs estimated to trace more than N rays in all
                        (every method and sweep point; default 1e10)
  --max-memory SIZE     refuse runs estimated to need more memory, e.g. 8G or
                        512M (default: 3/4 of physical memory)
  --force               run even above those ceilings (and sweeps above 10,000 points)

configs: configs/runs/*.json, keys documented in configs/README.md
outputs: report.json, summary.csv, summary.md, *.png heat maps, *.svg plots
)" + methods_help();
}

CliOptions parse_cli(const std::vector<std::string>& args) {
    CliOptions o;
    const auto value = [&](std::size_t& i, const std::string& flag) -> const std::string& {
        if (i + 1 >= args.size()) throw InputError("simulate: " + flag + " needs a value (see --help)");
        return args[++i];
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--help" || a == "-h") {
            o.help = true;
        } else if (a == "--version") {
            o.version = true;
        } else if (a == "--quiet" || a == "-q") {
            o.quiet = true;
        } else if (a == "--out") {
            o.out = value(i, a);
        } else if (a == "--threads") {
            const std::string& v = value(i, a);
            unsigned n = 0;
            const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
            if (ec != std::errc() || p != v.data() + v.size() || n == 0 || n > 1024)
                throw InputError("simulate: --threads: expected a positive integer, got \"" + v + "\"");
            o.threads = n;
        } else if (a == "--max-rays") {
            const std::string& v = value(i, a);
            double n = 0.0;
            const auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
            if (ec != std::errc() || p != v.data() + v.size() || !(n >= 1.0) || !std::isfinite(n))
                throw InputError("simulate: --max-rays: expected a number >= 1 such as 1e9, got \"" + v + "\"");
            o.limits.max_rays = n;
        } else if (a == "--max-memory") {
            const std::string& v = value(i, a);
            const std::optional<double> n = parse_byte_size(v);
            if (!n) throw InputError("simulate: --max-memory: expected a size such as 8G or 512M, got \"" + v + "\"");
            o.limits.max_memory = *n;
        } else if (a == "--force") {
            o.limits.force = true;
        } else if (a == "--set") {
            o.sets.push_back(value(i, a));
        } else if (a.rfind("--set=", 0) == 0) {
            o.sets.push_back(a.substr(6));
        } else if (a == "calibrate" && o.config.empty() && !o.calibrate) {
            o.calibrate = true;
        } else if (!a.empty() && a[0] == '-') {
            throw InputError("simulate: unknown option " + a + " (see --help)");
        } else if (o.config.empty()) {
            o.config = a;
        } else {
            throw InputError("simulate: more than one config given (" + o.config + ", " + a + ")");
        }
    }
    if (!o.help && !o.version && o.config.empty())
        throw InputError("simulate: no config given (usage: simulate CONFIG.json [options]; see --help)");
    return o;
}

}  // namespace rtc
