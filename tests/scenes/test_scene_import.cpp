// Scene import: pbrt-v4 files (curves, meshes, includes, transforms,
// instances) and glTF / PLY meshes through assimp, against small fixtures
// whose contents are worked out by hand in their comments (tests/fixtures/
// pbrt, gltf, ply) or written here.
#include "import_test_util.h"
#include "scenes/convert.h"
#include "scenes/loaders/loaders.h"

#include <doctest/doctest.h>

#include <cmath>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::bounds_of;
using rtc::test::kImportFixtures;
using rtc::test::scratch_file;

namespace {
bool near(const Vec3& a, const Vec3& b, float eps = 1e-5f) { return glm::length(a - b) <= eps; }
}  // namespace

TEST_CASE("pbrt import: the fixture scene's curves, mesh, include and transforms") {
    const PbrtScene s = load_pbrt(kImportFixtures / "pbrt/scene.pbrt");
    CHECK(s.files == 2);  // scene.pbrt and the included curves.pbrt
    CHECK(s.curve_shapes == 2);
    CHECK(s.mesh_shapes == 1);
    REQUIRE(s.skipped_shapes.count("sphere") == 1);
    CHECK(s.skipped_shapes.at("sphere") == 1);
    // What the scene drops is said, not silently lost (issue 40).
    CHECK(s.camera == "perspective");
    CHECK(s.film_resolution == std::array<double, 2>{64, 64});
    REQUIRE(s.notes.size() == 3);
    const std::string file = (kImportFixtures / "pbrt/scene.pbrt").string();
    CHECK(s.notes[0] == file + ": 1 sphere shape skipped (only curves and triangle meshes are traced)");
    CHECK(s.notes[1] == file + ": Camera \"perspective\" ignored (the config's workload.camera places the camera)");
    CHECK(s.notes[2] == file + ": Film resolution 64 x 64 ignored (workload.width and workload.height set the image)");
    // Two cubic segments each, sampled at thirds: 7 points per strand.
    REQUIRE(s.curves.strand_count() == 2);
    CHECK(s.curves.offsets[1] == 7);
    CHECK(s.curves.points.size() == 14);
    CHECK(s.curves.segment_count() == 12);
    // Bezier tube: control points 0..6 on x, translated by 10: the samples are x = 10..16.
    for (std::size_t i = 0; i < 7; ++i) {
        CHECK(near(s.curves.points[i], Vec3(10.0f + static_cast<float>(i), 0, 0)));
        CHECK(s.curves.radii[i] == doctest::Approx(0.1));
    }
    // B-spline: from y = 2 to y = 4 at x = 10, radius 0.2 -> 0.1 along the curve.
    CHECK(near(s.curves.points[7], Vec3(10, 2, 0)));
    CHECK(near(s.curves.points[13], Vec3(10, 4, 0)));
    CHECK(s.curves.radii[7] == doctest::Approx(0.2));
    CHECK(s.curves.radii[13] == doctest::Approx(0.1));
    CHECK(s.curves.radii[10] == doctest::Approx(0.15));
    // The square under Scale 2.
    CHECK(s.mesh.triangles.size() == 2);
    const Aabb mb = bounds_of(s.mesh.vertices);
    CHECK(near(mb.lo, Vec3(-2, -2, 0)));
    CHECK(near(mb.hi, Vec3(2, 2, 0)));

    // Through the format dispatch: curves with radius, the mesh part.
    const LoadedCurves c = load_curves(kImportFixtures / "pbrt/scene.pbrt");
    CHECK(c.has_radius);
    CHECK(c.strands.points.size() == 14);
    CHECK(c.notes == s.notes);
    std::vector<std::string> notes;
    CHECK(load_mesh(kImportFixtures / "pbrt/scene.pbrt", MeshFormat::Auto, &notes).triangles.size() == 2);
    CHECK(notes == s.notes);
}

