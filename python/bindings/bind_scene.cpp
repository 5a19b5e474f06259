// Scenes from Python: the `scene` block of a config loaded exactly as a run
// loads it, with strands, radii and the mesh as NumPy views, and the
// primitives a run would build from them (one record per primitive, its
// source strand, AABB and OBB).
#include "common.h"

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "scenes/convert.h"
#include "scenes/stats.h"
#include "sim/config/scene_config.h"
#include "sim/run/area_stats.h"
#include "sim/util/json_file.h"

namespace rtc::py_bind {

namespace {

struct SceneHandle {
    std::shared_ptr<Scene> scene;
};

py::object f4() { return py::str("<f4"); }
py::object f4n(int n) { return py::make_tuple("<f4", n); }

// The structured dtype fields of each primitive kind.
std::vector<Field> fields_of(const std::vector<Cylinder>&) {
    return {{"p0", f4n(3), offsetof(Cylinder, p0)}, {"p1", f4n(3), offsetof(Cylinder, p1)},
            {"radius", f4(), offsetof(Cylinder, radius)}};
}
std::vector<Field> fields_of(const std::vector<Capsule>&) {
    return {{"p0", f4n(3), offsetof(Capsule, p0)}, {"p1", f4n(3), offsetof(Capsule, p1)},
            {"radius", f4(), offsetof(Capsule, radius)}};
}
std::vector<Field> fields_of(const std::vector<Link>&) {
    return {{"p0", f4n(3), offsetof(Link, p0)}, {"r0", f4(), offsetof(Link, r0)},
            {"p1", f4n(3), offsetof(Link, p1)}, {"r1", f4(), offsetof(Link, r1)}};
}
std::vector<Field> fields_of(const std::vector<PhantomCurve>&) {
    return {{"cp", py::make_tuple("<f4", py::make_tuple(4, 3)), offsetof(PhantomCurve, cp)},
            {"radius", f4n(4), offsetof(PhantomCurve, radius)}};
}

py::dict primitives(const SceneHandle& h, const std::string& kind_name, int subdivision, const std::string& obb) {
    const std::optional<PrimitiveKind> kind = kind_from_name(kind_name);
    if (!kind) throw std::invalid_argument("kind: expected cylinder, capsule, link or phantom, got " + kind_name);
    const std::optional<ObbVariant> variant = obb_variant_from_name(obb);
    if (!variant) throw std::invalid_argument("obb: expected paper or tight, got " + obb);
    auto prims = std::make_shared<PrimitiveArray>(to_primitives(h.scene->strands, *kind, subdivision));
    const std::size_t n = primitive_count(*prims);
    py::array_t<float> aabb({static_cast<py::ssize_t>(n), py::ssize_t{2}, py::ssize_t{3}});
    py::array_t<float> box({static_cast<py::ssize_t>(n), py::ssize_t{4}, py::ssize_t{3}});
    py::dict out;
    std::visit([&](const auto& v) {
        float* a = aabb.mutable_data();
        float* o = box.mutable_data();
        for (std::size_t i = 0; i < v.size(); ++i) {
            const Aabb b = bounds(v[i]);
            const Obb ob = oriented_bounds(v[i], *variant);
            const Vec3 rows[6] = {b.lo, b.hi, ob.half_axis(0), ob.half_axis(1), ob.half_axis(2), ob.center()};
            for (int k = 0; k < 3; ++k) {
                a[6 * i + k] = rows[0][k];
                a[6 * i + 3 + k] = rows[1][k];
                for (int r = 0; r < 4; ++r) o[12 * i + 3 * r + k] = rows[2 + r][k];
            }
        }
        using T = typename std::decay_t<decltype(v)>::value_type;
        out["data"] = record_view(v.data(), v.size(), sizeof(T), fields_of(v), keep_alive(prims));
    }, *prims);
    const std::vector<std::uint32_t> strands = primitive_strands(h.scene->strands, *kind, subdivision);
    out["kind"] = kind_name;
    out["strand"] = py::array_t<std::uint32_t>(static_cast<py::ssize_t>(strands.size()), strands.data());
    out["aabb"] = aabb;
    out["obb"] = box;
    const AreaStats areas = area_stats(*prims);
    out["areas"] = py::dict(py::arg("aabb") = areas.aabb, py::arg("obb_paper") = areas.obb_paper,
                            py::arg("obb_tight") = areas.obb_tight,
                            py::arg("aabb_over_obb_paper") = areas.ratio_paper(),
                            py::arg("aabb_over_obb_tight") = areas.ratio_tight());
    return out;
}

py::dict stats(const SceneHandle& h) {
    const SceneStats s = compute_stats(*h.scene);
    py::dict d;
    d["strands"] = s.strands;
    d["segments"] = s.segments;
    d["points"] = s.points;
    d["triangles"] = s.triangles;
    d["curve_basis"] = std::string(curve_basis_name(s.curve_basis));
    d["curves"] = s.curves;
    if (!s.bounds.empty())
        d["bounds"] = py::make_tuple(py::make_tuple(s.bounds.lo.x, s.bounds.lo.y, s.bounds.lo.z),
                                     py::make_tuple(s.bounds.hi.x, s.bounds.hi.y, s.bounds.hi.z));
    d["mean_segment_length"] = s.mean_segment_length;
    d["mean_radius"] = s.mean_radius;
    d["mean_length_over_radius"] = s.mean_length_over_radius;
    return d;
}

}  // namespace

void bind_scene(py::module_& m) {
    py::class_<SceneHandle>(m, "Scene", "Strands (polylines with a radius per point) and a triangle mesh.")
        .def_property_readonly("name", [](const SceneHandle& h) { return h.scene->name; })
        .def_property_readonly("points", [](const SceneHandle& h) {
            const auto& p = h.scene->strands.points;
            return view<float>(p.data(), {static_cast<py::ssize_t>(p.size()), 3}, keep_alive(h.scene));
        }, "Every strand point, strand after strand: (N, 3) float32.")
        .def_property_readonly("radii", [](const SceneHandle& h) {
            const auto& r = h.scene->strands.radii;
            return view<float>(r.data(), {static_cast<py::ssize_t>(r.size())}, keep_alive(h.scene));
        }, "One radius per point: (N,) float32.")
        .def_property_readonly("offsets", [](const SceneHandle& h) {
            const auto& o = h.scene->strands.offsets;
            return view<std::uint32_t>(o.data(), {static_cast<py::ssize_t>(o.size())}, keep_alive(h.scene));
        }, "Strand i is points[offsets[i]:offsets[i+1]]: (strands + 1,) uint32.")
        .def_property_readonly("vertices", [](const SceneHandle& h) {
            const auto& v = h.scene->mesh.vertices;
            return view<float>(v.data(), {static_cast<py::ssize_t>(v.size()), 3}, keep_alive(h.scene));
        }, "Mesh vertices: (V, 3) float32.")
        .def_property_readonly("triangles", [](const SceneHandle& h) {
            const auto& t = h.scene->mesh.triangles;
            return view<std::uint32_t>(t.data(), {static_cast<py::ssize_t>(t.size()), 3}, keep_alive(h.scene));
        }, "Mesh triangles as vertex indices: (T, 3) uint32.")
        .def_property_readonly("stats", &stats, "Counts, bounds and segment shape (report.json's scene block).")
        .def("primitives", &primitives, py::arg("kind") = "capsule", py::arg("subdivision") = 1,
             py::arg("obb") = "paper",
             "The primitives a run builds: dict with data (structured view), strand, aabb (N, 2, 3: lo, hi), "
             "obb (N, 4, 3: three half axes, centre) and the surface-area sums.");

    m.def("load_scene", [](const std::string& text, const std::string& file, const std::string& path) {
        const nlohmann::json block = parse_json_text(text, file);
        auto scene = std::make_shared<Scene>();
        {
            py::gil_scoped_release release;
            *scene = load_scene(JsonReader(block, file, path));
        }
        return SceneHandle{scene};
    }, py::arg("block"), py::arg("file"), py::arg("path") = "/scene",
          "Loads a `scene` block (JSON text); errors name `file` and `path`, data paths resolve beside `file`.");
    m.def("load_scene_file", [](const std::string& file) {
        // As the CLI reads a config: a missing file, a directory or bad JSON
        // is an InputError naming the file (and line).
        const nlohmann::json config = parse_json_text(read_text_file(file), file);
        const bool whole = config.is_object() && config.contains("scene");
        const nlohmann::json block = whole ? config["scene"] : config;
        auto scene = std::make_shared<Scene>();
        {
            py::gil_scoped_release release;
            *scene = load_scene(JsonReader(block, file, whole ? "/scene" : ""));
        }
        return SceneHandle{scene};
    }, py::arg("file"), "Loads the scene of a config file (its `scene` block), or a file holding a scene block.");
}

}  // namespace rtc::py_bind
