// Tests of the "workload" config section: defaults, every key, and errors
// that name the file and the JSON path of the offending value.
#include "sim/config/workload_config.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

WorkloadDesc parse(const std::string& text, const std::string& file = "x.json") {
    const nlohmann::json j = nlohmann::json::parse(text);
    return parse_workload(JsonReader(j.at("workload"), file, "/workload"));
}

std::string error_of(const std::string& text) {
    try {
        (void)parse(text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("workload config: defaults") {
    const WorkloadDesc d = parse(R"({"workload": {}})");
    CHECK(d.type == WorkloadType::Camera);
    CHECK(d.camera.automatic);
    CHECK(d.camera.fov_deg == 45.0f);
    CHECK(d.width == 800);
    CHECK(d.height == 800);
    CHECK(d.spp == 4);
    CHECK(d.bounces == 3);
    CHECK(d.seed == 0);
    CHECK(d.curve_albedo == Vec3(0.6f));
    CHECK(d.triangle_albedo == Vec3(0.8f));
    CHECK(d.environment.top == Vec3(1.0f));
    CHECK(d.environment.bottom == Vec3(1.0f));
    CHECK_FALSE(d.russian_roulette);
    const PathOptions o = path_options(d);
    CHECK(o.shading == Shading::Path);
    CHECK(o.bounces == 3);
    CHECK(o.spp == 4);
    // Auto camera frames the bounds from +Z.
    const Camera c = make_camera(d, Aabb{Vec3(-1.0f), Vec3(1.0f)});
    CHECK(c.position.z > 1.0f);
    CHECK(c.position.x == doctest::Approx(0.0f));
    CHECK(c.width == 800);
}

TEST_CASE("workload config: every key") {
    const WorkloadDesc d = parse(R"({"workload": {
        "type": "camera", "width": 64, "height": 32, "spp": 9, "bounces": 0, "seed": 4000000000,
        "camera": {"position": [0, 1, 5], "target": [0, 1, 0], "up": [0, 1, 0], "fov_deg": 30},
        "albedo": {"curves": [0.5, 0.4, 0.3], "triangles": 0.9},
        "environment": {"type": "gradient", "top": [0.5, 0.7, 1.0], "bottom": 0.1},
        "russian_roulette": true}})");
    CHECK(d.width == 64);
    CHECK(d.height == 32);
    CHECK(d.spp == 9);
    CHECK(d.bounces == 0);
    CHECK(d.seed == 4000000000u);
    CHECK_FALSE(d.camera.automatic);
    CHECK(d.camera.position == Vec3(0, 1, 5));
    CHECK(d.camera.fov_deg == 30.0f);
    CHECK(d.curve_albedo == Vec3(0.5f, 0.4f, 0.3f));
    CHECK(d.triangle_albedo == Vec3(0.9f));
    CHECK(d.environment.top == Vec3(0.5f, 0.7f, 1.0f));
    CHECK(d.environment.bottom == Vec3(0.1f));
    CHECK(d.russian_roulette);
    const Camera c = make_camera(d, Aabb{});  // explicit: bounds unused
    CHECK(c.position == Vec3(0, 1, 5));
    CHECK(c.width == 64);
}

TEST_CASE("workload config: primary, auto camera options, albedo and environment forms") {
    const WorkloadDesc p = parse(R"({"workload": {"type": "primary", "spp": 1,
        "camera": {"from": [1, 0, 0], "fov_deg": 60}, "environment": 0.25}})");
    CHECK(p.type == WorkloadType::Primary);
    CHECK(p.camera.automatic);
    CHECK(p.camera.from == Vec3(1, 0, 0));
    CHECK(p.environment.top == Vec3(0.25f));
    CHECK(p.environment.bottom == Vec3(0.25f));
    const PathOptions o = path_options(p);
    CHECK(o.shading == Shading::Primary);
    CHECK(o.bounces == 0);
    CHECK(make_camera(p, Aabb{Vec3(-1.0f), Vec3(1.0f)}).position.x > 1.0f);

    const WorkloadDesc a = parse(R"({"workload": {"camera": "auto", "albedo": [0.1, 0.2, 0.3],
        "environment": {"type": "constant", "radiance": [2, 2, 2]}}})");
    CHECK(a.curve_albedo == Vec3(0.1f, 0.2f, 0.3f));
    CHECK(a.triangle_albedo == Vec3(0.1f, 0.2f, 0.3f));
    CHECK(a.environment.top == Vec3(2.0f));
}