TEST_CASE("pbrt import: skipped shapes are counted by type, Film without a resolution has pbrt's default") {
    const auto path = scratch_file("skipped.pbrt",
                                   "Film \"rgb\"\nWorldBegin\nShape \"sphere\"\nShape \"disk\"\nShape \"sphere\"\n"
                                   "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\n");
    const PbrtScene s = load_pbrt(path);
    REQUIRE(s.notes.size() == 2);
    CHECK(s.notes[0] == path.string() + ": 1 disk, 2 sphere shapes skipped (only curves and triangle meshes are traced)");
    CHECK(s.notes[1].find(": Film resolution 1280 x 720 ignored") != std::string::npos);
    // A file that drops nothing says nothing.
    CHECK(load_pbrt(scratch_file("clean.pbrt", "Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] "
                                               "\"integer indices\" [0 1 2]\n")).notes.empty());
}

TEST_CASE("pbrt import: curve bases and degrees lie on pbrt's curve") {
    // A quadratic Bezier (0,0,0) (1,2,0) (2,0,0) peaks at (1,1,0) for t = 1/2;
    // a cubic B-spline segment is sampled where bspline::eval puts it.
    const auto path = scratch_file("bases.pbrt", R"(
Shape "curve" "integer degree" 2 "point3 P" [ 0 0 0  1 2 0  2 0 0 ] "string type" "cylinder"
Shape "curve" "string basis" "bspline" "point3 P" [ 0 0 0  1 3 0  2 -1 1  4 0 2 ]
Shape "curve" "string basis" "bspline" "integer degree" 2 "point3 P" [ 0 0 0  2 2 0  4 0 0 ]
Shape "curve" "string type" "ribbon" "point3 P" [ 0 0 0  1 0 0  2 0 0  3 0 0 ] "normal N" [ 0 0 1  0 0 1 ]
)");
    const PbrtScene s = load_pbrt(path, {}, CurveBasis::BSpline);  // samples on the curve
    CHECK(s.curves.basis == CurveBasis::BSpline);
    REQUIRE(s.curves.strand_count() == 4);
    CHECK(s.curves.offsets[1] == 3);
    CHECK(near(s.curves.points[1], Vec3(1, 1, 0)));
    const std::array<Vec3, 4> p{Vec3(0, 0, 0), Vec3(1, 3, 0), Vec3(2, -1, 1), Vec3(4, 0, 2)};
    for (int k = 0; k < 4; ++k) CHECK(near(s.curves.points[3 + k], bspline::eval(p, k / 3.0f), 1e-4f));
    // Quadratic B-spline: from the midpoint (1,1,0) to (3,1,0), through (2,1.5,0) at t = 1/2.
    CHECK(near(s.curves.points[7], Vec3(1, 1, 0)));
    CHECK(near(s.curves.points[8], Vec3(2, 1.5f, 0)));
    CHECK(near(s.curves.points[9], Vec3(3, 1, 0)));
    CHECK(s.curves.radii.back() == doctest::Approx(0.5));  // pbrt's default width 1

    // A curved cubic Bezier: its samples at t = 0, 1/3, 2/3, 1 are bspline::bezier_point's.
    const auto bent = scratch_file("bezier.pbrt", "Shape \"curve\" \"point3 P\" [ 0 0 0  1 3 0  3 -2 1  4 1 2 ]\n");
    const PbrtScene b = load_pbrt(bent, {}, CurveBasis::BSpline);
    PhantomCurve c;
    c.cp = {Vec3(0, 0, 0), Vec3(1, 3, 0), Vec3(3, -2, 1), Vec3(4, 1, 2)};
    REQUIRE(b.curves.points.size() == 4);
    for (int k = 0; k < 4; ++k) CHECK(near(b.curves.points[k], bspline::bezier_point(c, k / 3.0f), 1e-5f));
    CHECK(load_curves(bent, CurveFormat::Auto, CurveBasis::BSpline).strands.points == b.curves.points);
}

