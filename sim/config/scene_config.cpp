// Reading the `scene` block of a config (see scene_config.h, docs/scenes.md).
// Values are range-checked here, through JsonReader, so the generators'
// own std::invalid_argument checks never fire on config input.
#include "sim/config/scene_config.h"

#include "scenes/generators/ribbons.h"
#include "sim/util/paths.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtc {

namespace {

constexpr long long kMaxCount = std::numeric_limits<std::uint32_t>::max();

Vec3 to_vec3(const std::array<double, 3>& a) {
    return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

// As JsonReader::fail, for a key read when the config was planned.
[[noreturn]] void fail_at(const SceneDesc& d, const std::string& key, const std::string& problem) {
    throw InputError(d.file + ": " + key + ": " + problem);
}

DataPath data_path(const JsonReader& block, std::string_view key) {
    const std::string given = block.string(key, std::nullopt);
    if (given.empty()) block.fail(key, "empty path");
    DataPath p;
    p.key = block.key_path(key);
    p.shown = config_data_path(given, block.file());
    std::error_code ec;  // a symlink loop or an over-long name: an error naming the key, not a filesystem_error
    const bool exists = std::filesystem::exists(p.shown, ec);
    if (ec) block.fail(key, "cannot access " + p.shown + " (" + ec.message() + ")");
    if (!exists && is_data_path(given))
        block.fail(key, "no such file: " + p.shown + " (data root " + data_root().string() +
                            "; run scripts/fetch-data, or give the root with --data DIR or RTCSIM_DATA)");
    if (!exists)
        block.fail(key, "no such file: " + p.shown +
                            (std::filesystem::path(given).is_absolute() ? "" : " (paths are relative to the config file)"));
    const std::filesystem::path abs = std::filesystem::absolute(p.shown, ec);
    p.path = ec ? std::filesystem::path(p.shown) : abs.lexically_normal();
    return p;
}

void parse_bundle(const JsonReader& j, SceneDesc& s) {
    j.allow_only({"type", "name", "count", "radius", "tilt_deg", "seed", "bundle_radius", "length", "curve_basis"});
    BundleDesc& d = s.bundle;
    d.count = static_cast<std::uint32_t>(j.integer("count", d.count, 1, kMaxCount));
    d.bundle_radius = j.length("bundle_radius", d.bundle_radius);
    d.radius = j.length("radius", d.radius);
    if (!(d.radius < d.bundle_radius))
        j.fail("radius", "must be smaller than bundle_radius (" + describe(d.bundle_radius) + ")");
    d.tilt_deg = static_cast<float>(j.number("tilt_deg", d.tilt_deg, -360.0, 360.0));
    d.seed = static_cast<std::uint64_t>(j.integer("seed", 1, 0, std::numeric_limits<long long>::max()));
    d.length = j.length("length", d.length);
}

void parse_hair(const JsonReader& j, SceneDesc& s) {
    j.allow_only({"type", "name", "emitter", "sphere_radius", "sphere_center", "mesh", "lock_center",
                  "lock_radius", "lock_axis", "style", "strands", "points_per_strand", "length", "radius",
                  "tip_radius", "lean", "wave_amplitude", "waves", "curl_radius", "curl_turns", "seed",
                  "with_mesh", "curve_basis", "ribbons"});
    HairDesc& d = s.hair;
    s.ribbons = j.boolean("ribbons", false);
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
        if (std::abs(x) > JsonReader::kMaxLength) j.fail("sphere_center", std::string("components must lie within +-") + kMaxCoordinateText);
    d.lock_radius = j.length("lock_radius", d.lock_radius);
    d.lock_center = to_vec3(j.vec3("lock_center", std::array<double, 3>{0, 0, 0}));
    for (const float x : {d.lock_center.x, d.lock_center.y, d.lock_center.z})
        if (std::abs(x) > JsonReader::kMaxLength) j.fail("lock_center", std::string("components must lie within +-") + kMaxCoordinateText);
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
    if (d.emitter == HairEmitter::Mesh) s.hair_mesh = data_path(j, "mesh");
}

CurveFileDesc parse_curves(const JsonReader& c) {
    c.allow_only({"path", "format", "radius", "radius_scale", "follow_hairs", "follow_spread",
                  "follow_tip_separation", "follow_seed"});
    CurveFileDesc d;
    d.key = c.path();
    d.format = *curve_format_from_name(
        c.choice("format", "auto", {"auto", "hair", "tfx", "trk", "swc", "obj", "txt", "pbrt"}));
    d.path = data_path(c, "path");
    d.radius_scale = c.positive("radius_scale", 1.0);
    if (c.has("radius")) d.radius = c.length("radius", std::nullopt);
    d.follow.per_guide = static_cast<std::uint32_t>(c.integer("follow_hairs", 0, 0, 64));
    if (d.follow.per_guide > 0) {
        d.follow.spread = c.length("follow_spread", std::nullopt);
        d.follow.tip_separation = static_cast<float>(c.number("follow_tip_separation", 1.0, 0.0, 1e6));
        d.follow.seed = static_cast<std::uint64_t>(c.integer("follow_seed", 1, 0, std::numeric_limits<long long>::max()));
    } else {
        for (const char* key : {"follow_spread", "follow_tip_separation", "follow_seed"})
            if (c.has(key)) c.fail(key, "only with \"follow_hairs\" > 0");
    }
    return d;
}

void parse_file(const JsonReader& j, SceneDesc& s) {
    j.allow_only({"type", "name", "curves", "mesh", "curve_basis"});
    if (!j.has("curves") && !j.has("mesh")) j.fail("", "a file scene needs \"curves\", \"mesh\" or both");
    if (j.has("curves") && j.json()["curves"].is_array()) {
        // Several curve files (e.g. one SWC per neuron) form one scene.
        const nlohmann::json& list = j.json()["curves"];
        if (list.empty()) j.fail("curves", "expected a curve object or a non-empty list of them");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const JsonReader c(list[i], j.file(), j.key_path("curves") + "/" + std::to_string(i));
            c.require_object();
            s.curves.push_back(parse_curves(c));
        }
        s.curve_list = true;
    } else if (j.has("curves")) {
        s.curves.push_back(parse_curves(j.child("curves")));
    }
    if (j.has("mesh")) {
        const JsonReader m = j.child("mesh");
        m.allow_only({"path", "format"});
        MeshFileDesc mesh;
        mesh.format = *mesh_format_from_name(m.choice("format", "auto", {"auto", "obj", "gltf", "glb", "ply", "pbrt"}));
        mesh.path = data_path(m, "path");
        s.mesh = std::move(mesh);
    }
}

Strands load_curve_file(const SceneDesc& s, const CurveFileDesc& c, std::vector<std::string>& notes) {
    LoadedCurves loaded = load_curves(c.path.path, c.format, s.curve_basis);
    notes.insert(notes.end(), loaded.notes.begin(), loaded.notes.end());
    if (loaded.strands.strand_count() == 0) fail_at(s, c.path.key, "no strands in " + c.path.shown);
    if (c.radius) {
        loaded.strands.radii.assign(loaded.strands.radii.size(), *c.radius);
    } else if (!loaded.has_radius) {
        fail_at(s, c.key + "/radius", "missing: " + c.path.shown + " carries no radius, so one must be set");
    }
    for (float& r : loaded.strands.radii) {
        r = static_cast<float>(r * c.radius_scale);
        if (!(r <= JsonReader::kMaxLength))
            fail_at(s, c.key + "/radius_scale", describe(c.radius_scale) + " makes a radius exceed " + kMaxCoordinateText);
    }
    if (c.follow.per_guide > 0) return add_follow_hairs(loaded.strands, c.follow);
    return std::move(loaded.strands);
}

// A pbrt curve file (by name or extension; a bad extension fails when loaded).
bool is_pbrt(const CurveFileDesc& c) {
    try {
        return resolve_curve_format(c.path.path, c.format) == CurveFormat::Pbrt;
    } catch (const InputError&) {
        return false;
    }
}

void append_strands(Strands& into, const Strands& more) {
    const auto base = static_cast<std::uint32_t>(into.points.size());
    into.points.insert(into.points.end(), more.points.begin(), more.points.end());
    into.radii.insert(into.radii.end(), more.radii.begin(), more.radii.end());
    into.basis = more.basis;  // every file of a scene is read with the scene's basis
    for (std::size_t i = 1; i < more.offsets.size(); ++i) into.offsets.push_back(base + more.offsets[i]);
}

Scene file_scene(const SceneDesc& d) {
    Scene s;
    if (d.curve_list) {
        for (const CurveFileDesc& c : d.curves) append_strands(s.strands, load_curve_file(d, c, s.notes));
        s.name = d.key + "/curves";
    } else if (!d.curves.empty()) {
        s.strands = load_curve_file(d, d.curves.front(), s.notes);
        s.name = d.curves.front().path.shown;
    }
    if (d.mesh) {
        s.mesh = load_mesh(d.mesh->path.path, d.mesh->format, &s.notes);
        if (s.mesh.triangles.empty()) fail_at(d, d.mesh->path.key, "no faces in " + d.mesh->path.shown);
        if (s.name.empty()) s.name = d.mesh->path.shown;
    }
    // One file read as curves and as mesh says its notes once.
    std::vector<std::string> unique;
    for (std::string& n : s.notes)
        if (std::find(unique.begin(), unique.end(), n) == unique.end()) unique.push_back(std::move(n));
    s.notes = std::move(unique);
    return s;
}

}  // namespace

