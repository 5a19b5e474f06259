// Bad pbrt-v4, glTF and PLY input: one InputError naming the file and line
// (and the token), from the fixtures in tests/fixtures/bad and files written
// here; and the config's mesh `format` key.
#include "import_test_util.h"
#include "scenes/loaders/loaders.h"
#include "sim/config/scene_config.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::error_of;
using rtc::test::kImportFixtures;
using rtc::test::scratch_file;

namespace {

// The message starts with "<file>: line <n>: " and contains `part`.
void expect(const std::string& msg, const std::string& file_and_line, const std::string& part) {
    CAPTURE(msg);
    CHECK(msg.find(file_and_line + ": ") != std::string::npos);
    CHECK(msg.find(part) != std::string::npos);
}

// `name`: each test case its own file, as ctest runs cases in parallel processes.
std::string pbrt_error(const std::string& text, const std::string& name = "bad.pbrt") {
    const auto path = scratch_file(name, text);
    return error_of([&] { (void)load_pbrt(path); });
}

}  // namespace

TEST_CASE("pbrt import errors: the bad fixtures name file and line") {
    const auto bad = kImportFixtures / "bad";
    expect(error_of([&] { (void)load_pbrt(bad / "pbrt_unterminated.pbrt"); }), "pbrt_unterminated.pbrt: line 3",
           "unterminated string");
    expect(error_of([&] { (void)load_pbrt(bad / "pbrt_bad_param_type.pbrt"); }), "pbrt_bad_param_type.pbrt: line 3",
           "unknown parameter type \"float3\"");
    expect(error_of([&] { (void)load_pbrt(bad / "pbrt_missing_include.pbrt"); }), "pbrt_missing_include.pbrt: line 3",
           "no such file: \"no_such_file.pbrt\"");
    const std::string cycle = error_of([&] { (void)load_pbrt(bad / "pbrt_cycle_a.pbrt"); });
    expect(cycle, "pbrt_cycle_b.pbrt: line 3", "include cycle: ");
    CHECK(cycle.find("pbrt_cycle_a.pbrt -> ") != std::string::npos);
    expect(error_of([&] { (void)load_mesh(bad / "ply_bad_index.ply"); }), "ply_bad_index.ply: line 17",
           "face refers to vertex 7, the file has 5");
    // Through pbrt's plymesh, the pbrt line comes first.
    const auto ply = scratch_file("bad_ply.pbrt", "\n\nShape \"plymesh\" \"string filename\" \"" +
                                                      (bad / "ply_bad_index.ply").string() + "\"\n");
    expect(error_of([&] { (void)load_pbrt(ply); }), "bad_ply.pbrt: line 3", "ply_bad_index.ply: line 17");
}

