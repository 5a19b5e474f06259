// Strict parsing of the "workload" config section (keys and defaults in
// docs/workload-config.md) and its translation into camera and path options.
#include "sim/config/workload_config.h"

#include "sim/util/paths.h"

#include <filesystem>
#include <limits>

namespace rtc {
namespace {

constexpr long long kMaxU32 = std::numeric_limits<std::uint32_t>::max();
constexpr long long kMaxInt = std::numeric_limits<int>::max();

Vec3 to_vec3(const std::array<double, 3>& a) {
    return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

// A colour: a number (gray) or [r, g, b], every component in [lo, hi].
Vec3 color(const JsonReader& r, std::string_view key, Vec3 fallback, double lo, double hi) {
    if (!r.has(key)) return fallback;
    const nlohmann::json& v = r.json().at(std::string(key));
    std::string range(1, '[');  // appended piecewise: GCC 12 warns on "[" + string&&
    range.append(describe(lo)).append(", ").append(describe(hi)).append("]");
    if (v.is_number()) {
        const double x = v.get<double>();
        if (!(x >= lo && x <= hi))
            r.fail(key, "expected a number in " + range + " or [r, g, b], got " + describe(v));
        return Vec3(static_cast<float>(x));
    }
    if (!v.is_array()) r.fail(key, "expected a number or [r, g, b], got " + describe(v));
    const auto c = r.vec3(key, std::nullopt);
    for (double x : c)
        if (!(x >= lo && x <= hi))
            r.fail(key, "expected components in " + range + ", got " + describe(v));
    return to_vec3(c);
}

CameraDesc parse_camera(const JsonReader& r, const CameraDesc& defaults) {
    if (!r.has("camera")) return defaults;
    const nlohmann::json& v = r.json().at("camera");
    if (v.is_string()) {
        if (v.get<std::string>() != "auto")
            r.fail("camera", "expected \"auto\" or an object, got " + describe(v));
        return defaults;
    }
    if (!v.is_object()) r.fail("camera", "expected \"auto\" or an object, got " + describe(v));
    const JsonReader c = r.child("camera");
    c.allow_only({"position", "target", "up", "fov_deg", "from"});
    CameraDesc d = defaults;
    d.fov_deg = static_cast<float>(c.number("fov_deg", defaults.fov_deg, 1e-3, 179.0));
    d.automatic = !c.has("position");
    if (d.automatic) {
        if (c.has("target")) c.fail("target", "only with \"position\" (explicit camera)");
        if (c.has("up")) c.fail("up", "only with \"position\" (auto cameras use +Y up)");
        d.from = to_vec3(c.vec3("from", std::array<double, 3>{0.0, 0.0, 1.0}));
        if (d.from == Vec3(0.0f)) c.fail("from", "expected a non-zero direction");
        return d;
    }
    if (c.has("from")) c.fail("from", "only for auto cameras (without \"position\")");
    d.position = to_vec3(c.vec3("position", std::nullopt));
    d.target = to_vec3(c.vec3("target", std::nullopt));
    d.up = to_vec3(c.vec3("up", std::array<double, 3>{0.0, 1.0, 0.0}));
    if (d.position == d.target) c.fail("target", "must differ from position");
    const Vec3 w = d.target - d.position;
    if (!(glm::length(glm::cross(glm::normalize(w), d.up)) > 1e-6f))
        c.fail("up", "must be non-zero and not parallel to target - position");
    return d;
}

std::pair<Vec3, Vec3> parse_albedo(const JsonReader& r, Vec3 curves, Vec3 triangles) {
    if (!r.has("albedo")) return {curves, triangles};
    const nlohmann::json& v = r.json().at("albedo");
    if (!v.is_object()) {
        const Vec3 both = color(r, "albedo", curves, 0.0, 1.0);
        return {both, both};
    }
    const JsonReader a = r.child("albedo");
    a.allow_only({"curves", "triangles"});
    return {color(a, "curves", curves, 0.0, 1.0), color(a, "triangles", triangles, 0.0, 1.0)};
}

Environment parse_environment(const JsonReader& r, const Environment& fallback) {
    if (!r.has("environment")) return fallback;
    const nlohmann::json& v = r.json().at("environment");
    constexpr double kMax = 1e30;
    if (!v.is_object()) return Environment::constant(color(r, "environment", fallback.top, 0.0, kMax));
    const JsonReader e = r.child("environment");
    const std::string type = e.choice("type", std::nullopt, {"constant", "gradient"});
    if (type == "constant") {
        e.allow_only({"type", "radiance"});
        return Environment::constant(color(e, "radiance", Vec3(1.0f), 0.0, kMax));
    }
    e.allow_only({"type", "top", "bottom"});
    return {color(e, "top", Vec3(1.0f), 0.0, kMax), color(e, "bottom", Vec3(0.0f), 0.0, kMax)};
}

// Keys that mean nothing for a type are rejected rather than ignored.
void reject(const JsonReader& r, std::initializer_list<std::string_view> keys, const char* type) {
    for (std::string_view k : keys)
        if (r.has(k)) r.fail(k, std::string("not used by workload type \"") + type + "\"");
}

}  // namespace

const char* workload_type_name(WorkloadType t) {
    switch (t) {
        case WorkloadType::Camera: return "camera";
        case WorkloadType::Primary: return "primary";
        case WorkloadType::Rays: return "rays";
    }
    return "?";
}

WorkloadDesc parse_workload(const JsonReader& r) {
    r.allow_only({"type", "camera", "width", "height", "spp", "bounces", "seed", "albedo",
                  "environment", "russian_roulette", "rays_file"});
    WorkloadDesc d;
    const std::string type = r.choice("type", "camera", {"camera", "primary", "rays"});
    d.type = type == "rays"      ? WorkloadType::Rays
             : type == "primary" ? WorkloadType::Primary
                                 : WorkloadType::Camera;
    if (d.type == WorkloadType::Rays) {
        reject(r, {"camera", "width", "height", "spp", "bounces", "seed", "albedo", "environment",
                   "russian_roulette"},
               "rays");
        const std::string file = r.string("rays_file", std::nullopt);
        if (file.empty()) r.fail("rays_file", "expected a non-empty path");
        // Absolute, so a run opens the file the config names from any working
        // directory, and nothing resolves it again.
        const std::string path = config_relative_path(file, r.file());
        std::error_code ec;
        const std::filesystem::path abs = std::filesystem::absolute(path, ec);
        d.rays_file = ec ? path : abs.lexically_normal().string();
        return d;
    }
    if (r.has("rays_file")) r.fail("rays_file", "only for workload type \"rays\"");
    if (d.type == WorkloadType::Primary) {
        reject(r, {"bounces", "albedo", "russian_roulette"}, "primary");
        d.bounces = 0;
    }
    d.camera = parse_camera(r, d.camera);
    d.width = static_cast<int>(r.integer("width", d.width, 1, kMaxInt));
    d.height = static_cast<int>(r.integer("height", d.height, 1, kMaxInt));
    d.spp = static_cast<std::uint32_t>(r.integer("spp", d.spp, 1, kMaxInt));
    if (d.type == WorkloadType::Camera) {
        d.bounces = static_cast<std::uint32_t>(r.integer("bounces", d.bounces, 0, 1000));
        std::tie(d.curve_albedo, d.triangle_albedo) =
            parse_albedo(r, d.curve_albedo, d.triangle_albedo);
        d.russian_roulette = r.boolean("russian_roulette", d.russian_roulette);
    }
    d.seed = static_cast<std::uint32_t>(r.integer("seed", d.seed, 0, kMaxU32));
    d.environment = parse_environment(r, d.environment);
    return d;
}

PathOptions path_options(const WorkloadDesc& w) {
    PathOptions o;
    o.shading = w.type == WorkloadType::Primary ? Shading::Primary : Shading::Path;
    o.spp = w.spp;
    o.bounces = w.type == WorkloadType::Primary ? 0 : w.bounces;
    o.seed = w.seed;
    o.curve_albedo = w.curve_albedo;
    o.triangle_albedo = w.triangle_albedo;
    o.environment = w.environment;
    o.russian_roulette = w.russian_roulette;
    return o;
}

Camera make_camera(const WorkloadDesc& w, const Aabb& scene_bounds) {
    if (w.camera.automatic)
        return auto_frame(scene_bounds, w.camera.fov_deg, w.width, w.height, w.camera.from);
    Camera c;
    c.position = w.camera.position;
    c.target = w.camera.target;
    c.up = w.camera.up;
    c.fov_deg = w.camera.fov_deg;
    c.width = w.width;
    c.height = w.height;
    validate(c);
    return c;
}

}  // namespace rtc
