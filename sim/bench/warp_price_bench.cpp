#include "sim/bench/warp_price_bench.h"

#include "core/input_error.h"
#include "core/parallel.h"
#include "sim/hardware/cost_model.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace rtc {

bool compare_warp_price(const BenchRun& bench_run, const BenchOptions& o) {
    const LoadedRun run = load_run(bench_run);
    const CostModel warp = load_cost_model(o.warp_preset);
    if (!warp.execution.warp())
        throw InputError(o.warp_preset + ": /execution/model: bench --warp-price needs a warp preset");
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

}  // namespace rtc