TEST_CASE("pbrt import errors: syntax, parameters and structure") {
    expect(pbrt_error("Shape \"curve\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 4 0 0 ]\n"), "bad.pbrt: line 1",
           "5 points, a degree 3 Bezier curve needs 3n + 1");
    expect(pbrt_error("\nShape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ]\n"),
           "bad.pbrt: line 2", "needs normals");
    expect(pbrt_error("Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ]\n"
                      "  \"normal N\" [ 0 0 1 ]"),
           "bad.pbrt: line 2", "1 normals, need one per segment end (2)");
    CHECK(pbrt_error("Shape \"curve\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ] \"normal N\" [ 0 0 1 ]") ==
          "(no error)");  // N on a flat curve: ignored, as pbrt-v4 does
    expect(pbrt_error("Shape \"curve\" \"string basis\" \"hermite\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ]"),
           "bad.pbrt: line 1", "\"bezier\" or \"bspline\"");
    expect(pbrt_error("Shape \"curve\" \"integer degree\" 4 \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ]"),
           "bad.pbrt: line 1", "must be 2 or 3");
    expect(pbrt_error("Shape \"curve\" \"float P\" [ 0 0 0 ]"), "bad.pbrt: line 1", "must have type point3");
    expect(pbrt_error("Shape \"trianglemesh\"\n \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 3 ]"),
           "bad.pbrt: line 2", "index 3 out of range");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"integer indices\" [ 0 1 2.5 ]"),
           "bad.pbrt: line 1", "expected an integer");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 ]"), "bad.pbrt: line 1",
           "need a multiple of 3");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 nan 1 0 0 0 1 0 ]"), "bad.pbrt: line 1",
           "expected a finite number");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"point3 P\" [ 0 0 0 ]"),
           "bad.pbrt: line 1", "given twice");
    expect(pbrt_error("Shape \"teapot\"\n"), "bad.pbrt: line 1", "unknown shape \"teapot\"");
    expect(pbrt_error("WorldBegin\nMakeTeapot \"x\"\n"), "bad.pbrt: line 2", "unknown directive MakeTeapot");
    expect(pbrt_error("Translate 1 2\nWorldBegin\n"), "bad.pbrt: line 2", "expected a finite number for Translate");
    expect(pbrt_error("Transform 1 0 0 0  0 1 0 0  0 0 1 0  0 0 0 1\n"), "bad.pbrt: line 1", "expects [");
    expect(pbrt_error("[ 1 2 ]\n"), "bad.pbrt: line 1", "expected a directive, got [");
    expect(pbrt_error("\nAttributeBegin\nTranslate 1 0 0\n"), "bad.pbrt: line 2", "AttributeBegin never closed");
    expect(pbrt_error("AttributeBegin\nTransformEnd\n"), "bad.pbrt: line 2", "closes AttributeBegin");
    expect(pbrt_error("AttributeEnd\n"), "bad.pbrt: line 1", "without a matching AttributeBegin");
    expect(pbrt_error("\nObjectInstance \"nothing\"\n"), "bad.pbrt: line 2", "no object named \"nothing\"");
    expect(pbrt_error("ObjectBegin \"a\"\nObjectBegin \"b\"\n"), "bad.pbrt: line 2", "inside ObjectBegin");
    expect(pbrt_error("Rotate 30 0 0 0\n"), "bad.pbrt: line 1", "zero axis");
    expect(pbrt_error("Shape \"curve\" \"point3 P\" [ 0 0 0 1 0 0 2 0 0 3 0 0 ] \"float width\" -1"),
           "bad.pbrt: line 1", "a width must lie in [0, 1e12]");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ] \"bool x\" maybe"),
           "bad.pbrt: line 1", "expected true or false");
    expect(pbrt_error("Shape \"trianglemesh\" \"point3 P\" [ 0 0 0 1 0 0 0 1 0 ]\n\"string s\" [ \"a\" \n"),
           "bad.pbrt: line 3", "unexpected end of file");
    expect(pbrt_error("Shape \"x\\q\"\n"), "bad.pbrt: line 1", "unknown escape");
    expect(pbrt_error("Scale 1e30 1 1\nShape \"trianglemesh\" \"point3 P\" [ 1e-10 0 0 1e10 0 0 0 1 0 ]"),
           "bad.pbrt: line 2", "beyond +-1e12");
    expect(pbrt_error("\n\nInclude \"" + kImportFixtures.string() + "\"\n"), "bad.pbrt: line 3", "is a directory");
    // Including itself (the depth guard is the same path with a longer chain).
    expect(pbrt_error("\nInclude \"bad.pbrt\"\n"), "bad.pbrt: line 2", "include cycle");
    PbrtLimits shallow;
    shallow.max_include_depth = 1;
    const auto outer = scratch_file("outer.pbrt", "Include \"" + (kImportFixtures / "pbrt/curves.pbrt").string() + "\"\n");
    expect(error_of([&] { (void)load_pbrt(outer, shallow); }), "outer.pbrt: line 1", "nested deeper than 1");
}

