// Every kind of bad input gives one InputError naming the file and where
// (byte offset or line): truncated files, wrong magic, counts that disagree
// with the size, non-numeric text, NaN, short strands, broken SWC trees.
// Binary cases are made here from a valid file by damaging it; text cases
// are the files in tests/fixtures/bad.
#include "core/input_error.h"
#include "scenes/export.h"
#include "scenes/loaders/loaders.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

const fs::path kBad = fs::path(RTCSIM_SOURCE_DIR) / "tests/fixtures/bad";

fs::path scratch_dir() {
    const fs::path dir = fs::path(RTCSIM_BINARY_DIR) / "test_scene_bad_input";
    fs::create_directories(dir);
    return dir;
}

using Bytes = std::vector<std::uint8_t>;

fs::path write_bytes(const std::string& name, const Bytes& b) {
    const fs::path p = scratch_dir() / name;
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()),
                                             static_cast<std::streamsize>(b.size()));
    return p;
}
Bytes read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}
template <class T>
void put(Bytes& b, std::size_t at, T v) {
    if (b.size() < at + sizeof(T)) b.resize(at + sizeof(T));
    std::memcpy(b.data() + at, &v, sizeof(T));
}

// Loads `file` with `load` and checks the one-line error names the file and `where`.
template <class Load>
void expect_input_error(Load&& load, const fs::path& file, const std::string& where,
                        const std::string& problem = "") {
    CAPTURE(file.string());
    try {
        (void)load(file);
        FAIL("no InputError");
    } catch (const InputError& e) {
        const std::string msg = e.what();
        CAPTURE(msg);
        CHECK(msg.rfind(file.string() + ": ", 0) == 0);
        CHECK(msg.find(where) != std::string::npos);
        CHECK(msg.find(problem) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

Strands two_strands() {
    Strands s;
    s.points = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};
    s.radii = {0.1f, 0.1f, 0.1f, 0.2f, 0.2f};
    s.offsets = {0, 3, 5};
    return s;
}

// TressFX 4 file: n strands of m float4 vertices from byte 160.
Bytes tfx4(std::uint32_t n, std::uint32_t m) {
    Bytes b(160, 0);
    put(b, 0, 4.0f);
    put(b, 4, n);
    put(b, 8, m);
    put(b, 12, std::uint32_t{160});
    for (std::uint32_t i = 0; i < n * m; ++i)
        for (int c = 0; c < 4; ++c) put(b, 160 + 16 * i + 4 * c, static_cast<float>(i + c));
    return b;
}
// TressFX 3 file: n strands of m float3 vertices from byte 296.
Bytes tfx3(std::uint32_t n, std::uint32_t m) {
    Bytes b(296, 0);
    put(b, 0, 3.0f);
    put(b, 4, n);
    put(b, 8, m);
    put(b, 144, std::uint32_t{296});
    for (std::uint32_t i = 0; i < n * m; ++i)
        for (int c = 0; c < 3; ++c) put(b, 296 + 12 * i + 4 * c, static_cast<float>(i + c));
    return b;
}
// TrackVis file with streamlines of the given point counts, one scalar per point.
Bytes trk(const std::vector<std::int32_t>& counts, std::int32_t n_count) {
    Bytes b(1000, 0);
    std::memcpy(b.data(), "TRACK", 6);
    put(b, 36, std::int16_t{1});
    put(b, 238, std::int16_t{1});
    put(b, 988, n_count);
    put(b, 992, std::int32_t{2});
    put(b, 996, std::int32_t{1000});
    for (std::int32_t m : counts) {
        const std::size_t at = b.size();
        put(b, at, m);
        for (std::int32_t j = 0; j < m; ++j)
            for (int c = 0; c < 4; ++c) put(b, at + 4 + 16 * j + 4 * c, static_cast<float>(j + c));
        put(b, b.size(), 7.0f);  // the property
    }
    return b;
}

}  // namespace

TEST_CASE("scene bad input: missing file") {
    expect_input_error(load_txt, kBad / "does_not_exist.txt", "cannot open");
    expect_input_error([](const fs::path& f) { return load_curves(f); }, kBad / "x.unknown", "extension");
}

TEST_CASE("scene bad input: HAIR") {
    const fs::path good = scratch_dir() / "good.hair";
    write_hair(two_strands(), good);
    const Bytes b = read_bytes(good);
    REQUIRE(load_hair(good).strands.segment_count() == 3);

    Bytes magic = b;
    magic[0] = 'X';
    expect_input_error(load_hair, write_bytes("magic.hair", magic), "byte 0", "magic");
    expect_input_error(load_hair, write_bytes("empty.hair", {}), "byte 0", "truncated");
    expect_input_error(load_hair, write_bytes("header.hair", Bytes(b.begin(), b.begin() + 100)),
                       "byte 0", "truncated");
    expect_input_error(load_hair, write_bytes("truncated.hair", Bytes(b.begin(), b.end() - 4)),
                       "byte 4", "need");
    Bytes count = b;
    put(count, 8, std::uint32_t{6});  // point count disagrees with the size
    expect_input_error(load_hair, write_bytes("count.hair", count), "byte 4", "need");
    Bytes segs = b;
    put(segs, 128, std::uint16_t{3});  // segment counts disagree with the points
    expect_input_error(load_hair, write_bytes("segs.hair", segs), "byte 128", "segment counts");
    Bytes nan = b;
    put(nan, 128 + 4 + 12 * 3 + 4, kNaN);  // y of point 3 (record at byte 168)
    expect_input_error(load_hair, write_bytes("nan.hair", nan), "byte 168", "non-finite");
    Strands one = two_strands();
    one.offsets = {0, 1, 5};  // a one-point strand
    write_hair(one, scratch_dir() / "one.hair");
    expect_input_error(load_hair, scratch_dir() / "one.hair", "byte", "strand 0 has 1 point");
}

TEST_CASE("scene bad input: TressFX 3 and 4") {
    REQUIRE(load_tfx(write_bytes("good4.tfx", tfx4(3, 4))).strands.segment_count() == 9);
    REQUIRE(load_tfx(write_bytes("good3.tfx", tfx3(3, 4))).strands.segment_count() == 9);
    Bytes version = tfx4(3, 4);
    put(version, 0, 7.5f);
    expect_input_error(load_tfx, write_bytes("version.tfx", version), "byte 0", "version");
    const Bytes t4 = tfx4(3, 4);
    expect_input_error(load_tfx, write_bytes("short4.tfx", Bytes(t4.begin(), t4.end() - 1)), "byte 4", "need");
    const Bytes t3 = tfx3(3, 4);
    expect_input_error(load_tfx, write_bytes("header3.tfx", Bytes(t3.begin(), t3.begin() + 200)),
                       "byte 0", "truncated");
    Bytes count = tfx3(3, 4);
    put(count, 4, std::uint32_t{4000000000u});  // absurd count, must not wrap or allocate
    expect_input_error(load_tfx, write_bytes("count3.tfx", count), "byte 4", "need");
    Bytes one = tfx4(3, 4);
    put(one, 8, std::uint32_t{1});
    expect_input_error(load_tfx, write_bytes("one.tfx", one), "byte 8", "at least 2");
    Bytes nan = tfx4(3, 4);
    put(nan, 160 + 16 * 5 + 8, kNaN);  // z of vertex 5
    expect_input_error(load_tfx, write_bytes("nan.tfx", nan), "byte 240", "non-finite");
    Bytes offset = tfx4(3, 4);
    put(offset, 12, std::uint32_t{8});
    expect_input_error(load_tfx, write_bytes("offset.tfx", offset), "byte 12", "inside the header");
}

TEST_CASE("scene bad input: TrackVis") {
    REQUIRE(load_trk(write_bytes("good.trk", trk({3, 2}, 2))).strands.segment_count() == 3);
    REQUIRE(load_trk(write_bytes("unknown_count.trk", trk({3, 2}, 0))).strands.segment_count() == 3);
    Bytes magic = trk({3, 2}, 2);
    magic[1] = 'X';
    expect_input_error(load_trk, write_bytes("magic.trk", magic), "byte 0", "magic");
    const Bytes good = trk({3, 2}, 2);
    expect_input_error(load_trk, write_bytes("cut.trk", Bytes(good.begin(), good.end() - 3)),
                       "byte 1060", "truncated");
    expect_input_error(load_trk, write_bytes("more.trk", trk({3, 2}, 1)), "byte 1056", "after the last");
    expect_input_error(load_trk, write_bytes("fewer.trk", trk({3, 2}, 3)), "byte 1096", "truncated");
    Bytes size = good;
    put(size, 996, std::int32_t{1001});
    expect_input_error(load_trk, write_bytes("size.trk", size), "byte 996", "header size");
    Bytes nan = good;
    put(nan, 1000 + 4 + 16, kNaN);  // x of point 1
    expect_input_error(load_trk, write_bytes("nan.trk", nan), "byte 1020", "non-finite");
    expect_input_error(load_trk, write_bytes("single.trk", trk({3, 1}, 2)), "byte 1056",
                       "strand 1 has 1 point");
    Bytes negative = good;
    put(negative, 1000, std::int32_t{-5});
    expect_input_error(load_trk, write_bytes("negative.trk", negative), "byte 1000", "negative");
}

TEST_CASE("scene bad input: SWC") {
    expect_input_error(load_swc, kBad / "swc_non_numeric.swc", "line 3", "\"zero\"");
    expect_input_error(load_swc, kBad / "swc_missing_parent.swc", "line 3", "does not exist");
    expect_input_error(load_swc, kBad / "swc_cycle.swc", "line 3", "cycle");
    expect_input_error(load_swc, kBad / "swc_nan.swc", "line 2", "non-finite");
    expect_input_error(load_swc, kBad / "swc_short_line.swc", "line 2", "7 fields");
    expect_input_error(load_swc, kBad / "swc_duplicate_id.swc", "line 2", "duplicate");
}

TEST_CASE("scene bad input: text curves") {
    expect_input_error(load_txt, kBad / "txt_non_numeric.txt", "line 5", "\"x\"");
    expect_input_error(load_txt, kBad / "txt_single_point.txt", "line 4", "1 point");
    expect_input_error(load_txt, kBad / "txt_nan.txt", "line 2", "non-finite");
    expect_input_error(load_txt, kBad / "txt_three_fields.txt", "line 2", "4 numbers");
    expect_input_error(load_txt, kBad / "txt_negative_radius.txt", "line 2", "radius");
}

TEST_CASE("scene bad input: OBJ") {
    expect_input_error(load_obj, kBad / "obj_bad_index.obj", "face 1", "does not exist");
    expect_input_error(load_obj, kBad / "obj_non_numeric.obj", "line 2", "\"abc\"");
    expect_input_error(load_obj, kBad / "obj_nan.obj", "line 2", "non-finite");
    expect_input_error(load_obj, kBad / "obj_single_point_line.obj", "polyline 1", "1 point");
}

}  // namespace RTCSIM_TEST_FILE
