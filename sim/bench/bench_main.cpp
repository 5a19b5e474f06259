// `bench`: the simulator's performance benchmark (issue 8). Runs the standard
// cases (sim/bench_cases.cpp) through the code simulate uses and prints, per
// method: build time, rays per second on 1 thread and on all threads,
// intersection-program calls per ray and bytes per primitive of the
// simulator's own structures. docs/benchmark.md has the figures and how to
// rerun them.
#include "core/input_error.h"
#include "core/parallel.h"
#include "sim/bench/bench_compare.h"
#include "sim/bench/bench_run.h"
#include "sim/bench/embree_bench.h"
#include "sim/bench/embree_hair_bench.h"
#include "sim/methods/method.h"
#include "sim/util/paths.h"
#include "sim/util/process_memory.h"
#include "sim/util/version.h"

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>

namespace {

using namespace rtc;

constexpr const char* kHelp =
    "usage: bench [options]\n"
    "  --cases LIST   comma-separated case numbers (default 1,2,3,4,5)\n"
    "                 1: bundle N=1000 r=0.002 tilt 45   2: same, tilt 0\n"
    "                 3: bundle N=100000 r=0.0005 tilt 30 (obb)\n"
    "                 4: Sintel hair + head (capsules, phantom)   5: 2 M fur, path tracing\n"
    "  --scale        run only the scale case: 2^24 obb instances, peak memory (heavy)\n"
    "  --threads LIST thread counts to time, e.g. 1,2 (default: 1 and all cores); one\n"
    "                 number N > 1 times 1 and N; scaling is against the first count\n"
    "  --repeat K     best of K traces per figure (default 3)\n"
    "  --data DIR     the data root for case 4 (default: $RTCSIM_DATA, else the\n"
    "                 repository's data/, filled by scripts/fetch-data)\n"
    "  --json FILE    also write the figures as JSON (not with --embree or --warp-price)\n"
    "  --compare A.json B.json  print B / A ratios of two --json files (rates, builds)\n"
    "                 and whether their event totals are identical; traces nothing\n"
    "  --methods LIST only these methods (any registered name) where a case has them\n"
    "  --execution M  per_ray (default) or warp: trace in warps priced under\n"
    "                 --warp-preset (default turing-calibrated)\n"
    "  --warp-preset P the warp preset of --execution warp and --warp-price, by name or path\n"
    "  --pixels N     override every case's resolution with N x N (quick runs, profiling)\n"
    "  --embree       trace each case's rays through Embree 3 too (ref, obb; default cases\n"
    "                 1,2,3): rates side by side, timed alternately, their ratio, and a\n"
    "                 check of the hits (exit 1 if they differ; 77 if built without Embree)\n"
    "  --embree-hair CONFIG  Embree 3's oriented hair BVH against its axis-aligned BVH over\n"
    "                 the same capsules, on the rays of the simulator's ref frame of each\n"
    "                 scene of CONFIG (e.g. configs/runs/embree_hair.json): builds, memory,\n"
    "                 Embree's BVH statistics, rates and their ratio, beside ref's and\n"
    "                 obb-nodes' counted tests (with --json: the figures; 77 without Embree)\n"
    "  --warp-price   time per-ray and warp traces of each case's frame alternately (default\n"
    "                 cases 1,2; warp under --warp-preset): their rates and warp's time over\n"
    "                 per-ray's, pair by pair (exit 1 if their event counts differ)\n"
    "  --help         this text\n"
    "Options take --opt value or --opt=value.\n";

struct Cli {
    std::set<int> cases{1, 2, 3, 4, 5};
    bool scale = false;
    bool embree = false;  // --embree
    bool warp_price = false;  // --warp-price
    std::string embree_hair;  // --embree-hair CONFIG
    BenchOptions bench;
    std::string data = data_root().string();  // as simulate's "data:" paths
    std::string json_file;
    int pixels = 0;  // 0: each case's own resolution
    std::set<std::string> methods{"ref", "obb"};
    std::string compare_a, compare_b;  // --compare
};

std::vector<unsigned> parse_thread_list(const std::string& a, const std::string& v) {
    std::vector<unsigned> out;
    std::stringstream list(v);
    for (std::string item; std::getline(list, item, ',');) {
        std::size_t used = 0;
        int n = 0;
        try { n = std::stoi(item, &used); } catch (const std::exception&) { used = 0; }
        if (used != item.size() || item.empty() || n < 1)
            throw InputError("bench: " + a + ": expected thread counts >= 1 separated by commas, got \"" +
                             v + "\"");
        if (std::find(out.begin(), out.end(), static_cast<unsigned>(n)) == out.end())
            out.push_back(static_cast<unsigned>(n));
    }
    if (out.empty()) throw InputError("bench: " + a + ": empty list");
    if (out.size() == 1 && out[0] > 1) out.insert(out.begin(), 1u);  // as before: 1 and N
    return out;
}

// The options on CLI11 (as simulate's): `--opt value` and `--opt=value`,
// errors naming the option, exit 2.
Cli parse(int argc, char** argv) {
    Cli cli;
    CLI::App app{"bench"};
    app.set_help_flag();  // kHelp is the help text
    bool help = false, scale = false, embree = false, warp_price = false;
    std::string cases, threads, repeat, data, methods, execution, warp_preset = "turing-calibrated", pixels, json,
        embree_hair;
    std::vector<std::string> compare;
    app.add_flag("-h,--help", help);
    app.add_flag("--scale", scale);
    app.add_flag("--embree", embree);
    app.add_flag("--warp-price", warp_price);
    for (const auto& [name, value] :
         {std::pair{"--cases", &cases}, {"--threads", &threads}, {"--repeat", &repeat}, {"--data", &data},
          {"--methods", &methods}, {"--execution", &execution}, {"--warp-preset", &warp_preset},
          {"--pixels", &pixels}, {"--json", &json}, {"--embree-hair", &embree_hair}})
        app.add_option(name, *value)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--compare", compare)->expected(2);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        std::string what = e.what();
        if (dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr)
            throw InputError("bench: unknown option or argument: " + what.substr(what.rfind(": ") + 2) +
                             " (see --help)");
        throw InputError("bench: " + what + " (see --help)");
    }
    if (help) {
        std::cout << kHelp;
        std::exit(0);
    }
    const auto given = [&](const char* name) { return app.count(name) > 0; };
    // CLI11 takes the next argument as a value even when it is an option.
    const auto value = [&](const char* name, const std::string& v) -> const std::string& {
        if (v.rfind("--", 0) == 0 || v.empty())
            throw InputError(std::string("bench: ") + name + " needs a value (got \"" + v + "\"; see --help)");
        return v;
    };
    const auto number = [&](const char* name, const std::string& v, int lo) {
        std::size_t used = 0;
        int n = 0;
        try { n = std::stoi(value(name, v), &used); } catch (const std::exception&) { used = 0; }
        if (used != v.size() || n < lo)
            throw InputError(std::string("bench: ") + name + ": expected an integer >= " + std::to_string(lo) +
                             ", got \"" + v + "\"");
        return n;
    };
    const auto items = [](const std::string& list) {
        std::vector<std::string> out;
        std::stringstream in(list);
        for (std::string item; std::getline(in, item, ',');) out.push_back(item);
        return out;
    };
    cli.scale = scale;
    cli.embree = embree;
    cli.warp_price = warp_price;
    if (given("--embree-hair")) {
        cli.embree_hair = value("--embree-hair", embree_hair);
        if (embree || warp_price || scale || given("--cases") || given("--execution") || given("--methods"))
            throw InputError("bench: --embree-hair runs its config's scenes alone (drop --embree, --warp-price, "
                             "--scale, --cases, --execution and --methods)");
    }
    if (embree && !given("--cases")) cli.cases = {1, 2, 3};
    if (warp_price && !given("--cases")) cli.cases = {1, 2};
    if (given("--cases")) {
        cli.cases.clear();
        for (const std::string& item : items(value("--cases", cases))) {
            if (item.size() != 1 || item[0] < '1' || item[0] > '5')
                throw InputError("bench: --cases: unknown case \"" + item + "\" (1..5)");
            cli.cases.insert(item[0] - '0');
        }
    }
    if (given("--threads")) cli.bench.threads = parse_thread_list("--threads", value("--threads", threads));
    if (given("--compare")) {
        cli.compare_a = value("--compare", compare.at(0));
        cli.compare_b = value("--compare", compare.at(1));
    }
    if (given("--repeat")) cli.bench.repeat = number("--repeat", repeat, 1);
    if (given("--data")) cli.data = value("--data", data);
    if (given("--methods")) {
        cli.methods.clear();
        for (const std::string& item : items(value("--methods", methods))) {
            if (!find_method(item))
                throw InputError("bench: --methods: unknown method \"" + item + "\" (" + method_names_list() + ")");
            cli.methods.insert(item);
        }
    }
    if (given("--execution") && value("--execution", execution) != "per_ray" && execution != "warp")
        throw InputError("bench: --execution: expected per_ray or warp, got \"" + execution + "\"");
    if (given("--pixels")) cli.pixels = number("--pixels", pixels, 1);
    if (given("--json")) cli.json_file = value("--json", json);
    // Embree's side is per-ray work on the standard cases' scenes.
    if (embree && scale) throw InputError("bench: --embree traces the standard cases, not --scale");
    if (embree && execution == "warp")
        throw InputError("bench: --embree times per-ray execution (drop --execution warp)");
    if ((embree || warp_price) && given("--json"))
        throw InputError(std::string("bench: ") + (embree ? "--embree" : "--warp-price") +
                         " prints its figures only (drop --json)");
    if (warp_price && (embree || scale || given("--execution")))
        throw InputError("bench: --warp-price times both executions itself (drop --embree, --scale and --execution)");
    // A preset by name (searched like simulate's) or by path.
    if (execution == "warp" || warp_price)
        cli.bench.warp_preset = resolve_preset(value("--warp-preset", warp_preset), "bench", "--warp-preset");
    return cli;
}