TEST_CASE("pbrt import: by default a curve's strand is its cubic Bezier control points, phantom curves are pbrt's") {
    const auto path = scratch_file("bezier_basis.pbrt", R"(
Shape "curve" "integer degree" 2 "point3 P" [ 0 0 0  1 2 0  2 0 0 ] "string type" "cylinder"
Shape "curve" "string basis" "bspline" "point3 P" [ 0 0 0  1 3 0  2 -1 1  4 0 2 ]
Shape "curve" "string basis" "bspline" "integer degree" 2 "point3 P" [ 0 0 0  2 2 0  4 0 0 ]
Shape "curve" "point3 P" [ 0 0 0  1 3 0  3 -2 1  4 1 2  5 4 2  6 0 0  7 0 1 ] "float width0" 2 "float width1" 0
)");
    const PbrtScene s = load_pbrt(path);
    CHECK(s.curves.basis == CurveBasis::Bezier);
    REQUIRE(s.curves.strand_count() == 4);
    CHECK(s.curves.offsets == std::vector<std::uint32_t>{0, 4, 8, 12, 19});
    // The quadratic, degree-elevated: (0,0,0) (2/3,4/3,0) (4/3,4/3,0) (2,0,0).
    CHECK(near(s.curves.points[1], Vec3(2.0f / 3, 4.0f / 3, 0)));
    CHECK(near(s.curves.points[2], Vec3(4.0f / 3, 4.0f / 3, 0)));
    // The cubic B-spline segment in Bezier form.
    const PhantomCurve bs = bspline::to_bezier({Vec3(0, 0, 0), Vec3(1, 3, 0), Vec3(2, -1, 1), Vec3(4, 0, 2)}, {});
    for (int k = 0; k < 4; ++k) CHECK(near(s.curves.points[4 + k], bs.cp[k]));
    // The quadratic B-spline: from (1,1,0) to (3,1,0) with (2,2,0) as its middle control point.
    CHECK(near(s.curves.points[8], Vec3(1, 1, 0)));
    CHECK(near(s.curves.points[9], Vec3(5.0f / 3, 5.0f / 3, 0)));
    CHECK(near(s.curves.points[11], Vec3(3, 1, 0)));
    // Two cubic Bezier segments: the file's seven control points as they are,
    // width 2 -> 0 linear along the curve: radius 1 - k/6 at control point k.
    for (int k = 0; k < 7; ++k) CHECK(s.curves.radii[12 + k] == doctest::Approx(1.0 - k / 6.0));
    CHECK(s.curves.points[15] == Vec3(4, 1, 2));
    // One phantom curve per cubic, exactly the file's; three capsules per cubic.
    const auto curves = std::get<std::vector<PhantomCurve>>(to_primitives(s.curves, PrimitiveKind::Phantom));
    REQUIRE(curves.size() == 5);
    CHECK(curves[3].cp == std::array<Vec3, 4>{Vec3(0, 0, 0), Vec3(1, 3, 0), Vec3(3, -2, 1), Vec3(4, 1, 2)});
    CHECK(curves[4].cp[0] == Vec3(4, 1, 2));
    CHECK(primitive_count(to_primitives(s.curves, PrimitiveKind::Capsule)) == 15);
    // Through the format dispatch, the pbrt default and the basis given.
    CHECK(load_curves(path).strands.basis == CurveBasis::Bezier);
    CHECK(load_curves(path).strands.points == s.curves.points);
    CHECK(load_curves(path, CurveFormat::Pbrt, CurveBasis::BSpline).strands.basis == CurveBasis::BSpline);
}

