#include "sim/config/config_json.h"

#include <filesystem>

namespace rtc {

namespace {

using ojson = nlohmann::ordered_json;

ojson vec3(const Vec3& v) { return ojson::array({v.x, v.y, v.z}); }

std::string absolute(const std::string& path) {
    if (path.empty()) return path;
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::absolute(path, ec);
    return ec ? path : p.lexically_normal().string();
}

ojson axis_json(const BreakEvenAxis& a) {
    ojson events = ojson::array();
    for (const Event e : a.events) events.push_back(std::string(event_name(e)));
    return {{"events", events}, {"min", a.min}, {"max", a.max}};
}

}  // namespace

ojson workload_to_json(const WorkloadDesc& w) {
    ojson j;
    j["type"] = workload_type_name(w.type);
    if (w.type == WorkloadType::Rays) {
        j["rays_file"] = absolute(w.rays_file);
        return j;
    }
    if (w.camera.automatic) {
        j["camera"] = {{"from", vec3(w.camera.from)}, {"fov_deg", w.camera.fov_deg}};
    } else {
        j["camera"] = {{"position", vec3(w.camera.position)},
                       {"target", vec3(w.camera.target)},
                       {"up", vec3(w.camera.up)},
                       {"fov_deg", w.camera.fov_deg}};
    }
    j["width"] = w.width;
    j["height"] = w.height;
    j["spp"] = w.spp;
    if (w.type == WorkloadType::Camera) {
        j["bounces"] = w.bounces;
        j["albedo"] = {{"curves", vec3(w.curve_albedo)}, {"triangles", vec3(w.triangle_albedo)}};
        j["russian_roulette"] = w.russian_roulette;
    }
    j["seed"] = w.seed;
    j["environment"] = {{"type", "gradient"}, {"top", vec3(w.environment.top)}, {"bottom", vec3(w.environment.bottom)}};
    return j;
}

ojson run_config_to_json(const RunConfig& c, const nlohmann::json& given) {
    ojson j;
    j["name"] = c.name;
    j["description"] = c.description;
    j["scene"] = given.is_object() && given.contains("scene") ? given["scene"] : nlohmann::json();
    j["primitives"] = {{"kind", std::string(kind_name(c.kind))},
                       {"subdivision", c.subdivision},
                       {"obb", std::string(obb_variant_name(c.build.obb))}};
    j["methods"] = c.methods;
    j["baseline"] = c.baseline;
    j["bvh"] = {{"width", c.build.custom_blas.width},
                {"bins", c.build.custom_blas.bins},
                {"triangle_leaf_size", c.build.triangle_blas.max_leaf_size},
                {"oriented_triangles", c.build.oriented_triangles}};
    j["traversal"] = {{"schedule", c.trace.schedule == IsSchedule::Deferred ? "deferred" : "immediate"},
                      {"phantom_early_out", c.trace.phantom.early_out},
                      {"phantom_program", std::string(phantom_program_name(c.trace.phantom.program))}};
    j["cluster"] = {{"strategy", c.build.cluster.strategy == ClusterStrategy::Strand ? "strand" : "orientation"},
                    {"size", c.build.cluster.size},
                    {"frame", c.build.cluster.frame == ClusterFrame::Principal ? "principal" : "best"}};
    ojson cost = ojson::array();
    for (const std::string& p : c.cost_presets) cost.push_back(absolute(p));
    j["cost"] = cost;
    j["memory"] = absolute(c.memory_preset);
    j["workload"] = workload_to_json(c.workload);
    j["output"] = {{"images", c.output.images}, {"rays", c.output.write_rays}, {"hits", c.output.write_hits}};
    j["uncertainty"] = {{"draws", c.uncertainty.draws}, {"seed", c.uncertainty.seed}};
    if (given.is_object() && given.contains("calibrate") && !given["calibrate"].is_null())
        j["calibrate"] = given["calibrate"];
    if (!c.break_even.empty()) {
        ojson list = ojson::array();
        for (const BreakEvenSpec& b : c.break_even)
            list.push_back({{"name", b.name}, {"preset", b.preset}, {"x", axis_json(b.x)}, {"y", axis_json(b.y)},
                            {"cells", b.cells}});
        j["break_even"] = list;
    }
    return j;
}

}  // namespace rtc