void print_run(const RunFigures& r) {
    std::printf("  %s (%s): %llu primitives, %llu triangles, scene %.2f s\n", r.label.c_str(),
                r.kind.c_str(), static_cast<unsigned long long>(r.primitives),
                static_cast<unsigned long long>(r.triangles), r.load_seconds);
    std::printf("    %-6s %9s %10s", "method", "build s", "rays");
    if (!r.methods.empty())
        for (const ThreadRate& t : r.methods.front().rates)
            std::printf("  %2ut Mrays/s best/median scaling", t.threads);
    std::printf(" %10s %10s %9s\n", "IS/ray", "boxes/ray", "B/prim");
    for (const MethodFigures& m : r.methods) {
        std::printf("    %-6s %9.3f %10llu", m.method.c_str(), m.build_seconds,
                    static_cast<unsigned long long>(m.rays));
        for (const ThreadRate& t : m.rates) {
            const double base = m.rates.front().best_rays_per_second;
            std::printf("  %14.3f / %7.3f %6.2fx", t.best_rays_per_second * 1e-6,
                        t.median_rays_per_second * 1e-6,
                        base > 0.0 ? t.best_rays_per_second / base : 0.0);
        }
        std::printf(" %10.2f %10.2f %9.1f%s\n", m.is_calls_per_ray, m.box_tests_per_ray,
                    m.bytes_per_primitive, m.counts_match ? "" : "  COUNTS DIFFER BETWEEN RUNS");
    }
}

