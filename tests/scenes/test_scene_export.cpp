// Export then re-import gives the same strands, bit for bit; and the scene
// statistics on a hand-computable scene.
#include "scenes/generators/bundle.h"
#include "scenes/export.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/loaders/loaders.h"
#include "scenes/stats.h"

#include "model_data.h"

#include <doctest/doctest.h>

#include <filesystem>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_scene_export";
    fs::create_directories(dir);
    return dir / name;
}
void check_same(const Strands& a, const Strands& b) {
    CHECK(a.offsets == b.offsets);
    CHECK(a.points == b.points);
    CHECK(a.radii == b.radii);
}
}  // namespace

TEST_CASE("scene export: text and HAIR round trips are exact") {
    HairDesc d;
    d.style = HairStyle::Curly;
    d.strands = 2000;
    d.points_per_strand = 7;
    d.radius = 0.013f;
    d.tip_radius = 0.0007f;
    d.seed = 99;
    const Strands s = make_hair(d).strands;
    write_txt(s, scratch("hair.txt"));
    write_hair(s, scratch("hair.hair"));
    const LoadedCurves txt = load_curves(scratch("hair.txt"));
    const LoadedCurves hair = load_curves(scratch("hair.hair"));
    check_same(s, txt.strands);
    check_same(s, hair.strands);
    CHECK(txt.has_radius);
    CHECK(hair.has_radius);
}

TEST_CASE("scene export: the real Sintel hair survives a text round trip") {
    const fs::path data = test::model_data() / "hair/sintel_hair_16pts.tfx";
    if (!test::models_present({data})) return;
    const Strands s = load_tfx(data).strands;
    write_txt(s, scratch("sintel.txt"));
    check_same(s, load_txt(scratch("sintel.txt")).strands);
}

TEST_CASE("scene stats: counts, bounds, means") {
    Scene sc;
    // Segments of length 1 and 2 with radii 0.1 / 0.3 (mean 0.2) and 0.5 / 0.5.
    sc.strands.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 5, 0), Vec3(0, 7, 0)};
    sc.strands.radii = {0.1f, 0.3f, 0.5f, 0.5f};
    sc.strands.offsets = {0, 2, 4};
    sc.mesh.vertices = {Vec3(-3, 0, 0), Vec3(0, 0, 4), Vec3(0, 1, 0)};
    sc.mesh.triangles = {{0, 1, 2}};
    const SceneStats st = compute_stats(sc);
    CHECK(st.strands == 2);
    CHECK(st.segments == 2);
    CHECK(st.points == 4);
    CHECK(st.triangles == 1);
    CHECK(st.mean_segment_length == doctest::Approx(1.5));
    CHECK(st.mean_radius == doctest::Approx(0.35));
    CHECK(st.mean_length_over_radius == doctest::Approx((1.0 / 0.2 + 2.0 / 0.5) / 2.0));
    CHECK(st.bounds.lo.x == -3.0f);                        // the mesh
    CHECK(st.bounds.lo.y == doctest::Approx(-0.3f));       // point (1,0,0) with r 0.3
    CHECK(st.bounds.lo.z == doctest::Approx(-0.5f));       // points with r 0.5
    CHECK(st.bounds.hi.y == doctest::Approx(7.5f));
    CHECK(st.bounds.hi.z == 4.0f);

    const SceneStats b = compute_stats(make_bundle({100, 0.01f, 0.0f, 1}));
    CHECK(b.mean_segment_length == doctest::Approx(1.0));
    CHECK(b.mean_length_over_radius == doctest::Approx(100.0));
}

}  // namespace RTCSIM_TEST_FILE
