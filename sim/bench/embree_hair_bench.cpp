#include "sim/bench/embree_hair_bench.h"

#include "core/input_error.h"
#include "core/parallel.h"
#include "sim/bench/embree_hair.h"
#include "sim/util/json_file.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <variant>

namespace rtc {

std::vector<BenchRun> hair_runs_of_config(const std::string& path) {
    const nlohmann::json config = parse_json_text(read_text_file(path), path);
    if (!config.is_object()) throw InputError(path + ": expected a run config (a JSON object)");
    nlohmann::json scenes = nlohmann::json::array();
    if (config.contains("sweep")) {
        const nlohmann::json& sweep = config["sweep"];
        if (!sweep.is_object() || sweep.size() != 1 || !sweep.contains("scene") || !sweep["scene"].is_array())
            throw InputError(path + ": /sweep: bench --embree-hair sweeps scenes only (a \"scene\" list)");
        scenes = sweep["scene"];
    } else if (config.contains("scene")) {
        scenes.push_back(config["scene"]);
    } else {
        throw InputError(path + ": no scene and no sweep of scenes");
    }
    std::vector<BenchRun> runs;
    for (const nlohmann::json& scene : scenes) {
        nlohmann::json one = config;
        one.erase("sweep");
        one["scene"] = scene;
        const std::string label = scene.is_object() && scene.contains("name") && scene["name"].is_string()
                                      ? scene["name"].get<std::string>()
                                      : "scene " + std::to_string(runs.size() + 1);
        runs.push_back({label, one});
    }
    return runs;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// How far two lists of closest hits are apart. The two Embree sides run
// different capsule tests (rtcsim's in double, Embree's curve test in float),
// so grazing rays may differ; the nearest t of the rays both hit is compared.
struct HitAgreement {
    std::size_t rays = 0, one_side = 0, far_t = 0;  // far_t: both hit, |dt|/t > 1e-3
    double max_relative_dt = 0.0;
    [[nodiscard]] double agreement() const {
        return rays ? 1.0 - static_cast<double>(one_side + far_t) / static_cast<double>(rays) : 1.0;
    }
};

template <class A, class B>
HitAgreement agree(const std::vector<A>& a, const std::vector<B>& b) {
    HitAgreement c;
    c.rays = a.size();
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].hit() != b[i].hit()) {
            ++c.one_side;
        } else if (a[i].hit()) {
            const double t = a[i].t, dt = std::abs(t - static_cast<double>(b[i].t)) / std::max(std::abs(t), 1e-30);
            c.max_relative_dt = std::max(c.max_relative_dt, dt);
            c.far_t += dt > 1e-3;
        }
    }
    return c;
}

nlohmann::json to_json(const HitAgreement& c) {
    return {{"rays", c.rays}, {"one_side", c.one_side}, {"far_t", c.far_t},
            {"max_relative_dt", c.max_relative_dt}, {"agreement", c.agreement()}};
}

nlohmann::json to_json(const EmbreeBvhStats& s) {
    return {{"primitive", s.primitive}, {"builder", s.builder}, {"sah", s.sah}, {"bytes", s.bytes},
            {"aligned_nodes", s.aligned_nodes}, {"oriented_nodes", s.oriented_nodes}, {"leaves", s.leaves}};
}

// What the simulator counted for one method on the frame, per ray.
nlohmann::json counted(const FrameResult& f) {
    const double rays = static_cast<double>(std::max<std::uint64_t>(f.rays_traced, 1));
    const auto per_ray = [&](Event e) { return static_cast<double>(f.totals[e]) / rays; };
    return {{"rays", f.rays_traced},
            {"blas_node_visits", per_ray(Event::BlasNodeVisit)},
            {"blas_box_tests", per_ray(Event::BlasBoxTest)},
            {"obb_box_tests", per_ray(Event::ObbBoxTest)},
            {"is_calls", per_ray(Event::IsCall)},
            {"triangle_tests", per_ray(Event::TriangleTest)}};
}

void print_counted(const char* name, const nlohmann::json& c) {
    std::printf("    rtcsim %-9s per ray: %5.2f BLAS node visits, %6.2f aligned box tests, %5.2f oriented box tests, "
                "%5.2f capsule tests (IS), %5.2f triangle tests\n",
                name, c["blas_node_visits"].get<double>(), c["blas_box_tests"].get<double>(),
                c["obb_box_tests"].get<double>(), c["is_calls"].get<double>(), c["triangle_tests"].get<double>());
}

}  // namespace

