// The loaders against the real models of the data root (counts from the
// .SOURCE.txt files of ../shared/data) and against tiny hand-made fixtures.
#include "scenes/loaders/loaders.h"
#include "model_data.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {
const std::filesystem::path kData = test::model_data();
const std::filesystem::path kFixtures = std::filesystem::path(RTCSIM_SOURCE_DIR) / "tests/fixtures";

bool all_radii(const Strands& s, float r) {
    for (float x : s.radii)
        if (x != r) return false;
    return true;
}
}  // namespace

TEST_CASE("scene loaders: Sintel hair (TressFX 4) and head (OBJ)") {
    if (!test::models_present({kData / "hair/sintel_hair_16pts.tfx", kData / "hair/sintel_head.obj"})) return;
    const LoadedCurves hair = load_curves(kData / "hair/sintel_hair_16pts.tfx");
    CHECK(hair.strands.strand_count() == 11400);
    CHECK(hair.strands.segment_count() == 171000);
    CHECK(hair.strands.points.size() == 182400);
    CHECK_FALSE(hair.has_radius);
    CHECK(all_radii(hair.strands, 0.0f));
    // First vertex, read by hand from the file bytes a97c29bd e66fc03f 839779bd.
    CHECK(hair.strands.points[0].x == doctest::Approx(-0.04138).epsilon(1e-3));
    CHECK(hair.strands.points[0].y == doctest::Approx(1.5034).epsilon(1e-3));
    const ObjContents head = load_obj(kData / "hair/sintel_head.obj");
    CHECK(head.mesh.triangles.size() == 5952);
    CHECK(head.mesh.vertices.size() == 3046);
    CHECK(head.lines.strand_count() == 0);
}

TEST_CASE("scene loaders: TressFX 3 bear guides") {
    if (!test::models_present({kData / "hair/tressfx_bear.tfx"})) return;
    const LoadedCurves bear = load_curves(kData / "hair/tressfx_bear.tfx", CurveFormat::Tfx);
    CHECK(bear.strands.strand_count() == 48113);
    CHECK(bear.strands.segment_count() == 144339);
}

TEST_CASE("scene loaders: HAIR fur with per-point thickness") {
    if (!test::models_present({kData / "hair/fur_synthetic.hair"})) return;
    const LoadedCurves fur = load_curves(kData / "hair/fur_synthetic.hair");
    CHECK(fur.strands.strand_count() == 50000);
    CHECK(fur.strands.segment_count() == 150000);
    CHECK(fur.has_radius);
    // Roots lie on the unit sphere (SOURCE.txt).
    const Vec3 root = fur.strands.points[0];
    CHECK(std::sqrt(root.x * root.x + root.y * root.y + root.z * root.z) ==
          doctest::Approx(1.0).epsilon(1e-4));
}

TEST_CASE("scene loaders: TrackVis stroke streamlines") {
    if (!test::models_present({kData / "streamlines/stroke.trk"})) return;
    const LoadedCurves trk = load_curves(kData / "streamlines/stroke.trk");
    CHECK(trk.strands.strand_count() == 36763);
    CHECK(trk.strands.segment_count() == 200705);
    CHECK(trk.strands.points.size() == 237468);
}

TEST_CASE("scene loaders: SWC neurons, one segment per parent-child pair") {
    if (!test::models_present({kData / "neurons/hemibrain_DA1_lPN"})) return;
    std::size_t total = 0;
    const std::pair<const char*, std::size_t> expected[] = {{"1734350788", 4464}, {"1734350908", 4846},
                                                            {"722817260", 4331}, {"754534424", 4695},
                                                            {"754538881", 4879}};
    for (const auto& neuron : expected) {  // no structured binding: CAPTURE's lambda cannot take one (clang 14)
        const char* const id = neuron.first;
        const std::size_t segments = neuron.second;
        CAPTURE(id);
        const LoadedCurves n = load_curves(kData / "neurons/hemibrain_DA1_lPN" / (std::string(id) + ".swc"));
        CHECK(n.strands.segment_count() == segments);
        CHECK(n.has_radius);
        total += n.strands.segment_count();
    }
    CHECK(total == 23215);
}

TEST_CASE("scene loaders: SWC fixture, branches become chains") {
    // Tree: 1-2-3, 2-4-5, 2-6, plus a second root 7-8, nodes listed out of order.
    const LoadedCurves t = load_swc(kFixtures / "swc/branchy.swc");
    CHECK(t.strands.segment_count() == 6);
    REQUIRE(t.strands.strand_count() == 4);
    // Chain 1: 1 2 3 (first child continues); then 2 4 5; 2 6; 7 8.
    const std::vector<std::uint32_t> offsets{0, 3, 6, 8, 10};
    CHECK(t.strands.offsets == offsets);
    CHECK(t.strands.points[3].x == 2.0f);  // chain 2 starts at the branch node 2
    CHECK(t.strands.radii[5] == 0.5f);     // node 5's own radius
}

TEST_CASE("scene loaders: text curves with comments and several blank lines") {
    const LoadedCurves t = load_txt(kFixtures / "txt/two_strands.txt");
    REQUIRE(t.strands.strand_count() == 2);
    CHECK(t.strands.segment_count() == 3);
    CHECK(t.strands.points[2] == Vec3(0, 2, 0));
    CHECK(t.strands.radii[4] == 0.25f);
}

TEST_CASE("scene loaders: OBJ fixture, quads fanned and polylines") {
    const ObjContents o = load_obj(kFixtures / "obj/quad_and_line.obj");
    REQUIRE(o.mesh.triangles.size() == 3);  // a quad (2) and a triangle (1)
    CHECK(o.mesh.triangles[1] == std::array<std::uint32_t, 3>{0, 2, 3});
    CHECK(o.lines.strand_count() == 1);
    CHECK(o.lines.segment_count() == 2);
    const LoadedCurves lines = load_curves(kFixtures / "obj/quad_and_line.obj");
    CHECK(lines.strands.segment_count() == 2);
}

}  // namespace RTCSIM_TEST_FILE
