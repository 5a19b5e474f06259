#include "sim/bench/embree_bench.h"

#if RTCSIM_EMBREE
#include "core/parallel.h"
#include "sim/bench/embree_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <variant>
#endif

namespace rtc {

#if RTCSIM_EMBREE

namespace {

// How far apart the two sides' hits are.
struct HitCheck {
    std::size_t rays = 0, rtcsim_hits = 0, embree_hits = 0;
    std::size_t one_side = 0;    // rays that hit on one side only
    std::size_t other_prim = 0;  // both hit, different capsules (ties, grazing overlaps)
    double max_relative_dt = 0.0;
    // Both run the same capsule test on the same rays, so a disagreement can
    // only come from the boxes around it (each side rounds its own box tests
    // outward): a ray grazing a box's edge. A few in a million rays, and the
    // nearest t within 1e-5 of each other, is agreement.
    [[nodiscard]] bool ok() const {
        return static_cast<double>(one_side) <= 5e-6 * static_cast<double>(rays) && max_relative_dt <= 1e-5;
    }
};

HitCheck check_hits(const std::vector<TraceHit>& ours, const std::vector<EmbreeHit>& theirs) {
    HitCheck c;
    c.rays = ours.size();
    for (std::size_t i = 0; i < ours.size(); ++i) {
        const bool a = ours[i].hit(), b = theirs[i].hit();
        c.rtcsim_hits += a;
        c.embree_hits += b;
        if (a != b) {
            ++c.one_side;
        } else if (a) {
            c.other_prim += ours[i].prim != theirs[i].prim;
            const double t = ours[i].t;
            c.max_relative_dt = std::max(c.max_relative_dt, std::abs(t - theirs[i].t) / std::max(std::abs(t), 1e-30));
        }
    }
    return c;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One method: build both, check the hits, time them alternately.
bool compare_method(const std::string& name, const LoadedRun& run, const std::vector<Capsule>& capsules,
                    const BenchOptions& o) {
    const auto t_build = std::chrono::steady_clock::now();
    const std::unique_ptr<BuiltMethod> built = find_method(name)->build(run.geometry, run.config.build);
    const double rtcsim_build = seconds_since(t_build);
    const EmbreeCapsules embree(capsules, name);

    FrameOptions record;
    record.progress = false;
    record.record_rays = record.record_hits = true;
    const FrameResult recorded = built->run(run.geometry, run.frame, run.config.trace, record);
    std::vector<EmbreeHit> hits(recorded.rays.size());
    embree.trace(recorded.rays, hits, hardware_threads());
    const HitCheck c = check_hits(recorded.hits, hits);
    std::printf("    %-4s build s: rtcsim %.3f, Embree %.3f; %zu rays; hits: rtcsim %zu, Embree %zu, on one side "
                "only %zu, other capsule %zu, max |dt|/t %.2g%s\n",
                name.c_str(), rtcsim_build, embree.build_seconds(), c.rays, c.rtcsim_hits, c.embree_hits,
                c.one_side, c.other_prim, c.max_relative_dt, c.ok() ? "" : "  HITS DIFFER");
    std::printf("      %7s  %26s  %26s  %25s\n", "threads", "rtcsim Mrays/s med [range]",
                "Embree Mrays/s med [range]", "rtcsim/Embree med [range]");
    for (const unsigned t0 : o.threads) {
        const unsigned t = t0 ? t0 : hardware_threads();
        std::vector<double> ours, theirs, ratio;
        for (int r = 0; r < o.repeat; ++r) {
            const FrameResult f = bench_trace_frame(*built, run.geometry, run.frame, run.config.trace, t, nullptr);
            const double a = static_cast<double>(f.rays_traced) / std::max(f.trace_seconds, 1e-9);
            const auto start = std::chrono::steady_clock::now();
            embree.trace(recorded.rays, hits, t);
            const double b = static_cast<double>(hits.size()) / std::max(seconds_since(start), 1e-9);
            ours.push_back(a * 1e-6);
            theirs.push_back(b * 1e-6);
            ratio.push_back(a / b);
        }
        const Spread x = spread(ours), y = spread(theirs), q = spread(ratio);
        std::printf("      %7u  %10.4g [%6.4g-%6.4g]  %10.4g [%6.4g-%6.4g]  %10.2fx [%5.2f-%5.2f]\n", t, x.median,
                    x.lo, x.hi, y.median, y.lo, y.hi, q.median, q.lo, q.hi);
    }
    return c.ok();
}

}  // namespace

bool embree_built() { return true; }

bool compare_with_embree(const BenchRun& bench_run, const BenchOptions& o) {
    const LoadedRun run = load_run(bench_run);
    const auto* capsules = std::get_if<std::vector<Capsule>>(&run.geometry.prims);
    std::printf("  %s: %zu primitives, %zu triangles\n", bench_run.label.c_str(), run.geometry.primitive_count(),
                run.geometry.triangles.size());
    if (!capsules || !run.geometry.triangles.empty()) {
        std::printf("    Embree: skipped (it mirrors capsule scenes without a mesh)\n");
        return true;
    }
    bool ok = true;
    for (const std::string& name : run.config.methods) {
        if (name != "ref" && name != "obb") {
            std::printf("    %s: skipped (Embree mirrors ref and obb)\n", name.c_str());
            continue;
        }
        ok = compare_method(name, run, *capsules, o) && ok;
        std::fflush(stdout);
    }
    return ok;
}

#else

bool embree_built() { return false; }
bool compare_with_embree(const BenchRun&, const BenchOptions&) { return true; }

#endif

}  // namespace rtc
