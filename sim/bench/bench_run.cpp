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
#include <variant>

namespace rtc {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

FrameResult trace_frame(const BuiltMethod& method, const Geometry& g, const RayWorkload& frame,
                        const TraceOptions& trace, unsigned threads, const CostModel* warp) {
    FrameOptions fo;
    fo.threads = threads;
    fo.progress = false;
    if (warp) {
        fo.warp = &warp->execution;
        fo.warp_presets = {warp};
    }
    return method.run(g, frame, trace, fo);
}

// Best rate of `repeat` traces; every trace must count the same events.
double best_rate(const BuiltMethod& method, const Geometry& g, const RayWorkload& frame,
                 const TraceOptions& trace, unsigned threads, int repeat, MethodFigures& m,
                 const CostModel* warp) {
    double best = 0.0;
    for (int i = 0; i < repeat; ++i) {
        const FrameResult r = trace_frame(method, g, frame, trace, threads, warp);
        if (m.rays == 0) {
            m.rays = r.rays_traced;
            m.totals = r.totals;
        } else if (!(r.totals == m.totals)) {
            m.counts_match = false;
        }
        best = std::max(best, static_cast<double>(r.rays_traced) / r.trace_seconds);
    }
    return best;
}

}  // namespace

std::uint64_t peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<std::uint64_t>(u.ru_maxrss) * 1024;  // Linux: KiB
}

RunFigures run_bench(const BenchRun& run, const BenchOptions& o) {
    const RunConfig c = parse_run_config(run.config, "bench:" + run.label);
    RunFigures out;
    out.label = run.label;
    out.kind = std::string(kind_name(c.kind));

    const auto t_load = std::chrono::steady_clock::now();
    Geometry geometry;
    {
        const Scene scene = load_scene(JsonReader(c.scene, c.file, "/scene"));
        geometry = make_geometry(scene, c.kind, c.subdivision);
    }  // the strands go now: the scale case needs the memory
    out.load_seconds = seconds_since(t_load);
    out.primitives = geometry.primitive_count();
    out.triangles = geometry.triangles.size();

    RayWorkload frame;
    frame.camera = make_camera(c.workload, geometry_bounds(geometry));
    frame.path = path_options(c.workload);
    const unsigned threads = o.threads ? o.threads : hardware_threads();
    std::optional<CostModel> warp;
    if (!o.warp_preset.empty()) warp = load_cost_model(o.warp_preset);
    if (warp && !warp->execution.warp())
        throw InputError(o.warp_preset + ": /execution/model: bench --execution warp needs a warp preset");
    const CostModel* warp_ptr = warp ? &*warp : nullptr;

    for (const std::string& name : c.methods) {
        MethodFigures m;
        m.method = name;
        m.threads = threads;
        const auto t_build = std::chrono::steady_clock::now();
        const std::unique_ptr<BuiltMethod> built = find_method(name)->build(geometry, c.build);
        m.build_seconds = seconds_since(t_build);
        m.bytes_per_primitive = static_cast<double>(built->simulator_bytes()) /
                                static_cast<double>(std::max<std::uint64_t>(out.primitives, 1));
        std::fprintf(stderr, "  %s %s: built in %.2f s, tracing...\n", run.label.c_str(),
                     m.method.c_str(), m.build_seconds);
        if (o.single_thread)
            m.rays_per_second_1t = best_rate(*built, geometry, frame, c.trace, 1, o.repeat, m, warp_ptr);
        m.rays_per_second_nt = best_rate(*built, geometry, frame, c.trace, threads, o.repeat, m, warp_ptr);
        const double rays = static_cast<double>(std::max<std::uint64_t>(m.rays, 1));
        m.is_calls_per_ray = static_cast<double>(m.totals[Event::IsCall]) / rays;
        m.box_tests_per_ray =
            static_cast<double>(m.totals[Event::TlasBoxTest] + m.totals[Event::BlasBoxTest]) / rays;
        out.methods.push_back(std::move(m));
    }
    return out;
}

}  // namespace rtc
