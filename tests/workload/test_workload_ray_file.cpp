// Tests of the binary ray and hit files: bit-exact round trips, and corrupt
// files rejected with the file name and the byte offset of the bad record.
#include "sim/workload/ray_file.h"

#include "core/input_error.h"

#include <doctest/doctest.h>

#include <bit>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

std::string temp_path(const std::string& name) {
    const auto dir = std::filesystem::path(RTCSIM_BINARY_DIR) / "test_tmp";
    std::filesystem::create_directories(dir);
    return (dir / ("workload_" + name)).string();
}

void write_floats(const std::string& path, const std::vector<float>& v, std::size_t extra = 0) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    for (float f : v) {
        const auto u = std::bit_cast<std::uint32_t>(f);
        for (int i = 0; i < 4; ++i) out.put(static_cast<char>(u >> (8 * i)));
    }
    for (std::size_t i = 0; i < extra; ++i) out.put('\0');
}

std::string error_of(const std::string& path) {
    try {
        (void)read_ray_file(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

bool same_bits(float a, float b) { return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b); }

}  // namespace

TEST_CASE("workload ray file: round trip is bit exact, little endian, streaming") {
    const std::string path = temp_path("round_trip.rays");
    const float tiny = std::numeric_limits<float>::denorm_min();
    const std::vector<Ray> rays = {
        {Vec3(1.0f, -2.5f, 3.25f), 0.0f, Vec3(0.0f, 0.0f, -1.0f), kInfinity},
        {Vec3(0.1f, 1e-30f, -7e20f), 0.5f, Vec3(3.0f, 4.0f, 0.0f), 10.0f},
        {Vec3(-0.0f, tiny, 0.3f), 2.0f, Vec3(-tiny, 0.0f, 1e-8f), 2.0f},
    };
    {
        RayFileWriter w(path);
        w.append(std::span(rays).first(1));
        w.append(std::span(rays).subspan(1));
        CHECK(w.rays_written() == 3);
        w.close();
    }
    CHECK(std::filesystem::file_size(path) == 3 * kRayRecordBytes);
    // First record's bytes: ox = 1.0f = 0x3F800000 little endian.
    std::ifstream in(path, std::ios::binary);
    unsigned char head[4];
    in.read(reinterpret_cast<char*>(head), 4);
    CHECK(head[0] == 0x00);
    CHECK(head[3] == 0x3F);

    const std::vector<Ray> back = read_ray_file(path);
    REQUIRE(back.size() == rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            CHECK(same_bits(back[i].origin[k], rays[i].origin[k]));
            CHECK(same_bits(back[i].direction[k], rays[i].direction[k]));
        }
        CHECK(same_bits(back[i].tmin, rays[i].tmin));
        CHECK(same_bits(back[i].tmax, rays[i].tmax));
    }
    CHECK(back[0].tmax == kInfinity);

    RayFileReader reader(path);
    CHECK(reader.ray_count() == 3);
    std::vector<Ray> batch(2);
    CHECK(reader.read(batch) == 2);
    CHECK(reader.read(batch) == 1);
    CHECK(batch[0].tmax == 2.0f);
    CHECK(reader.read(batch) == 0);

    write_ray_file(temp_path("empty.rays"), {});
    CHECK(read_ray_file(temp_path("empty.rays")).empty());
}

TEST_CASE("workload ray file: corrupt files name the file and byte offset") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> good = {0, 0, 0, 0, 0, 0, 1, kInfinity};
    auto with_second = [&](std::vector<float> second) {
        std::vector<float> v = good;
        v.insert(v.end(), second.begin(), second.end());
        return v;
    };
    const std::string path = temp_path("corrupt.rays");

    write_floats(path, good, 5);  // 37 bytes
    std::string e = error_of(path);
    CHECK(e.find(path) == 0);
    CHECK(e.find("size 37") != std::string::npos);
    CHECK(e.find("multiple of 32") != std::string::npos);
    CHECK(e.find("byte offset 32") != std::string::npos);

    const struct { std::vector<float> ray; const char* problem; } cases[] = {
        {{nan, 0, 0, 0, 0, 0, 1, 1}, "origin is not finite"},
        {{0, 0, kInfinity, 0, 0, 0, 1, 1}, "origin is not finite"},
        {{0, 0, 0, 0, 0, nan, 1, 1}, "direction is not finite"},
        {{0, 0, 0, 0, 0, 0, 0, 1}, "direction is zero"},
        {{0, 0, 0, 0, -0.0f, 0, -0.0f, 1}, "direction is zero"},
        {{0, 0, 0, 2, 0, 0, 1, 1}, "tmax must be >= tmin"},
        {{0, 0, 0, -1, 0, 0, 1, 1}, "tmin must be finite and >= 0"},
        {{0, 0, 0, 0, 0, 0, 1, nan}, "tmax must be >= tmin"},
    };
    for (const auto& c : cases) {
        write_floats(path, with_second(c.ray));
        e = error_of(path);
        CAPTURE(e);
        CHECK(e.find(path + ": byte offset 32 (ray 1): ") == 0);
        CHECK(e.find(c.problem) != std::string::npos);
    }
    e = error_of(temp_path("does_not_exist.rays"));
    CHECK(e.find("cannot open ray file") != std::string::npos);
    CHECK_THROWS_AS(RayFileWriter(temp_path("no_such_dir/x.rays")), InputError);
}

