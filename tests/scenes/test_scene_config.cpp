// The scene block of a config: each type, path resolution, defaults, and the
// errors (unknown keys, bad values, missing radius) naming file and JSON path.
#include "scenes/stats.h"
#include "sim/util/json_file.h"
#include "sim/config/scene_config.h"
#include "model_data.h"

#include <doctest/doctest.h>

#include <filesystem>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using nlohmann::json;

namespace {
// A config that claims to live in the data root, so relative data paths
// resolve beside it.
const std::string kConfig = (test::model_data() / "run.json").string();
const std::filesystem::path kData = test::model_data();

Scene load(const json& j) { return load_scene(JsonReader(j, kConfig, "/scene")); }

std::string error_of(const json& j) {
    try {
        (void)load(j);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST_CASE("scene config: bundle with defaults and with every key") {
    const Scene d = load({{"type", "bundle"}});
    CHECK(d.strands.strand_count() == 1000);
    CHECK(d.strands.radii[0] == 0.002f);
    const Scene s = load({{"type", "bundle"}, {"count", 10}, {"radius", 0.01}, {"tilt_deg", 90},
                          {"seed", 3}, {"name", "b"}, {"bundle_radius", 2.0}, {"length", 4.0}});
    CHECK(s.name == "b");
    CHECK(s.strands.strand_count() == 10);
    CHECK(std::abs(s.strands.points[1].x - s.strands.points[0].x) == doctest::Approx(4.0f));  // tilted 90 deg
}

TEST_CASE("scene config: procedural hair") {
    const Scene s = load({{"type", "hair"}, {"style", "wavy"}, {"strands", 100}, {"points_per_strand", 5},
                          {"radius", 0.01}, {"tip_radius", 0.001}, {"with_mesh", true}});
    CHECK(s.strands.segment_count() == 400);
    CHECK(s.strands.radii[4] == doctest::Approx(0.001f));
    CHECK_FALSE(s.mesh.triangles.empty());
    if (!test::models_present({kData / "hair/sintel_head.obj"})) return;
    // Mesh emitter, mesh path relative to the config's directory.
    const Scene m = load({{"type", "hair"}, {"emitter", "mesh"}, {"mesh", "hair/sintel_head.obj"},
                          {"strands", 50}, {"with_mesh", true}});
    CHECK(m.strands.strand_count() == 50);
    CHECK(m.mesh.triangles.size() == 5952);
    // Lock emitter: roots in a disk around lock_center, growing along lock_axis.
    const Scene lock = load({{"type", "hair"}, {"emitter", "lock"}, {"style", "curly"}, {"strands", 20},
                             {"points_per_strand", 33}, {"lock_center", {1, 2, 3}}, {"lock_radius", 0.05},
                             {"lock_axis", {0, 0, 2}}, {"lean", 0}, {"length", 1}});
    CHECK(lock.strands.segment_count() == 20 * 32);
    CHECK(lock.mesh.triangles.empty());
    const Vec3 root = lock.strands.points[0], tip = lock.strands.points[32];
    CHECK(glm::length(Vec3(root.x, root.y, 0) - Vec3(1, 2, 0)) <= 0.05f + 1e-6f);
    CHECK(root.z == doctest::Approx(3.0f));
    CHECK(tip.z - root.z == doctest::Approx(1.0f).epsilon(1e-5));
}

TEST_CASE("scene config: the curly stand-ins of curly_table1.json have the paper's curve counts") {
    const std::string file = std::string(RTCSIM_SOURCE_DIR) + "/configs/runs/curly_table1.json";
    const json config = parse_json_text(read_text_file(file), file);
    const json& scenes = config.at("sweep").at("scene");
    REQUIRE(scenes.size() == 2);
    const std::size_t curves[] = {600000, 3300000};  // Wald et al. 2020: ~600 K, ~3.3 M cubics
    for (std::size_t i = 0; i < 2; ++i) {
        const Scene s = load_scene(JsonReader(scenes[i], file, "/sweep/scene/" + std::to_string(i)));
        CAPTURE(s.name);
        CHECK(s.strands.basis == CurveBasis::Bezier);
        CHECK(s.strands.segment_count() == 3 * curves[i]);  // capsules and links: three per cubic
        CHECK(s.mesh.triangles.empty());
        const SceneStats st = compute_stats(s);
        CHECK(st.curves == curves[i]);
        CHECK(st.mean_radius == doctest::Approx(3e-5).epsilon(1e-3));
        CHECK(st.mean_length_over_radius > 50.0);
    }
}

TEST_CASE("scene config: curve_basis, its defaults and its errors") {
    CHECK(load({{"type", "hair"}, {"strands", 3}}).strands.basis == CurveBasis::BSpline);
    const Scene bez = load({{"type", "hair"}, {"strands", 3}, {"points_per_strand", 7}, {"curve_basis", "bezier"}});
    CHECK(bez.strands.basis == CurveBasis::Bezier);
    CHECK(compute_stats(bez).curves == 3 * 2);
    CHECK(load({{"type", "bundle"}, {"count", 2}, {"curve_basis", "bezier"}}).strands.basis == CurveBasis::Bezier);
    // Files: polyline formats default to bspline, pbrt curves to bezier; the key overrides both.
    const std::string fixtures = std::string(RTCSIM_SOURCE_DIR) + "/tests/fixtures/";
    const json txt = {{"path", fixtures + "txt/two_strands.txt"}};
    const json pbrt = {{"path", fixtures + "pbrt/scene.pbrt"}};
    CHECK(load({{"type", "file"}, {"curves", txt}}).strands.basis == CurveBasis::BSpline);
    CHECK(load({{"type", "file"}, {"curves", txt}, {"curve_basis", "bezier"}}).strands.basis == CurveBasis::Bezier);
    CHECK(load({{"type", "file"}, {"curves", pbrt}}).strands.basis == CurveBasis::Bezier);
    CHECK(load({{"type", "file"}, {"curves", pbrt}, {"curve_basis", "bspline"}}).strands.basis == CurveBasis::BSpline);
    CHECK(load({{"type", "file"}, {"curves", json::array({pbrt, pbrt})}}).strands.basis == CurveBasis::Bezier);
    CHECK(load({{"type", "file"}, {"curves", json::array({pbrt, txt})}}).strands.basis == CurveBasis::BSpline);
    for (const json& type : {json("bundle"), json("hair")}) {
        const std::string e = error_of({{"type", type}, {"curve_basis", "catmull-rom"}});
        CAPTURE(e);
        CHECK(e.rfind(kConfig + ": /scene/curve_basis: ", 0) == 0);
        CHECK(e.find("bezier") != std::string::npos);
    }
    CHECK(error_of({{"type", "file"}, {"curves", txt}, {"curve_basis", 3}}).find("/scene/curve_basis") != std::string::npos);
}

TEST_CASE("scene config: files, radius set or scaled, follow hairs, hair with head") {
    if (!test::models_present({kData / "hair/sintel_hair_16pts.tfx", kData / "hair/sintel_head.obj",
                               kData / "hair/tressfx_bear.tfx", kData / "hair/fur_synthetic.hair"}))
        return;
    const Scene sintel = load({{"type", "file"},
                               {"curves", {{"path", "hair/sintel_hair_16pts.tfx"}, {"radius", 0.0001}}},
                               {"mesh", {{"path", "hair/sintel_head.obj"}}}});
    CHECK(sintel.strands.segment_count() == 171000);
    CHECK(sintel.strands.radii[17] == 0.0001f);
    CHECK(sintel.mesh.triangles.size() == 5952);

    const Scene bear = load({{"type", "file"},
                             {"curves", {{"path", "hair/tressfx_bear.tfx"}, {"radius", 0.05},
                                         {"follow_hairs", 4}, {"follow_spread", 0.5}}}});
    CHECK(bear.strands.strand_count() == 5 * 48113);
    CHECK(bear.strands.segment_count() == 5 * 144339);

    const Scene fur = load({{"type", "file"}, {"curves", {{"path", "hair/fur_synthetic.hair"}}}});
    const Scene fur2 = load({{"type", "file"}, {"curves", {{"path", "hair/fur_synthetic.hair"}, {"radius_scale", 2}}}});
    CHECK(fur2.strands.radii[5] == 2.0f * fur.strands.radii[5]);
    CHECK(fur.strands.radii[5] > 0.0f);
}

TEST_CASE("scene config: errors name the config file and the JSON path") {
    auto has = [](const std::string& msg, const std::string& part) {
        CAPTURE(msg);
        CHECK(msg.rfind(kConfig + ": ", 0) == 0);
        CHECK(msg.find(part) != std::string::npos);
    };
    has(error_of({{"type", "cube"}}), "/scene/type");
    has(error_of({{"count", 3}}), "/scene/type: missing");
    has(error_of({{"type", "bundle"}, {"cuont", 3}}), "/scene/cuont: unknown key");
    has(error_of({{"type", "bundle"}, {"radius", 0.6}}), "/scene/radius: must be smaller");
    has(error_of({{"type", "bundle"}, {"count", 0}}), "/scene/count");
    has(error_of({{"type", "hair"}, {"style", "frizzy"}}), "/scene/style");
    has(error_of({{"type", "hair"}, {"points_per_strand", 1}}), "/scene/points_per_strand");
    has(error_of({{"type", "hair"}, {"mesh", "x.obj"}}), "/scene/mesh: only with");
    has(error_of({{"type", "hair"}, {"lock_radius", 0.1}}), "/scene/lock_radius: only with \"emitter\": \"lock\"");
    has(error_of({{"type", "hair"}, {"emitter", "lock"}, {"sphere_radius", 1}}), "/scene/sphere_radius: only with");
    has(error_of({{"type", "hair"}, {"emitter", "lock"}, {"lock_axis", {0, 0, 0}}}), "/scene/lock_axis: must not be zero");
    has(error_of({{"type", "hair"}, {"emitter", "lock"}, {"lock_radius", 0}}), "/scene/lock_radius");
    has(error_of({{"type", "hair"}, {"emitter", "lock"}, {"with_mesh", true}}), "/scene/with_mesh: a lock has no");
    has(error_of({{"type", "file"}}), "/scene: a file scene needs");
    has(error_of({{"type", "file"}, {"curves", {{"path", "nope.hair"}}}}), "/scene/curves/path: no such file");
    if (!test::models_present({kData / "hair/tressfx_bear.tfx", kData / "hair/fur_synthetic.hair",
                               kData / "hair/sintel_head.obj"}))
        return;  // the rest reads real files
    has(error_of({{"type", "file"}, {"curves", {{"path", "hair/tressfx_bear.tfx"}}}}),
        "/scene/curves/radius: missing");
    has(error_of({{"type", "file"}, {"curves", {{"path", "hair/tressfx_bear.tfx"}, {"radius", -1}}}}),
        "/scene/curves/radius: expected a positive number");
    has(error_of({{"type", "file"}, {"curves", {{"path", "hair/fur_synthetic.hair"}, {"format", "abc"}}}}),
        "/scene/curves/format");
    has(error_of({{"type", "file"}, {"curves", {{"path", "hair/fur_synthetic.hair"}, {"follow_spread", 1}}}}),
        "/scene/curves/follow_spread: only with");
    has(error_of({{"type", "file"}, {"mesh", {{"path", "hair/sintel_head.obj"}, {"scale", 1}}}}),
        "/scene/mesh/scale: unknown key");
    // A data file error names the data file instead.
    const std::string wrong_format =
        error_of({{"type", "file"}, {"curves", {{"path", "hair/fur_synthetic.hair"}, {"format", "trk"}}}});
    CHECK(wrong_format.find("fur_synthetic.hair: byte 0: bad magic") != std::string::npos);
}

TEST_CASE("scene config: hair as ribbons is a triangle scene, two triangles per link and one at a pointed tip") {
    const json hair = {{"type", "hair"}, {"strands", 10}, {"points_per_strand", 4}, {"radius", 0.01}, {"seed", 3}};
    const Scene curves = load(hair);
    json as_ribbons = hair;
    as_ribbons["ribbons"] = true;
    const Scene ribbons = load(as_ribbons);
    CHECK(ribbons.strands.strand_count() == 0);
    CHECK(ribbons.mesh.triangles.size() == 10 * 3 * 2);
    CHECK(ribbons.mesh.vertices.size() == 10 * 4 * 2);
    // Each vertex lies a radius from its point of the same strands.
    for (std::size_t i = 0; i < curves.strands.points.size(); ++i)
        CHECK(glm::distance(ribbons.mesh.vertices[2 * i], curves.strands.points[i]) == doctest::Approx(0.01).epsilon(1e-4));
    as_ribbons["tip_radius"] = 0.0;
    CHECK(load(as_ribbons).mesh.triangles.size() == 10 * (2 * 2 + 1));
    as_ribbons["with_mesh"] = true;
    CHECK(load(as_ribbons).mesh.triangles.size() > 10 * (2 * 2 + 1));
}

}  // namespace RTCSIM_TEST_FILE
