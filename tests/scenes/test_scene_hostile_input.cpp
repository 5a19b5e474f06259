// The hostile inputs of issue 18, one test per class: files whose header
// counts would make a loader allocate gigabytes or wrap 64-bit sizes, OBJ
// statements that reach tinyobjloader's unchecked paths (`mtllib` to a
// device, `vw` with out-of-range numbers), directories given as files, and
// coordinates too large for float boxes. Each must be one InputError naming
// the file and where, thrown before any large allocation.
#include "core/input_error.h"
#include "scenes/loaders/loaders.h"

#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_scene_hostile_input";
    fs::create_directories(dir);
    return dir / name;
}

using Bytes = std::vector<std::uint8_t>;

fs::path write_bytes(const std::string& name, const Bytes& b) {
    const fs::path p = scratch(name);
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()),
                                             static_cast<std::streamsize>(b.size()));
    return p;
}
fs::path write_text(const std::string& name, const std::string& text) {
    const fs::path p = scratch(name);
    std::ofstream(p, std::ios::binary) << text;
    return p;
}
template <class T>
void put(Bytes& b, std::size_t at, T v) {
    if (b.size() < at + sizeof(T)) b.resize(at + sizeof(T));
    std::memcpy(b.data() + at, &v, sizeof(T));
}

std::string error_of(const std::function<void(const fs::path&)>& load, const fs::path& file) {
    try {
        load(file);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

void check_names(const std::string& msg, const fs::path& file, const std::string& where,
                 const std::string& problem) {
    CAPTURE(msg);
    CHECK(msg.rfind(file.string() + ": ", 0) == 0);
    CHECK(msg.find(where) != std::string::npos);
    CHECK(msg.find(problem) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
}

const auto kCurves = [](const fs::path& f) { (void)load_curves(f); };
const auto kObj = [](const fs::path& f) { (void)load_obj(f); };

}  // namespace

TEST_CASE("hostile input: HAIR header whose default segment count wraps to zero points") {
    // 2^32-1 strands of 2^32-1 default segments: in 32 bits each strand had
    // 1 + (2^32-1) = 0 points, the sum matched "0 points" and the loader
    // reserved 16 GiB of strand offsets.
    Bytes b(128, 0);
    std::memcpy(b.data(), "HAIR", 4);
    put(b, 4, std::uint32_t{0xFFFFFFFFu});
    put(b, 8, std::uint32_t{0});
    put(b, 12, std::uint32_t{2});  // points only
    put(b, 16, std::uint32_t{0xFFFFFFFFu});
    const fs::path f = write_bytes("wrap.hair", b);
    check_names(error_of(kCurves, f), f, "byte 16", "segment counts");
}

TEST_CASE("hostile input: TressFX counts whose byte size passes 2^64") {
    Bytes b(160, 0);
    put(b, 0, 4.0f);
    put(b, 4, std::uint32_t{0xFFFFFFFFu});
    put(b, 8, std::uint32_t{0xFFFFFFFFu});
    put(b, 12, std::uint32_t{160});
    const fs::path f = write_bytes("wrap.tfx", b);
    check_names(error_of(kCurves, f), f, "byte 4", "need");
}

TEST_CASE("hostile input: OBJ material libraries are never read") {
    // /dev/zero never ends; a directory or a missing file must not matter.
    const fs::path f = write_text("mtllib.obj",
                                  "mtllib /dev/zero\nmtllib ../\nmtllib missing.mtl\nusemtl skin\n"
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const ObjContents obj = load_obj(f);
    CHECK(obj.mesh.triangles.size() == 1);
}

TEST_CASE("hostile input: OBJ numbers out of range (vw, indices, coordinates)") {
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const fs::path vw = write_text("vw.obj", tri + "vw 0 5e55 1\nf 1 2 3\n");
    check_names(error_of(kObj, vw), vw, "line 4", "joint id");
    const fs::path vw_int = write_text("vw_int.obj", tri + "vw 99999999999 0 1\nf 1 2 3\n");
    check_names(error_of(kObj, vw_int), vw_int, "line 4", "out of range");
    const fs::path ok = write_text("vw_ok.obj", tri + "vw 0 1 0.5 2 0.5\nf 1 2 3\n");
    CHECK(load_obj(ok).mesh.triangles.size() == 1);

    const fs::path idx = write_text("index.obj", tri + "f 1 2 99999999999\n");
    check_names(error_of(kObj, idx), idx, "line 4", "vertex index");
    const fs::path rel = write_text("relative.obj", tri + "f -1 -2 -4\n");
    check_names(error_of(kObj, rel), rel, "line 4", "before the first vertex");
    const fs::path later = write_text("later.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\n");
    check_names(error_of(kObj, later), later, "line 2", "does not exist");
    const fs::path slashes = write_text("slashes.obj", tri + "vt 0 0\nvn 0 0 1\nf 1/1/1 2//1 -1/1\n");
    CHECK(load_obj(slashes).mesh.triangles.size() == 1);

    std::string big = tri + "f";
    for (int i = 0; i < 300; ++i) big += " 1";
    const fs::path wide = write_text("wide.obj", big + "\n");
    check_names(error_of(kObj, wide), wide, "line 4", "at most 255");

    const fs::path huge = write_text("huge.obj", "v 0 0 0\nv 3e38 0 0\nv 0 1 0\nf 1 2 3\n");
    check_names(error_of(kObj, huge), huge, "line 2", "beyond");
    const fs::path over = write_text("over.obj", "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n");
    check_names(error_of(kObj, over), over, "line 2", "1e400");
}

TEST_CASE("hostile input: curve coordinates and radii too large for float boxes") {
    const fs::path txt = write_text("huge.txt", "0 0 0 0.1\n1e30 0 0 0.1\n");
    check_names(error_of(kCurves, txt), txt, "line 2", "beyond");
    const fs::path radius = write_text("radius.txt", "0 0 0 1e30\n1 0 0 0.1\n");
    check_names(error_of(kCurves, radius), radius, "line 1", "bad radius");
}

TEST_CASE("hostile input: a directory given as a curve or mesh file") {
    const fs::path dir = scratch("a_directory.hair");
    fs::create_directories(dir);
    check_names(error_of(kCurves, dir), dir, "", "is a directory");
    const fs::path obj_dir = scratch("a_directory.obj");
    fs::create_directories(obj_dir);
    check_names(error_of(kObj, obj_dir), obj_dir, "", "is a directory");
    check_names(error_of([](const fs::path& f) { (void)load_trk(f); }, "/dev/null"), "/dev/null", "",
                "not a regular file");
}

}  // namespace RTCSIM_TEST_FILE