bool compare_hair_bvhs(const BenchRun& bench_run, const BenchOptions& o, nlohmann::json& out) {
    const LoadedRun run = load_run(bench_run);
    const auto* capsules = std::get_if<std::vector<Capsule>>(&run.geometry.prims);
    if (!capsules) throw InputError("bench --embree-hair: " + bench_run.label + ": primitives must be capsules");
    std::printf("  %s: %zu capsules, %zu triangles\n", bench_run.label.c_str(), capsules->size(),
                run.geometry.triangles.size());
    nlohmann::json j = {{"scene", bench_run.label}, {"segments", capsules->size()},
                        {"triangles", run.geometry.triangles.size()}};

    // The simulator: ref's rays and hits, and what ref and obb-nodes count on them.
    FrameOptions record;
    record.progress = false;
    record.threads = hardware_threads();
    record.record_rays = record.record_hits = true;
    const FrameResult ref = find_method("ref")->build(run.geometry, run.config.build)->run(
        run.geometry, run.frame, run.config.trace, record);
    FrameOptions plain;
    plain.progress = false;
    plain.threads = hardware_threads();
    const FrameResult obb_nodes = find_method("obb-nodes")->build(run.geometry, run.config.build)->run(
        run.geometry, run.frame, run.config.trace, plain);
    j["rtcsim"] = {{"ref", counted(ref)}, {"obb-nodes", counted(obb_nodes)}};
    std::printf("    %zu rays (ref's frame, recorded: camera and path rays)\n", ref.rays.size());
    print_counted("ref", j["rtcsim"]["ref"]);
    print_counted("obb-nodes", j["rtcsim"]["obb-nodes"]);
    std::fflush(stdout);

    // Embree: builds alternated, the last pair kept for tracing.
    const unsigned build_threads = o.threads.empty() || o.threads.back() == 0 ? hardware_threads() : o.threads.back();
    std::unique_ptr<EmbreeHairScene> aligned, oriented;
    std::vector<double> build_a, build_o, build_ratio;
    for (int r = 0; r < o.repeat; ++r) {
        aligned.reset();
        aligned = std::make_unique<EmbreeHairScene>(*capsules, run.geometry.triangles, HairBvh::Aligned, build_threads);
        oriented.reset();
        oriented = std::make_unique<EmbreeHairScene>(*capsules, run.geometry.triangles, HairBvh::Oriented, build_threads);
        build_a.push_back(aligned->build_seconds());
        build_o.push_back(oriented->build_seconds());
        build_ratio.push_back(oriented->build_seconds() / std::max(aligned->build_seconds(), 1e-9));
    }
    const Spread ba = spread(build_a), bo = spread(build_o), br = spread(build_ratio);

    std::vector<HairHit> hits_a(ref.rays.size()), hits_o(ref.rays.size());
    const std::uint64_t tests = aligned->trace(ref.rays, hits_a, build_threads);
    oriented->trace(ref.rays, hits_o, build_threads);
    const HitAgreement ao = agree(hits_a, hits_o), ra = agree(ref.hits, hits_a), ro = agree(ref.hits, hits_o);
    // The aligned side runs rtcsim's capsule test, so it must find ref's hits
    // (bench --embree's rule); the oriented side runs Embree's own curve test
    // in float, so a few grazing rays in a thousand may differ.
    const bool ok = ra.one_side <= 5e-6 * static_cast<double>(ra.rays) + 1 && ao.agreement() >= 0.99;

    // Primitive data each side keeps besides Embree's own allocations: the
    // aligned side's callbacks read rtcsim's capsules; the oriented side's
    // vertices are an Embree buffer, already in its byte count.
    const double capsule_bytes = static_cast<double>(capsules->size() * sizeof(Capsule));
    const double mem_a = static_cast<double>(aligned->embree_bytes()) + capsule_bytes;
    const double mem_o = static_cast<double>(oriented->embree_bytes());
    for (const EmbreeHairScene* s : {aligned.get(), oriented.get()}) {
        const EmbreeBvhStats& h = s->hair_stats();
        std::printf("    Embree %-8s (%s): BVH8<%s> by %s: %llu aligned + %llu oriented nodes, %llu leaves, "
                    "SAH %.1f, %.2f MB; Embree holds %.2f MB\n",
                    hair_bvh_name(s->bvh()), s->device_config().c_str(), h.primitive.c_str(), h.builder.c_str(),
                    static_cast<unsigned long long>(h.aligned_nodes), static_cast<unsigned long long>(h.oriented_nodes),
                    static_cast<unsigned long long>(h.leaves), h.sah, h.bytes * 1e-6,
                    static_cast<double>(s->embree_bytes()) * 1e-6);
    }
    const double rays = static_cast<double>(std::max<std::size_t>(ref.rays.size(), 1));
    std::printf("    build s (%u threads, median of %d): aligned %.3f, oriented %.3f, oriented/aligned %.2fx [%.2f-%.2f]\n",
                build_threads, o.repeat, ba.median, bo.median, br.median, br.lo, br.hi);
    std::printf("    memory: aligned %.2f MB (Embree's %.2f + capsules %.2f), oriented %.2f MB: oriented/aligned %.2fx; "
                "hair BVHs alone %.2fx\n",
                mem_a * 1e-6, static_cast<double>(aligned->embree_bytes()) * 1e-6, capsule_bytes * 1e-6, mem_o * 1e-6,
                mem_o / mem_a, oriented->hair_stats().bytes / std::max(aligned->hair_stats().bytes, 1.0));
    std::printf("    aligned side: %.2f capsule tests per ray (its callbacks; Embree counts none on the oriented side)\n",
                static_cast<double>(tests) / rays);
    std::printf("    hits: aligned vs oriented %.5f agree (%zu on one side only, %zu with |dt|/t > 1e-3, max %.2g); "
                "ref vs aligned %zu on one side only, max |dt|/t %.2g; ref vs oriented %.5f agree%s\n",
                ao.agreement(), ao.one_side, ao.far_t, ao.max_relative_dt, ra.one_side, ra.max_relative_dt,
                ro.agreement(), ok ? "" : "  HITS DIFFER");
    std::printf("      %7s  %26s  %26s  %26s\n", "threads", "aligned Mrays/s med [range]",
                "oriented Mrays/s med [range]", "oriented/aligned med [range]");
    nlohmann::json rates = nlohmann::json::array();
    for (const unsigned t0 : o.threads) {
        const unsigned t = t0 ? t0 : hardware_threads();
        std::vector<double> a, b, ratio;
        for (int r = 0; r < o.repeat; ++r) {
            auto start = std::chrono::steady_clock::now();
            aligned->trace(ref.rays, hits_a, t);
            const double ra_rate = rays / std::max(seconds_since(start), 1e-9);
            start = std::chrono::steady_clock::now();
            oriented->trace(ref.rays, hits_o, t);
            const double ro_rate = rays / std::max(seconds_since(start), 1e-9);
            a.push_back(ra_rate * 1e-6);
            b.push_back(ro_rate * 1e-6);
            ratio.push_back(ro_rate / ra_rate);
        }
        const Spread x = spread(a), y = spread(b), q = spread(ratio);
        std::printf("      %7u  %10.4g [%6.4g-%6.4g]  %10.4g [%6.4g-%6.4g]  %10.2fx [%5.2f-%5.2f]\n", t, x.median,
                    x.lo, x.hi, y.median, y.lo, y.hi, q.median, q.lo, q.hi);
        rates.push_back({{"threads", t},
                         {"aligned_mrays", {x.median, x.lo, x.hi}},
                         {"oriented_mrays", {y.median, y.lo, y.hi}},
                         {"speedup", {q.median, q.lo, q.hi}}});
    }
    std::fflush(stdout);
    j["embree"] = {
        {"version", embree_version()},
        {"rays", ref.rays.size()},
        {"repeat", o.repeat},
        {"build_threads", build_threads},
        {"aligned",
         {{"device_config", aligned->device_config()}, {"bvh", to_json(aligned->hair_stats())},
          {"build_seconds", ba.median}, {"embree_bytes", aligned->embree_bytes()}, {"memory_bytes", mem_a},
          {"capsule_tests_per_ray", static_cast<double>(tests) / rays}}},
        {"oriented",
         {{"device_config", oriented->device_config()}, {"bvh", to_json(oriented->hair_stats())},
          {"build_seconds", bo.median}, {"embree_bytes", oriented->embree_bytes()}, {"memory_bytes", mem_o}}},
        {"build_ratio", {br.median, br.lo, br.hi}},
        {"memory_ratio", mem_o / mem_a},
        {"hair_bvh_bytes_ratio", oriented->hair_stats().bytes / std::max(aligned->hair_stats().bytes, 1.0)},
        {"rates", rates},
        {"hits", {{"aligned_vs_oriented", to_json(ao)}, {"ref_vs_aligned", to_json(ra)}, {"ref_vs_oriented", to_json(ro)}}},
    };
    out.push_back(j);
    return ok;
}

}  // namespace rtc