SceneDesc parse_scene(const JsonReader& j) {
    j.require_object();
    SceneDesc s;
    s.file = j.file();
    s.key = j.path();
    const std::string type = j.choice("type", std::nullopt, {"bundle", "hair", "file"});
    if (type == "bundle") {
        s.type = SceneType::Bundle;
        parse_bundle(j, s);
    } else if (type == "hair") {
        s.type = SceneType::Hair;
        parse_hair(j, s);
    } else {
        s.type = SceneType::File;
        parse_file(j, s);
    }
    if (j.has("name")) s.name = j.string("name", std::nullopt);
    if (j.has("curve_basis")) {
        s.curve_basis = *curve_basis_from_name(j.choice("curve_basis", std::nullopt, {"bspline", "bezier"}));
    } else if (!s.curves.empty() && std::all_of(s.curves.begin(), s.curves.end(), is_pbrt)) {
        s.curve_basis = CurveBasis::Bezier;
    }
    s.hair.basis = s.curve_basis;
    return s;
}

Scene load_scene(const SceneDesc& d) {
    Scene s;
    switch (d.type) {
        case SceneType::Bundle: s = make_bundle(d.bundle); break;
        case SceneType::Hair:
            if (!d.hair_mesh) {
                s = make_hair(d.hair);
            } else {
                const ObjContents obj = load_obj(d.hair_mesh->path);
                if (obj.mesh.triangles.empty()) fail_at(d, d.hair_mesh->key, "no faces in " + d.hair_mesh->shown);
                s = make_hair_on_mesh(d.hair, obj.mesh);
            }
            if (d.ribbons) {  // the strands become triangles; the scene keeps no curves
                append_ribbons(s.strands, d.hair.seed, s.mesh);
                s.strands = Strands{};
            }
            break;
        case SceneType::File: s = file_scene(d); break;
    }
    s.strands.basis = d.curve_basis;
    if (d.name) s.name = *d.name;
    return s;
}

Scene load_scene(const JsonReader& scene_block) { return load_scene(parse_scene(scene_block)); }

}  // namespace rtc