TEST_CASE("workload hit file: round trip and validation") {
    const std::string path = temp_path("round_trip.hits");
    TraceHit curve;
    curve.t = 1.5f;
    curve.prim = 42;
    curve.geom = GeometryId::Curves;
    TraceHit tri;
    tri.t = 0.0f;
    tri.prim = 0;
    tri.geom = GeometryId::Triangles;
    TraceHit miss;
    miss.prim = 9;  // junk on a miss is not written
    const std::vector<TraceHit> hits = {curve, miss, tri};
    {
        HitFileWriter w(path);
        w.append(std::span<const TraceHit>(hits));
        w.append(std::span<const FileHit>(std::vector<FileHit>{{3.0f, 7, GeometryId::Triangles}}));
        CHECK(w.hits_written() == 4);
        w.close();
    }
    CHECK(std::filesystem::file_size(path) == 4 * kHitRecordBytes);
    const std::vector<FileHit> back = read_hit_file(path);
    REQUIRE(back.size() == 4);
    CHECK(back[0] == FileHit{1.5f, 42, GeometryId::Curves});
    CHECK(back[1] == FileHit{});
    CHECK(back[1].t == kInfinity);
    CHECK(back[1].prim == 0xFFFFFFFFu);
    CHECK(back[2] == FileHit{0.0f, 0, GeometryId::Triangles});
    CHECK(back[3] == FileHit{3.0f, 7, GeometryId::Triangles});

    // Geometry id 2, a miss with a finite t, a hit without a primitive.
    const struct { FileHit bad; const char* problem; } cases[] = {
        {{1.0f, 3, static_cast<GeometryId>(2)}, "geometry id must be 0, 1 or 0xFFFFFFFF"},
        {{1.0f, kNoPrim, GeometryId::None}, "a miss"},
        {{1.0f, kNoPrim, GeometryId::Curves}, "must name a primitive"},
        {{-1.0f, 1, GeometryId::Curves}, "hit t must be finite"},
    };
    for (const auto& c : cases) {
        write_hit_file(path, std::vector<FileHit>{FileHit{}, c.bad});
        std::string e;
        try {
            (void)read_hit_file(path);
        } catch (const InputError& x) {
            e = x.what();
        }
        CAPTURE(e);
        CHECK(e.find(path + ": byte offset 12 (hit 1): ") == 0);
        CHECK(e.find(c.problem) != std::string::npos);
    }
    write_floats(path, {1.0f, 2.0f});  // 8 bytes
    CHECK_THROWS_WITH_AS((void)read_hit_file(path),
                         doctest::Contains("not a multiple of 12"), InputError);
}

TEST_CASE("workload ray file: a writer not closed (a failed run) leaves no file under the real name") {
    // Issue 56: a failed run's cut rays.bin stayed and replayed with exit 0.
    const std::string rays = temp_path("cut.rays"), hits = temp_path("cut.hits");
    std::filesystem::remove(rays);
    std::filesystem::remove(hits);
    {
        RayFileWriter w(rays);
        w.append(std::vector<Ray>(3, Ray{Vec3(0.0f), 0.0f, Vec3(0.0f, 0.0f, 1.0f), 1.0f}));
        HitFileWriter h(hits);
        h.append(std::span<const FileHit>(std::vector<FileHit>(2)));
    }  // destroyed as by an exception, without close()
    CHECK_FALSE(std::filesystem::exists(rays));
    CHECK_FALSE(std::filesystem::exists(rays + ".partial"));
    CHECK_FALSE(std::filesystem::exists(hits));
    CHECK_FALSE(std::filesystem::exists(hits + ".partial"));
    CHECK_THROWS_AS((void)read_ray_file(rays), InputError);
}

}  // namespace RTCSIM_TEST_FILE