// The 1-minute load average (other processes compete for the cores).
double load_average() {
    double l[1] = {0.0};
    return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}

nlohmann::json to_json(const RunFigures& r) {
    nlohmann::json j = {{"label", r.label}, {"kind", r.kind}, {"primitives", r.primitives},
                        {"triangles", r.triangles}, {"load_seconds", r.load_seconds}};
    for (const MethodFigures& m : r.methods) {
        nlohmann::json rates = nlohmann::json::array();
        for (const ThreadRate& t : m.rates)
            rates.push_back({{"threads", t.threads},
                             {"best_rays_per_second", t.best_rays_per_second},
                             {"median_rays_per_second", t.median_rays_per_second},
                             {"best_seconds", t.best_seconds}});
        nlohmann::json events;
        for (std::size_t e = 0; e < kEventCount; ++e)
            events[std::string(kEventNames[e])] = m.totals.n[e];
        j["methods"].push_back({{"method", m.method},
                                {"build_seconds", m.build_seconds},
                                {"rays", m.rays},
                                {"rays_per_second_1_thread", m.rays_per_second_1t},
                                {"rays_per_second_all_threads", m.rays_per_second_nt},
                                {"threads", m.threads},
                                {"rates", rates},
                                {"is_calls_per_ray", m.is_calls_per_ray},
                                {"box_tests_per_ray", m.box_tests_per_ray},
                                {"bytes_per_primitive", m.bytes_per_primitive},
                                {"counts_match", m.counts_match},
                                {"events", events}});
    }
    return j;
}