TEST_CASE("pbrt import: Rotate, Transform, ConcatTransform, Identity, stacks and widths") {
    const auto path = scratch_file("transforms.pbrt", R"(
WorldBegin
AttributeBegin
  Rotate 90 0 0 1
  Shape "trianglemesh" "point3 P" [ 1 0 0  0 0 0  0 0 1 ]
AttributeEnd
TransformBegin
  Transform [ 1 0 0 0  0 1 0 0  0 0 1 0  1 2 3 1 ]
  ConcatTransform [ 2 0 0 0  0 2 0 0  0 0 2 0  0 0 0 1 ]
  Shape "curve" "point3 P" [ 1 0 0  1 0 0  1 0 0  1 1 0 ] "float width" 0.5
  Identity
  Translate 0 0 7
  Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ]
TransformEnd
Shape "trianglemesh" "point3 P" [ 5 5 5  6 5 5  5 6 5 ]
)");
    const PbrtScene s = load_pbrt(path);
    REQUIRE(s.mesh.vertices.size() == 9);
    CHECK(near(s.mesh.vertices[0], Vec3(0, 1, 0)));      // (1,0,0) turned 90 degrees about z
    CHECK(near(s.mesh.vertices[3], Vec3(0, 0, 7)));      // Identity, then Translate
    CHECK(near(s.mesh.vertices[6], Vec3(5, 5, 5)));      // after TransformEnd: identity again
    // Scale 2 then translation (1,2,3): (1,0,0) -> (3,2,3); the width doubles.
    CHECK(near(s.curves.points[0], Vec3(3, 2, 3)));
    CHECK(near(s.curves.points.back(), Vec3(3, 4, 3)));
    CHECK(s.curves.radii[0] == doctest::Approx(0.5));
}

TEST_CASE("pbrt import: object instances are flattened, each with its transform") {
    const auto path = scratch_file("instances.pbrt", R"(
WorldBegin
ObjectBegin "strand"
  Translate 0 1 0
  Shape "curve" "point3 P" [ 0 0 0  0 0 1  0 0 2  0 0 3 ] "float width" 0.1
  Shape "trianglemesh" "point3 P" [ 0 0 0  1 0 0  0 1 0 ]
ObjectEnd
ObjectInstance "strand"
AttributeBegin
  Translate 10 0 0
  ObjectInstance "strand"
AttributeEnd
)");
    const PbrtScene s = load_pbrt(path);
    CHECK(s.curve_shapes == 2);
    CHECK(s.mesh_shapes == 2);
    REQUIRE(s.curves.strand_count() == 2);
    CHECK(near(s.curves.points[0], Vec3(0, 1, 0)));
    CHECK(near(s.curves.points[4], Vec3(10, 1, 0)));
    CHECK(s.mesh.triangles.size() == 2);
    CHECK(s.mesh.triangles[1][0] == 3);  // the second copy's own vertices
    CHECK(near(s.mesh.vertices[3], Vec3(10, 1, 0)));
    // The instance count is bounded: 2 copies x (4 points + 3 vertices + 1 triangle) = 16 elements.
    PbrtLimits tight;
    tight.max_elements = 15;
    CHECK(test::error_of([&] { (void)load_pbrt(path, tight); }).find("instances.pbrt: line 11: the scene grows past 15") !=
          std::string::npos);
}

TEST_CASE("pbrt import: plymesh relative to the pbrt file, under a transform") {
    const auto dir = kImportFixtures / "ply";
    const auto path = scratch_file("plymesh.pbrt", "Translate 0 0 1\nShape \"plymesh\" \"string filename\" \"" +
                                                       (dir / "pyramid.ply").string() + "\"\n");
    const PbrtScene s = load_pbrt(path);
    CHECK(s.mesh.triangles.size() == 3);
    const Aabb b = bounds_of(s.mesh.vertices);
    CHECK(near(b.lo, Vec3(0, 0, 1)));
    CHECK(near(b.hi, Vec3(1, 1, 3)));
}

