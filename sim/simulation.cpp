#include "sim/simulation.h"

#include "sim/json_reader.h"
#include "sim/ray_file.h"
#include "sim/scene_config.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

namespace rtc {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

StructureCounts count_structures(const MethodAccel& m) {
    StructureCounts c;
    c.width = m.accel.tlas.width;
    c.tlas_nodes = m.accel.tlas.node_count();
    c.instances = m.accel.instances.size();
    for (std::size_t b = 0; b < m.accel.blases.size(); ++b) {
        const Bvh& blas = m.accel.blases[b];
        c.blas_nodes += blas.node_count();
        (m.blas_kind[b] == BlasKind::Triangles ? c.triangles : c.custom_prims) +=
            blas.primitive_count();
    }
    return c;
}

RayWorkload make_frame(const WorkloadDesc& w, const Aabb& bounds, const std::string& config_file) {
    RayWorkload f;
    if (w.type == WorkloadType::Rays) {
        f.from_camera = false;
        f.rays = read_ray_file(resolve_config_path(w.rays_file, config_file));
        return f;
    }
    f.camera = make_camera(w, bounds);
    f.path = path_options(w);
    return f;
}

}  // namespace

const MethodRun* RunResult::find(Method m) const {
    for (const MethodRun& r : methods)
        if (r.method == m) return &r;
    return nullptr;
}

double RunResult::speedup(Method m, std::size_t preset) const {
    const MethodRun* ref = find(Method::Ref);
    const MethodRun* other = find(m);
    if (!ref || !other || !ref->runnable || !other->runnable || preset >= ref->priced.size() ||
        preset >= other->priced.size() || other->priced[preset].total_cycles <= 0.0)
        return 0.0;
    return ref->priced[preset].total_cycles / other->priced[preset].total_cycles;
}

RunResult run_simulation(const RunConfig& c, const nlohmann::json& effective,
                         const RunContext& ctx) {
    const auto t_start = std::chrono::steady_clock::now();
    RunResult r;
    r.config = c;
    r.effective_config = effective;
    for (const std::string& p : c.cost_presets) r.costs.push_back(load_cost_model(p));
    r.memory = load_memory_model(c.memory_preset);

    const auto t_load = std::chrono::steady_clock::now();
    const Scene scene = load_scene(JsonReader(c.scene, c.file, "/scene"));
    r.load_seconds = seconds_since(t_load);
    check_work(estimate_scene_work(c, scene), ctx.limits, c.file);
    const auto t_convert = std::chrono::steady_clock::now();
    const Geometry geometry = make_geometry(scene, c.kind, c.subdivision);
    r.primitives = geometry.primitive_count();
    r.scene = compute_stats(scene);
    r.areas = area_stats(geometry.prims);
    r.convert_seconds = seconds_since(t_convert);

    RayWorkload frame = make_frame(c.workload, geometry_bounds(geometry), c.file);
    r.camera = frame.camera;
    bool rays_written = false;
    for (const Method method : c.methods) {
        MethodRun m;
        m.method = method;
        m.instances = instance_count(method, geometry);
        if (m.instances > r.memory.instance_limit) {
            m.runnable = false;
            m.reason = std::to_string(m.instances) + " instances exceed the instance limit of " +
                       std::to_string(r.memory.instance_limit) + " (" + r.memory.name + ")";
            r.methods.push_back(std::move(m));
            continue;
        }
        const std::string name(method_name(method));
        const auto t_build = std::chrono::steady_clock::now();
        if (!ctx.quiet) std::fprintf(stderr, "build %s: %llu instances...", name.c_str(),
                                     static_cast<unsigned long long>(m.instances));
        MethodOptions build = c.build;
        build.custom_blas.threads = build.triangle_blas.threads = build.tlas.threads = ctx.threads;
        const MethodAccel accel = build_method(method, geometry, build);
        m.build_seconds = seconds_since(t_build);
        if (!ctx.quiet) std::fprintf(stderr, " done in %.2f s\n", m.build_seconds);
        m.structures = count_structures(accel);
        m.simulator_bytes = accel.accel.memory_bytes();
        FrameOptions fo;
        fo.threads = ctx.threads;
        fo.progress = !ctx.quiet;
        fo.label = "trace " + name;
        fo.record_hits = c.output.write_hits;
        fo.record_rays = c.output.write_rays && !rays_written;
        m.frame = run_frame(accel, geometry, frame, c.trace, fo);
        if (!ctx.out_dir.empty() && fo.record_rays) {
            write_ray_file((std::filesystem::path(ctx.out_dir) / "rays.bin").string(), m.frame.rays);
            rays_written = true;
        }
        if (!ctx.out_dir.empty() && fo.record_hits) {
            HitFileWriter w((std::filesystem::path(ctx.out_dir) / ("hits_" + name + ".bin")).string());
            w.append(std::span<const TraceHit>(m.frame.hits));
            w.close();
        }
        m.frame.rays.clear();
        m.frame.rays.shrink_to_fit();
        m.frame.hits.clear();
        m.frame.hits.shrink_to_fit();
        for (const CostModel& cost : r.costs) m.priced.push_back(price(m.frame.totals, cost));
        m.memory = price_memory(m.structures, r.memory, c.kind, r.primitives,
                                scene.mesh.vertices.size(), scene.mesh.triangles.size());
        r.methods.push_back(std::move(m));
    }
    r.total_seconds = seconds_since(t_start);
    return r;
}

}  // namespace rtc