// `--embree-hair CONFIG`: every scene of the config through both of Embree's
// hair BVHs (sim/bench/embree_hair_bench.h); exit 1 if their hits differ.
int run_embree_hair(const Cli& cli) {
    if (!embree_built()) {
        std::printf("bench: --embree-hair: this bench was built without Embree 3 (apt-get install "
                    "libembree-dev, then configure again)\n");
        return 77;
    }
    std::vector<BenchRun> runs = hair_runs_of_config(cli.embree_hair);
    std::string listed;
    for (const unsigned t : cli.bench.threads)
        listed += (listed.empty() ? "" : ",") + std::to_string(t ? t : hardware_threads());
    std::printf("bench --embree-hair %s: threads %s (%u cores), %d alternated pairs; load average %.2f\n",
                cli.embree_hair.c_str(), listed.c_str(), hardware_threads(), cli.bench.repeat, load_average());
    nlohmann::json scenes = nlohmann::json::array();
    bool ok = true;
    for (BenchRun& run : runs) {
        if (cli.pixels > 0) run.config["workload"]["width"] = run.config["workload"]["height"] = cli.pixels;
        ok = compare_hair_bvhs(run, cli.bench, scenes) && ok;
    }
    std::printf("  (load average %.2f)\n", load_average());
    if (!cli.json_file.empty()) {
        const nlohmann::json out = {{"config", cli.embree_hair}, {"repeat", cli.bench.repeat},
                                    {"git_commit", std::string(git_commit()) + (git_dirty() ? "+dirty" : "")},
                                    {"cores", hardware_threads()}, {"scenes", scenes}};
        std::ofstream f(cli.json_file);
        f << out.dump(2) << "\n";
        if (!f) throw InputError("bench: cannot write " + cli.json_file);
    }
    if (!ok) std::printf("bench: Embree's two hair BVHs disagree on the hits (HITS DIFFER above)\n");
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    keep_freed_memory();  // as simulate does: the figures are simulate's
    if (!set_huge_pages_from_environment("bench")) return 2;
    try {
        Cli cli = parse(argc, argv);
        if (!cli.compare_a.empty()) return compare_bench_json(cli.compare_a, cli.compare_b);
        if (!cli.embree_hair.empty()) return run_embree_hair(cli);
        if (cli.embree && !embree_built()) {
            std::printf("bench: --embree: this bench was built without Embree 3 (apt-get install "
                        "libembree-dev, then configure again)\n");
            return 77;  // ctest's SKIP_RETURN_CODE for the Embree test
        }
        bool hits_agree = true, counts_agree = true;
        std::vector<BenchCase> cases;
        if (cli.scale) {
            cases.push_back(scale_case());
            cli.bench.threads = {0};  // one all-threads trace is enough here
            cli.bench.repeat = 1;
        } else {
            for (BenchCase& c : standard_cases(cli.data))
                if (cli.cases.count(c.id)) cases.push_back(std::move(c));
        }
        nlohmann::json counts = nlohmann::json::array();
        unsigned threads = 1;
        std::string listed;
        for (const unsigned t : cli.bench.threads) {
            const unsigned n = t ? t : hardware_threads();
            counts.push_back(n);
            threads = std::max(threads, n);
            if (!listed.empty()) listed.push_back(',');
            listed.append(std::to_string(n));
        }
        std::printf("bench: threads %s (%u cores), best and median of %d traces; counting sinks on; "
                    "load average %.2f\n",
                    listed.c_str(), hardware_threads(), cli.bench.repeat, load_average());
        nlohmann::json out = {{"threads", threads}, {"thread_counts", counts},
                              {"cores", hardware_threads()}, {"repeat", cli.bench.repeat},
                              {"load_average_start", load_average()}};
        for (BenchCase& c : cases) {
            for (BenchRun& run : c.runs) {
                if (cli.pixels > 0)
                    run.config["workload"]["width"] = run.config["workload"]["height"] = cli.pixels;
                nlohmann::json kept = nlohmann::json::array();
                for (const auto& m : run.config["methods"])
                    if (cli.methods.count(m.get<std::string>())) kept.push_back(m);
                run.config["methods"] = kept;
            }
            std::printf("case %d: %s%s%s\n", c.id, c.title.c_str(), c.note.empty() ? "" : "\n  (",
                        c.note.empty() ? "" : (c.note + ")").c_str());
            nlohmann::json jc = {{"id", c.id}, {"title", c.title}, {"note", c.note}};
            if (!c.missing_data.empty()) {
                std::printf("  SKIPPED: %s\n", c.missing_data.c_str());
                jc["skipped"] = c.missing_data;
            }
            std::fflush(stdout);  // before the builds' progress lines on stderr
            for (const BenchRun& run : c.runs) {
                if (run.config["methods"].empty()) continue;  // filtered out by --methods
                if (cli.embree) {
                    hits_agree = compare_with_embree(run, cli.bench) && hits_agree;
                    continue;
                }
                if (cli.warp_price) {
                    counts_agree = compare_warp_price(run, cli.bench) && counts_agree;
                    continue;
                }
                const RunFigures r = run_bench(run, cli.bench);
                print_run(r);
                jc["runs"].push_back(to_json(r));
            }
            std::printf("  (load average %.2f)\n", load_average());
            std::fflush(stdout);
            jc["load_average_end"] = load_average();
            out["cases"].push_back(jc);
        }
        const double peak_mib = static_cast<double>(peak_rss_bytes()) / (1024.0 * 1024.0);
        std::printf("peak memory (ru_maxrss): %.1f MiB\n", peak_mib);
        std::printf("huge pages (RTCSIM_HUGE_PAGES): %s\n", huge_pages_summary().c_str());
        out["peak_rss_mib"] = peak_mib;
        out["huge_pages"] = huge_pages_summary();
        if (!cli.json_file.empty()) {
            std::ofstream f(cli.json_file);
            f << out.dump(2) << "\n";
            if (!f) throw InputError("bench: cannot write " + cli.json_file);
        }
        if (!hits_agree) std::printf("bench: rtcsim and Embree disagree on the hits (HITS DIFFER above)\n");
        if (!counts_agree)
            std::printf("bench: per-ray and warp execution counted different events (COUNTS DIFFER above)\n");
        return hits_agree && counts_agree ? 0 : 1;
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench: error: %s\n", e.what());
        return 3;
    }
}
