// Reading the `scene` block of a config (see scene_config.h, docs/scenes.md).
// Values are range-checked here, through JsonReader, so the generators'
// own std::invalid_argument checks never fire on config input.
#include "sim/config/scene_config.h"

#include "scenes/generators/bundle.h"
#include "scenes/generators/follow_hairs.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/loaders/loaders.h"
#include "sim/util/paths.h"

#include <cmath>
#include <limits>

namespace rtc {

namespace {

constexpr long long kMaxCount = std::numeric_limits<std::uint32_t>::max();

Vec3 to_vec3(const std::array<double, 3>& a) {
    return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

Scene bundle_scene(const JsonReader& j) {
    j.allow_only({"type", "name", "count", "radius", "tilt_deg", "seed", "bundle_radius", "length"});
    BundleDesc d;
    d.count = static_cast<std::uint32_t>(j.integer("count", d.count, 1, kMaxCount));
    d.bundle_radius = j.length("bundle_radius", d.bundle_radius);
    d.radius = j.length("radius", d.radius);
    if (!(d.radius < d.bundle_radius))
        j.fail("radius", "must be smaller than bundle_radius (" + describe(d.bundle_radius) + ")");
    d.tilt_deg = static_cast<float>(j.number("tilt_deg", d.tilt_deg, -360.0, 360.0));
    d.seed = static_cast<std::uint64_t>(j.integer("seed", 1, 0, std::numeric_limits<long long>::max()));
    d.length = j.length("length", d.length);
    Scene s = make_bundle(d);
    if (j.has("name")) s.name = j.string("name", std::nullopt);
    return s;
}

Scene hair_scene(const JsonReader& j) {
    j.allow_only({"type", "name", "emitter", "sphere_radius", "sphere_center", "mesh", "lock_center",
                  "lock_radius", "lock_axis", "style", "strands", "points_per_strand", "length", "radius",
                  "tip_radius", "lean", "wave_amplitude", "waves", "curl_radius", "curl_turns", "seed",
                  "with_mesh"});
    HairDesc d;
    const std::string emitter = j.choice("emitter", "sphere", {"sphere", "mesh", "lock"});
    d.emitter = emitter == "sphere" ? HairEmitter::Sphere : emitter == "mesh" ? HairEmitter::Mesh : HairEmitter::Lock;
    // Each emitter's own keys only with that emitter.
    for (const auto& [key, owner] : {std::pair{"sphere_radius", "sphere"}, {"sphere_center", "sphere"},
                                     {"mesh", "mesh"}, {"lock_center", "lock"}, {"lock_radius", "lock"},
                                     {"lock_axis", "lock"}})
        if (j.has(key) && emitter != owner) j.fail(key, std::string("only with \"emitter\": \"") + owner + "\"");
    d.sphere_radius = j.length("sphere_radius", d.sphere_radius);
    d.sphere_center = to_vec3(j.vec3("sphere_center", std::array<double, 3>{0, 0, 0}));
    for (const float x : {d.sphere_center.x, d.sphere_center.y, d.sphere_center.z})
        if (std::abs(x) > JsonReader::kMaxLength) j.fail("sphere_center", "components must lie in [-1e18, 1e18]");
    d.lock_radius = j.length("lock_radius", d.lock_radius);
    d.lock_center = to_vec3(j.vec3("lock_center", std::array<double, 3>{0, 0, 0}));
    for (const float x : {d.lock_center.x, d.lock_center.y, d.lock_center.z})
        if (std::abs(x) > JsonReader::kMaxLength) j.fail("lock_center", "components must lie in [-1e18, 1e18]");
    d.lock_axis = to_vec3(j.vec3("lock_axis", std::array<double, 3>{0, -1, 0}));
    if (!(glm::length(d.lock_axis) > 0.0f)) j.fail("lock_axis", "must not be zero");
    const std::string style = j.choice("style", "straight", {"straight", "wavy", "curly"});
    d.style = style == "straight" ? HairStyle::Straight : style == "wavy" ? HairStyle::Wavy : HairStyle::Curly;
    d.strands = static_cast<std::uint32_t>(j.integer("strands", d.strands, 1, kMaxCount));
    d.points_per_strand = static_cast<std::uint32_t>(j.integer("points_per_strand", d.points_per_strand, 2, 65536));
    if (std::uint64_t{d.strands} * d.points_per_strand >= (std::uint64_t{1} << 32))
        j.fail("strands", "strands x points_per_strand must stay below 2^32");
    d.length = j.length("length", d.length);
    d.radius = j.length("radius", d.radius);
    d.tip_radius = j.length("tip_radius", d.radius, /*allow_zero=*/true);
    d.lean = static_cast<float>(j.number("lean", d.lean, 0.0, 10.0));
    d.wave_amplitude = static_cast<float>(j.number("wave_amplitude", d.wave_amplitude, 0.0, 1e3));  // x length
    d.waves = static_cast<float>(j.number("waves", d.waves, 0.0, 1e6));
    d.curl_radius = static_cast<float>(j.number("curl_radius", d.curl_radius, 0.0, 1e3));  // x length
    d.curl_turns = static_cast<float>(j.number("curl_turns", d.curl_turns, 0.0, 1e6));
    d.seed = static_cast<std::uint64_t>(j.integer("seed", 1, 0, std::numeric_limits<long long>::max()));
    d.with_mesh = j.boolean("with_mesh", d.with_mesh);
    if (d.with_mesh && d.emitter == HairEmitter::Lock) j.fail("with_mesh", "a lock has no emitter mesh");
    Scene s;
    if (d.emitter != HairEmitter::Mesh) {
        s = make_hair(d);
    } else {
        const std::filesystem::path path = resolve_data_path(j, "mesh");
        const ObjContents obj = load_obj(path);
        if (obj.mesh.triangles.empty()) j.fail("mesh", "no faces in " + path.string());
        s = make_hair_on_mesh(d, obj.mesh);
    }
    if (j.has("name")) s.name = j.string("name", std::nullopt);
    return s;
}

Strands curves_from_file(const JsonReader& c) {
    c.allow_only({"path", "format", "radius", "radius_scale", "follow_hairs", "follow_spread",
                  "follow_tip_separation", "follow_seed"});
    const std::string format_name =
        c.choice("format", "auto", {"auto", "hair", "tfx", "trk", "swc", "obj", "txt", "pbrt"});
    const std::filesystem::path path = resolve_data_path(c, "path");
    LoadedCurves loaded = load_curves(path, *curve_format_from_name(format_name));
    if (loaded.strands.strand_count() == 0) c.fail("path", "no strands in " + path.string());
    const double scale = c.positive("radius_scale", 1.0);
    if (c.has("radius")) {
        const float r = c.length("radius", std::nullopt);
        loaded.strands.radii.assign(loaded.strands.radii.size(), r);
    } else if (!loaded.has_radius) {
        c.fail("radius", "missing: " + path.string() + " carries no radius, so one must be set");
    }
    for (float& r : loaded.strands.radii) {
        r = static_cast<float>(r * scale);
        if (!(r <= JsonReader::kMaxLength))
            c.fail("radius_scale", describe(scale) + " makes a radius exceed 1e18");
    }

    FollowHairDesc f;
    f.per_guide = static_cast<std::uint32_t>(c.integer("follow_hairs", 0, 0, 64));
    if (f.per_guide > 0) {
        f.spread = c.length("follow_spread", std::nullopt);
        f.tip_separation = static_cast<float>(c.number("follow_tip_separation", 1.0, 0.0, 1e6));
        f.seed = static_cast<std::uint64_t>(c.integer("follow_seed", 1, 0, std::numeric_limits<long long>::max()));
        return add_follow_hairs(loaded.strands, f);
    }
    for (const char* key : {"follow_spread", "follow_tip_separation", "follow_seed"})
        if (c.has(key)) c.fail(key, "only with \"follow_hairs\" > 0");
    return std::move(loaded.strands);
}

void append_strands(Strands& into, const Strands& more) {
    const auto base = static_cast<std::uint32_t>(into.points.size());
    into.points.insert(into.points.end(), more.points.begin(), more.points.end());
    into.radii.insert(into.radii.end(), more.radii.begin(), more.radii.end());
    for (std::size_t i = 1; i < more.offsets.size(); ++i) into.offsets.push_back(base + more.offsets[i]);
}

Scene file_scene(const JsonReader& j) {
    j.allow_only({"type", "name", "curves", "mesh"});
    if (!j.has("curves") && !j.has("mesh")) j.fail("", "a file scene needs \"curves\", \"mesh\" or both");
    Scene s;
    if (j.has("curves") && j.json()["curves"].is_array()) {
        // Several curve files (e.g. one SWC per neuron) form one scene.
        const nlohmann::json& list = j.json()["curves"];
        if (list.empty()) j.fail("curves", "expected a curve object or a non-empty list of them");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const JsonReader c(list[i], j.file(), j.key_path("curves") + "/" + std::to_string(i));
            c.require_object();
            append_strands(s.strands, curves_from_file(c));
        }
        s.name = j.key_path("curves");
    } else if (j.has("curves")) {
        const JsonReader c = j.child("curves");
        s.strands = curves_from_file(c);
        s.name = c.string("path", std::nullopt);
    }
    if (j.has("mesh")) {
        const JsonReader m = j.child("mesh");
        m.allow_only({"path", "format"});
        const std::string format = m.choice("format", "auto", {"auto", "obj", "gltf", "glb", "ply", "pbrt"});
        const std::filesystem::path path = resolve_data_path(m, "path");
        s.mesh = load_mesh(path, *mesh_format_from_name(format));
        if (s.mesh.triangles.empty()) m.fail("path", "no faces in " + path.string());
        if (s.name.empty()) s.name = path.string();
    }
    if (j.has("name")) s.name = j.string("name", std::nullopt);
    return s;
}

}  // namespace

std::filesystem::path resolve_data_path(const JsonReader& block, std::string_view key) {
    const std::string given = block.string(key, std::nullopt);
    if (given.empty()) block.fail(key, "empty path");
    const std::filesystem::path path = config_relative_path(given, block.file());
    std::error_code ec;  // a symlink loop or an over-long name: an error naming the key, not a filesystem_error
    if (std::filesystem::exists(path, ec)) return path;
    if (ec) block.fail(key, "cannot access " + path.string() + " (" + ec.message() + ")");
    block.fail(key, "no such file: " + path.string() +
                        (std::filesystem::path(given).is_absolute() ? "" : " (paths are relative to the config file)"));
}

Scene load_scene(const JsonReader& j) {
    j.require_object();
    const std::string type = j.choice("type", std::nullopt, {"bundle", "hair", "file"});
    if (type == "bundle") return bundle_scene(j);
    if (type == "hair") return hair_scene(j);
    return file_scene(j);
}

}  // namespace rtc
