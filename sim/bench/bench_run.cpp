#include "sim/bench/bench_run.h"

#include "core/input_error.h"
#include "core/parallel.h"
#include "sim/hardware/cost_model.h"
#include "sim/execution/frame.h"
#include "sim/util/json_reader.h"
#include "sim/config/run_config.h"
#include "sim/config/scene_config.h"

#include <sys/resource.h>

#include <algorithm>
#include <optional>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>
#include <variant>

namespace rtc {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Best and median rate of `repeat` traces; every trace must count the same events.
ThreadRate time_traces(const BuiltMethod& method, const Geometry& g, const RayWorkload& frame,
                       const TraceOptions& trace, unsigned threads, int repeat, MethodFigures& m,
                       const CostModel* warp) {
    std::vector<double> seconds;
    std::uint64_t rays = 0;
    for (int i = 0; i < repeat; ++i) {
        const FrameResult r = bench_trace_frame(method, g, frame, trace, threads, warp);
        if (m.rates.empty() && i == 0) {  // the first trace of this method
            m.rays = r.rays_traced;
            m.totals = r.totals;
        } else if (!(r.totals == m.totals) || r.rays_traced != m.rays) {
            m.counts_match = false;
        }
        rays = r.rays_traced;
        seconds.push_back(std::max(r.trace_seconds, 1e-9));
    }
    std::sort(seconds.begin(), seconds.end());
    ThreadRate rate;
    rate.threads = threads;
    rate.best_seconds = seconds.front();
    rate.best_rays_per_second = static_cast<double>(rays) / seconds.front();
    rate.median_rays_per_second = static_cast<double>(rays) / seconds[seconds.size() / 2];
    return rate;
}

}  // namespace

// Not inlined: `valgrind --tool=callgrind --toggle-collect='*bench_trace_frame*'`
// counts the traces' instructions only (sim/bench/callgrind_per_ray.sh toggles
// on BuiltMethod::run instead, which older bench binaries have too).
[[gnu::noinline]] FrameResult bench_trace_frame(const BuiltMethod& method, const Geometry& g,
                                                const RayWorkload& frame, const TraceOptions& trace,
                                                unsigned threads, const CostModel* warp) {
    FrameOptions fo;
    fo.threads = threads;
    fo.progress = false;
    if (warp) {
        fo.warp = &warp->execution;
        fo.warp_presets = {warp};
    }
    return method.run(g, frame, trace, fo);
}

namespace {

// The preset `name` (--warp-preset), refused unless it models warps; `option`
// names what needs it.
CostModel load_warp_preset(const std::string& name, const char* option) {
    CostModel m = load_cost_model(name);
    if (!m.execution.warp())
        throw InputError(name + ": /execution/model: bench " + option + " needs a warp preset");
    return m;
}

}  // namespace

bool compare_warp_price(const BenchRun& bench_run, const BenchOptions& o) {
    const LoadedRun run = load_run(bench_run);
    const CostModel warp = load_warp_preset(o.warp_preset, "--warp-price");
    std::printf("  %s: %zu primitives, %zu triangles; warp preset %s\n", bench_run.label.c_str(),
                run.geometry.primitive_count(), run.geometry.triangles.size(), warp.name.c_str());
    bool same = true;
    for (const std::string& name : run.config.methods) {
        const std::unique_ptr<BuiltMethod> built = find_method(name)->build(run.geometry, run.config.build);
        std::printf("    %-6s %7s  %27s  %27s  %26s\n", name.c_str(), "threads", "per-ray Mrays/s med [range]",
                    "warp Mrays/s med [range]", "warp/per-ray time med [range]");
        for (const unsigned t0 : o.threads) {
            const unsigned t = t0 ? t0 : hardware_threads();
            std::vector<double> per_ray, warped, ratio;
            bool counts_same = true;
            for (int r = 0; r < o.repeat; ++r) {
                const FrameResult a = bench_trace_frame(*built, run.geometry, run.frame, run.config.trace, t, nullptr);
                const FrameResult b = bench_trace_frame(*built, run.geometry, run.frame, run.config.trace, t, &warp);
                counts_same = counts_same && a.totals == b.totals && a.rays_traced == b.rays_traced;
                const double sa = std::max(a.trace_seconds, 1e-9), sb = std::max(b.trace_seconds, 1e-9);
                per_ray.push_back(static_cast<double>(a.rays_traced) / sa * 1e-6);
                warped.push_back(static_cast<double>(b.rays_traced) / sb * 1e-6);
                ratio.push_back(sb / sa);
            }
            const Spread x = spread(per_ray), y = spread(warped), q = spread(ratio);
            std::printf("    %-6s %7u  %10.4g [%6.4g-%6.4g]  %10.4g [%6.4g-%6.4g]  %10.3f [%5.3f-%5.3f]%s\n", "", t,
                        x.median, x.lo, x.hi, y.median, y.lo, y.hi, q.median, q.lo, q.hi,
                        counts_same ? "" : "  COUNTS DIFFER");
            same = same && counts_same;
        }
        std::fflush(stdout);
    }
    return same;
}