TEST_CASE("mesh import: glTF with an embedded buffer and a node transform, ASCII PLY") {
    const TriangleMesh g = load_mesh(kImportFixtures / "gltf/quad.gltf");
    CHECK(g.triangles.size() == 2);
    const Aabb gb = bounds_of(g.vertices);
    CHECK(near(gb.lo, Vec3(-2, -1, 3)));  // node: scale (2,1,1), then translation (0,0,3)
    CHECK(near(gb.hi, Vec3(2, 1, 3)));
    CHECK(load_mesh(kImportFixtures / "gltf/quad.gltf", MeshFormat::Gltf).triangles.size() == 2);

    const TriangleMesh p = load_mesh(kImportFixtures / "ply/pyramid.ply");
    CHECK(p.triangles.size() == 3);  // the quad fan-triangulated, and one triangle
    const Aabb pb = bounds_of(p.vertices);
    CHECK(near(pb.lo, Vec3(0, 0, 0)));
    CHECK(near(pb.hi, Vec3(1, 1, 2)));
    CHECK(mesh_format_from_name("glb") == MeshFormat::Gltf);
    CHECK_FALSE(mesh_format_from_name("stl").has_value());
}

TEST_CASE("pbrt import: the fuzz seed with the other directives loads as pbrt-v4 reads it") {
    const PbrtScene s = load_pbrt(std::filesystem::path(RTCSIM_SOURCE_DIR) / "tests/fuzz/corpus/pbrt/instances.pbrt");
    CHECK(s.curve_shapes == 3);        // two instances of the object's curve, one ribbon
    CHECK(s.mesh.triangles.size() == 5);  // 2 x (one bilinear patch = 2 triangles) + the loopsubdiv control triangle
    CHECK(s.skipped_shapes.at("disk") == 1);
    // Quadratic B-spline of 4 points: 2 segments, each a cubic (3 control
    // links, the default Bezier basis), + 1; sampled (B-spline basis): 2 each, + 1.
    CHECK(s.curves.offsets[1] == 7);
    const PbrtScene sampled = load_pbrt(std::filesystem::path(RTCSIM_SOURCE_DIR) / "tests/fuzz/corpus/pbrt/instances.pbrt",
                                        {}, CurveBasis::BSpline);
    CHECK(sampled.curves.offsets[1] == 5);
    // `Translate` while only the end-time transform is active does not move the last shape.
    CHECK(near(s.mesh.vertices[s.mesh.vertices.size() - 3], Vec3(0, 0, 0)));
    // The ribbon under the tilted frame scaled by 2: width 1 -> radius 1.
    CHECK(s.curves.radii.back() == doctest::Approx(1.0));
}

TEST_CASE("mesh import: binary little-endian PLY, and a body shorter than its header says") {
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float xyz[9] = {0, 0, 0, 4, 0, 0, 0, 0, -3};
    ply.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const std::int32_t idx[3] = {0, 1, 2};
    ply += static_cast<char>(3);
    ply.append(reinterpret_cast<const char*>(idx), sizeof idx);
    const TriangleMesh m = load_mesh(scratch_file("binary.ply", ply));
    CHECK(m.triangles.size() == 1);
    const Aabb b = bounds_of(m.vertices);
    CHECK(near(b.lo, Vec3(0, 0, -3)));
    CHECK(near(b.hi, Vec3(4, 0, 0)));
    // Cut inside the face list: the header promises 36 + 1 + 4 bytes at least.
    const auto cut = scratch_file("binary_cut.ply", ply.substr(0, ply.size() - 13));
    CHECK(test::error_of([&] { (void)load_mesh(cut); }).find("binary_cut.ply: line 7: the elements up to face need") !=
          std::string::npos);
    // Cut inside the list (the walk reads its length), and an index past the vertices.
    const std::size_t list_at = ply.size() - 12;
    const auto cut_list = scratch_file("binary_cut_list.ply", ply.substr(0, ply.size() - 4));
    CHECK(test::error_of([&] { (void)load_mesh(cut_list); })
              .find("binary_cut_list.ply: byte " + std::to_string(list_at) + ": file truncated in element face item 0") !=
          std::string::npos);
    std::string bad_index = ply;
    bad_index[list_at + 8] = 3;
    CHECK(test::error_of([&] { (void)load_mesh(scratch_file("binary_index.ply", bad_index)); })
              .find("binary_index.ply: byte " + std::to_string(list_at + 8) + ": face 0 refers to vertex 3, the file has 3") !=
          std::string::npos);
}

}  // namespace RTCSIM_TEST_FILE