TEST_CASE("workload config: rays type resolves the file against the config directory") {
    const WorkloadDesc r =
        parse(R"({"workload": {"type": "rays", "rays_file": "data/a.rays"}})", "configs/runs/x.json");
    CHECK(r.type == WorkloadType::Rays);
    // Absolute, once: a run opens it from any working directory.
    CHECK(r.rays_file == (std::filesystem::current_path() / "configs/runs/data/a.rays").string());
    const WorkloadDesc abs =
        parse(R"({"workload": {"type": "rays", "rays_file": "/tmp/a.rays"}})", "configs/x.json");
    CHECK(abs.rays_file == "/tmp/a.rays");
}

TEST_CASE("workload config: errors name the file and JSON path") {
    const struct { const char* text; const char* expect; } cases[] = {
        {R"({"workload": {"spp": -4}})", "x.json: /workload/spp: expected a positive integer, got -4"},
        {R"({"workload": {"spp": 0}})", "x.json: /workload/spp: expected a positive integer"},
        {R"({"workload": {"width": 2.5}})", "x.json: /workload/width: expected an integer"},
        {R"({"workload": {"bounces": -1}})", "x.json: /workload/bounces: expected an integer in [0, 1000]"},
        {R"({"workload": {"sp": 4}})", "x.json: /workload/sp: unknown key"},
        {R"({"workload": {"type": "paths"}})", "x.json: /workload/type: expected one of camera, primary, rays"},
        {R"({"workload": {"camera": "front"}})", "x.json: /workload/camera: expected \"auto\" or an object"},
        {R"({"workload": {"camera": {"position": [0, 0, 1]}}})", "x.json: /workload/camera/target: missing"},
        {R"({"workload": {"camera": {"position": [0, 0, 1], "target": [0, 0, 0], "up": [0, 0, 2]}}})",
         "x.json: /workload/camera/up: must be non-zero and not parallel"},
        {R"({"workload": {"camera": {"target": [0, 0, 0]}}})", "x.json: /workload/camera/target: only with"},
        {R"({"workload": {"camera": {"fov_deg": 180}}})", "x.json: /workload/camera/fov_deg: expected a number in"},
        {R"({"workload": {"camera": {"from": [0, 0, 0]}}})", "x.json: /workload/camera/from: expected a non-zero"},
        {R"({"workload": {"camera": {"zoom": 2}}})", "x.json: /workload/camera/zoom: unknown key"},
        {R"({"workload": {"albedo": 1.5}})", "x.json: /workload/albedo: expected a number in [0.0, 1.0]"},
        {R"({"workload": {"albedo": {"hair": 0.5}}})", "x.json: /workload/albedo/hair: unknown key"},
        {R"({"workload": {"albedo": {"curves": [0.5, 2, 0.5]}}})", "x.json: /workload/albedo/curves: expected components in [0.0, 1.0]"},
        {R"({"workload": {"environment": {"type": "sun"}}})", "x.json: /workload/environment/type: expected one of constant, gradient"},
        {R"({"workload": {"environment": {"type": "constant", "top": 1}}})", "x.json: /workload/environment/top: unknown key"},
        {R"({"workload": {"environment": -1}})", "x.json: /workload/environment: expected a number in"},
        {R"({"workload": {"seed": 4294967296}})", "x.json: /workload/seed: expected an integer in [0, 4294967295]"},
        {R"({"workload": {"russian_roulette": 1}})", "x.json: /workload/russian_roulette: expected true or false"},
        {R"({"workload": {"type": "rays"}})", "x.json: /workload/rays_file: missing"},
        {R"({"workload": {"type": "rays", "rays_file": "a", "spp": 2}})", "x.json: /workload/spp: not used by workload type \"rays\""},
        {R"({"workload": {"type": "primary", "bounces": 2}})", "x.json: /workload/bounces: not used by workload type \"primary\""},
        {R"({"workload": {"rays_file": "a.rays"}})", "x.json: /workload/rays_file: only for workload type \"rays\""},
        {R"({"workload": []})", "x.json: /workload: expected an object"},
    };
    for (const auto& c : cases) {
        const std::string e = error_of(c.text);
        const std::string text = c.text;
        CAPTURE(text);
        CAPTURE(e);
        CHECK(e.rfind(c.expect, 0) == 0);
    }
}

}  // namespace RTCSIM_TEST_FILE