Spread spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return {v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]), v.front(), v.back()};
}

std::uint64_t peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<std::uint64_t>(u.ru_maxrss) * 1024;  // Linux: KiB
}

LoadedRun load_run(const BenchRun& run) {
    LoadedRun out{parse_run_config(run.config, "bench:" + run.label), {}, {}, 0.0};
    const auto t_load = std::chrono::steady_clock::now();
    {
        const Scene scene = load_scene(out.config.scene);
        out.geometry = make_geometry(scene, out.config.kind, out.config.subdivision);
    }  // the strands go now: the scale case needs the memory
    out.load_seconds = seconds_since(t_load);
    out.frame.camera = make_camera(out.config.workload, geometry_bounds(out.geometry));
    out.frame.path = path_options(out.config.workload);
    return out;
}

RunFigures run_bench(const BenchRun& run, const BenchOptions& o) {
    LoadedRun loaded = load_run(run);
    const RunConfig& c = loaded.config;
    const Geometry& geometry = loaded.geometry;
    const RayWorkload& frame = loaded.frame;
    RunFigures out;
    out.label = run.label;
    out.kind = std::string(kind_name(c.kind));
    out.load_seconds = loaded.load_seconds;
    out.primitives = geometry.primitive_count();
    out.triangles = geometry.triangles.size();
    std::vector<unsigned> thread_counts;
    for (const unsigned t : o.threads) thread_counts.push_back(t ? t : hardware_threads());
    std::optional<CostModel> warp;
    if (!o.warp_preset.empty()) warp = load_warp_preset(o.warp_preset, "--execution warp");
    const CostModel* warp_ptr = warp ? &*warp : nullptr;

    for (const std::string& name : c.methods) {
        MethodFigures m;
        m.method = name;
        const auto t_build = std::chrono::steady_clock::now();
        const std::unique_ptr<BuiltMethod> built = find_method(name)->build(geometry, c.build);
        m.build_seconds = seconds_since(t_build);
        m.bytes_per_primitive = static_cast<double>(built->simulator_bytes()) /
                                static_cast<double>(std::max<std::uint64_t>(out.primitives, 1));
        std::fprintf(stderr, "  %s %s: built in %.2f s, tracing...\n", run.label.c_str(),
                     m.method.c_str(), m.build_seconds);
        for (const unsigned t : thread_counts) {
            m.rates.push_back(time_traces(*built, geometry, frame, c.trace, t, o.repeat, m, warp_ptr));
            if (t == 1) m.rays_per_second_1t = m.rates.back().best_rays_per_second;
            if (t >= m.threads) {
                m.threads = t;
                m.rays_per_second_nt = m.rates.back().best_rays_per_second;
            }
        }
        const double rays = static_cast<double>(std::max<std::uint64_t>(m.rays, 1));
        m.is_calls_per_ray = static_cast<double>(m.totals[Event::IsCall]) / rays;
        m.box_tests_per_ray =
            static_cast<double>(m.totals[Event::TlasBoxTest] + m.totals[Event::BlasBoxTest]) / rays;
        out.methods.push_back(std::move(m));
    }
    return out;
}

}  // namespace rtc