TEST_CASE("mesh import errors: PLY headers and sizes, glTF, formats") {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    auto ply_error = [](const std::string& text) {
        const auto path = scratch_file("bad.ply", text);
        return error_of([&] { (void)load_assimp_mesh(path); });
    };
    CHECK(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n") == "(no error)");
    expect(ply_error(header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"), "bad.ply: line 14", "text after the last element");
    expect(ply_error(header + "0 0 0\n1 \v0 0\n0 1 0\n3 0 1 2\n"), "bad.ply: line 11", "unexpected character 11");
    expect(ply_error("plx\n"), "bad.ply: line 1", "not a PLY file");
    expect(ply_error(header + "0 0 0\n1 0 0 5\n0 1 0\n3 0 1 2\n"), "bad.ply: line 11", "expected 3 fields");
    expect(ply_error(header + "0 0 0\n1 0 x\n0 1 0\n3 0 1 2\n"), "bad.ply: line 11", "expected a number for z");
    expect(ply_error("ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0 0 0\n"),
           "bad.ply: line 3", "declares 1000000000 items");
    expect(ply_error("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                     "property float z\nend_header\n0123456789"),
           "bad.ply: line 3", "more than the 10 bytes");
    expect(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float z\nend_header\n0 0\n"),
           "bad.ply: line 3", "element vertex needs one scalar property y");
    expect(ply_error("ply\nformat ascii 1.0\n#element vertex 1\nend_header\n"), "bad.ply: line 3",
           "unexpected character 35 in the PLY header");
    expect(ply_error("ply\nformat ascii 1.0\nend_header\n"), "bad.ply", "no \"element vertex\" in the header");
    expect(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                     "end_header\n0 0 0\n"),
           "bad.ply", "no \"element face\" with a \"vertex_indices\" list");
    expect(ply_error("ply\nformat ascii 1.0\nformat binary_little_endian 1.0\nend_header\n"), "bad.ply: line 3",
           "a second \"format\" line");
    expect(ply_error(header.substr(0, header.size() - 11) + "element face 1\nend_header\n"), "bad.ply: line 9",
           "a second element \"face\"");
    expect(ply_error("ply\nformat ascii 2.0\nend_header\n"), "bad.ply: line 2", "expected \"format ascii");
    expect(ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n0\n"),
           "bad.ply: line 4", "unknown property type \"float128\"");

    // Not a JSON object / no magic: refused before assimp tries its other
    // readers (one read past this short buffer, found by the fuzz harness).
    const auto not_json = scratch_file("short.gltf", "metrict''''{\"a");
    expect(error_of([&] { (void)load_mesh(not_json); }), "short.gltf", "byte 0: a .gltf file must be a JSON object");
    const auto not_glb = scratch_file("short.glb", "  glTF");
    expect(error_of([&] { (void)load_mesh(not_glb); }), "short.glb", "byte 0: a .glb file must start with");
    // Only the start is read: the byte named is the first that is not a
    // byte-order mark or whitespace; a file with no object at all ends there.
    const auto spaced = scratch_file("spaced.gltf", "\xEF\xBB\xBF \r\n\t[]");
    expect(error_of([&] { (void)load_mesh(spaced); }), "spaced.gltf", "byte 7: a .gltf file must be a JSON object");
    const auto blank = scratch_file("blank.gltf", "   ");
    expect(error_of([&] { (void)load_mesh(blank); }), "blank.gltf", "byte 3: a .gltf file must be a JSON object");
    const auto half_mark = scratch_file("mark.gltf", "\xEF\xBB{");
    expect(error_of([&] { (void)load_mesh(half_mark); }), "mark.gltf", "byte 0: a .gltf file must be a JSON object");
    // The structure assimp relies on, checked first and named by JSON key
    // (assimp 5.2 crashed on a line-loop primitive with indices and no
    // POSITION, found by the fuzz harness).
    const auto no_prims = scratch_file("prims.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {\"primitives\": 7} ]}");
    expect(error_of([&] { (void)load_mesh(no_prims); }), "prims.gltf", "JSON key /meshes/0/primitives: expected an array");
    const auto no_position = scratch_file(
        "loop.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [{\"primitives\": [{\"attributes\": {}, "
                     "\"indices\": 0, \"mode\": 2}]}], \"accessors\": [{}]}");
    expect(error_of([&] { (void)load_mesh(no_position); }), "loop.gltf",
           "JSON key /meshes/0/primitives/0/attributes/POSITION: missing");
    const auto far_index = scratch_file(
        "far.gltf", "{\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 3}}]}], \"accessors\": [{}]}");
    expect(error_of([&] { (void)load_mesh(far_index); }), "far.gltf",
           "JSON key /meshes/0/primitives/0/attributes/POSITION: names accessors 3, the file has 1");
    expect(error_of([&] { (void)load_mesh(scratch_file("cut.gltf", "{\"meshes\": [")); }), "cut.gltf",
           "invalid JSON");
    expect(error_of([&] { (void)load_mesh(scratch_file("huge.gltf", "{\"scene\": 5E555550}")); }), "huge.gltf",
           "invalid JSON");
    expect(error_of([&] { (void)load_mesh(scratch_file("bin.glb", std::string("glTF\2\0\0\0\40\0\0\0\4\0\0\0BIN\0", 20))); }),
           "bin.glb", "byte 16: the first .glb chunk is not JSON");
    // What passes the check and assimp still refuses: its reason, after the file.
    const auto gltf = scratch_file(
        "bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [{\"primitives\": [{\"attributes\": "
                    "{\"POSITION\": 0}}]}], \"accessors\": [{\"bufferView\": 5, \"componentType\": 5126, "
                    "\"count\": 1, \"type\": \"VEC3\"}]}");
    const std::string g = error_of([&] { (void)load_mesh(gltf); });
    CHECK(g.rfind(gltf.string() + ": cannot read the mesh: ", 0) == 0);
    CHECK(g.size() > gltf.string().size() + 30);  // assimp's reason follows
    expect(error_of([&] { (void)load_assimp_mesh(kImportFixtures / "gltf/quad.gltf", 100); }), "quad.gltf",
           "more than the 100 a mesh may have");
    expect(error_of([&] { (void)load_mesh(scratch_file("x.stl", "solid")); }), "x.stl",
           "cannot tell the mesh format from the extension \".stl\"");
}

TEST_CASE("mesh import errors: glTF node hierarchies too deep, cyclic or shared (issue 56)") {
    // quad.gltf with its one node at the bottom of a chain of `levels` nodes
    // (node i's child is i + 1), or with `extra` spliced into the nodes.
    nlohmann::json quad = parse_json_text(read_text_file((kImportFixtures / "gltf/quad.gltf").string()), "quad");
    const auto chain = [&](int levels) {
        nlohmann::json j = quad;
        const nlohmann::json leaf = j["nodes"][0];
        j["nodes"] = nlohmann::json::array();
        for (int i = 0; i + 1 < levels; ++i) j["nodes"].push_back({{"children", {i + 1}}});
        j["nodes"].push_back(leaf);
        return j.dump();
    };
    // A million levels overflowed assimp's recursive node walk (SEGV).
    expect(error_of([&] { (void)load_mesh(scratch_file("deep.gltf", chain(1000000))); }), "deep.gltf",
           "JSON key /nodes/255/children: node hierarchy nested deeper than 256 levels");
    expect(error_of([&] { (void)load_mesh(scratch_file("deep257.gltf", chain(257))); }), "deep257.gltf",
           "nested deeper than 256 levels");
    CHECK(load_mesh(scratch_file("deep256.gltf", chain(256))).triangles.size() == 2);  // the limit itself loads
    const auto with_nodes = [&](const std::string& name, const nlohmann::json& nodes) {
        nlohmann::json j = quad;
        j["nodes"] = nodes;
        return scratch_file(name, j.dump());
    };
    const nlohmann::json mesh = quad["nodes"][0];
    expect(error_of([&] { (void)load_mesh(with_nodes("cycle.gltf", {{{"children", {1}}}, {{"children", {2}}},
                                                                     {{"children", {0}}}, mesh})); }),
           "cycle.gltf", "the hierarchy has a cycle");
    expect(error_of([&] { (void)load_mesh(with_nodes("self.gltf", {{{"children", {0}}}, mesh})); }), "self.gltf",
           "JSON key /nodes/0/children/0: a node cannot be its own child");
    expect(error_of([&] { (void)load_mesh(with_nodes("shared.gltf", {{{"children", {2}}}, {{"children", {2}}},
                                                                      mesh})); }),
           "shared.gltf", "JSON key /nodes/1/children/0: node 2 is already a child of node 0");
    expect(error_of([&] { (void)load_mesh(with_nodes("far_child.gltf", {{{"children", {9}}}, mesh})); }),
           "far_child.gltf", "JSON key /nodes/0/children/0: names nodes 9, the file has 2");
}

TEST_CASE("scene config: mesh and curve formats of the new importers") {
    const std::string config = (kImportFixtures / "run.json").string();
    auto load = [&](const nlohmann::json& j) { return load_scene(JsonReader(j, config, "/scene")); };
    const std::string pbrt = (kImportFixtures / "pbrt/scene.pbrt").string();
    const Scene s = load({{"type", "file"}, {"curves", {{"path", pbrt}, {"radius_scale", 2}}}, {"mesh", {{"path", pbrt}}}});
    CHECK(s.strands.points.size() == 14);
    CHECK(s.strands.radii[0] == doctest::Approx(0.2));
    CHECK(s.mesh.triangles.size() == 2);
    const Scene g = load({{"type", "file"},
                          {"curves", {{"path", pbrt}, {"format", "pbrt"}}},
                          {"mesh", {{"path", (kImportFixtures / "gltf/quad.gltf").string()}, {"format", "glb"}}}});
    CHECK(g.mesh.triangles.size() == 2);
    const std::string bad =
        error_of([&] { (void)load({{"type", "file"}, {"mesh", {{"path", pbrt}, {"format", "stl"}}}}); });
    CHECK(bad.find("/scene/mesh/format") != std::string::npos);
}

TEST_CASE("import: inputs the fuzzers found end as a mesh or an InputError") {
    // assimp 5.2's triangulation aborted on this PLY (an ai_assert): it is not run any more, and the
    // header (a vertex element without x) is refused first.
    const std::string ply = error_of([] { (void)load_mesh(kImportFixtures / "bad/ply_assimp_triangulate_assert.ply"); });
    expect(ply, "ply_assimp_triangulate_assert.ply: line 3", "element vertex needs one scalar property x");
    // assimp looped for ever on this one ('#' lines in the header; TextLines took them for comments).
    expect(error_of([] { (void)load_mesh(kImportFixtures / "bad/ply_assimp_hang.ply"); }), "ply_assimp_hang.ply: line 3",
           "unexpected character 35");
    // A file name longer than the file system allows made std::filesystem::exists throw.
    expect(pbrt_error("\nInclude \"" + std::string(5000, 'x') + "\"\n", "long_name.pbrt"), "long_name.pbrt: line 2",
           "no such file");
}

}  // namespace RTCSIM_TEST_FILE
