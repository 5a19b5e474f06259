// End to end: `simulate` (in process, as tests/sim/test_simulate_e2e.cpp
// does) on the pbrt-v4 fixture's curves and mesh, and on its curves with the
// glTF mesh: both methods run, trace the same rays and agree on the hits.
#include "import_test_util.h"
#include "sim/app/run_all.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

nlohmann::json run_scene(const std::string& name, const nlohmann::json& scene) {
    const fs::path source(RTCSIM_SOURCE_DIR);
    const nlohmann::json config = {
        {"name", name},
        {"scene", scene},
        {"primitives", {{"kind", "capsule"}}},
        {"methods", {"ref", "obb"}},
        {"cost", {(source / "configs/hw/turing-per-ray-guess.json").string()}},
        {"memory", (source / "configs/hw/memory-optix7.json").string()},
        {"workload", {{"type", "camera"}, {"camera", "auto"}, {"width", 24}, {"height", 24}, {"spp", 1}, {"bounces", 1}}},
        {"output", {{"images", false}, {"rays", false}, {"hits", true}}}};
    const fs::path file = test::scratch_file(name + ".json", config.dump(1));
    const fs::path out = fs::path(RTCSIM_BINARY_DIR) / "e2e" / name;
    fs::remove_all(out);
    CliOptions cli;
    cli.config = file.string();
    cli.out = out.string();
    cli.quiet = true;
    cli.threads = 2;
    REQUIRE(run_all(cli) == 0);
    const nlohmann::json report = nlohmann::json::parse(read_text_file((out / "report.json").string()));
    CHECK(read_text_file((out / "hits_ref.bin").string()) == read_text_file((out / "hits_obb.bin").string()));
    return report;
}

}  // namespace

TEST_CASE("scene import e2e: simulate runs a pbrt-v4 scene and a glTF mesh") {
    const std::string pbrt = (test::kImportFixtures / "pbrt/scene.pbrt").string();
    const nlohmann::json a =
        run_scene("import_pbrt", {{"type", "file"},
                                  {"curves", {{"path", pbrt}, {"radius_scale", 5}}},  // thick enough to be hit
                                  {"mesh", {{"path", pbrt}}}});
    // 2 strands x 6 segments = 12 capsules; the 2 triangles of the square.
    CHECK(a["scene"]["primitives"] == 12);
    CHECK(a["scene"]["triangles"] == 2);
    CHECK(a["methods"]["obb"]["instances"] == 12 + 1);  // one per capsule, one for the mesh
    CHECK(a["methods"]["ref"]["events"]["is_call"]["total"].get<std::uint64_t>() > 0);
    CHECK(a["methods"]["ref"]["events"]["ray"]["total"] == a["methods"]["obb"]["events"]["ray"]["total"]);
    CHECK(a["methods"]["ref"]["events"]["ray"]["total"].get<std::uint64_t>() >= 24 * 24);
    // The sphere, camera and film resolution it drops, once although the
    // file is read as curves and as mesh.
    REQUIRE(a["scene"]["notes"].size() == 3);
    CHECK(a["scene"]["notes"][0].get<std::string>().ends_with("scene.pbrt: 1 sphere shape skipped (only curves and "
                                                              "triangle meshes are traced)"));

    const nlohmann::json b = run_scene(
        "import_gltf", {{"type", "file"},
                        {"curves", {{"path", pbrt}, {"radius_scale", 5}}},
                        {"mesh", {{"path", (test::kImportFixtures / "gltf/quad.gltf").string()}}}});
    CHECK(b["scene"]["primitives"] == 12);
    CHECK(b["scene"]["triangles"] == 2);
    CHECK(b["scene"]["notes"].size() == 3);  // the pbrt curves file's
}

}  // namespace RTCSIM_TEST_FILE
