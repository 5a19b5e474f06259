// Tests of ray generation: the counter-based RNG, sampling warps, the pinhole
// camera and automatic framing.
#include "sim/workload/camera.h"
#include "sim/workload/rng.h"
#include "sim/workload/sampling.h"

#include "core/input_error.h"

#include <doctest/doctest.h>
#include <glm/trigonometric.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <set>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("workload rng: deterministic, distinct per counter, roughly uniform") {
    CHECK(uniform_float(7, 3, 4, 5, 6) == uniform_float(7, 3, 4, 5, 6));
    const SampleRng a(1, 10, 20, 0);
    CHECK(a.uniform(3) == SampleRng(1, 10, 20, 0).uniform(3));
    // Changing any one counter changes the value.
    const float base = uniform_float(1, 10, 20, 0, 3);
    CHECK(uniform_float(2, 10, 20, 0, 3) != base);
    CHECK(uniform_float(1, 11, 20, 0, 3) != base);
    CHECK(uniform_float(1, 10, 21, 0, 3) != base);
    CHECK(uniform_float(1, 10, 20, 1, 3) != base);
    CHECK(uniform_float(1, 10, 20, 0, 4) != base);
    // Swapping px and py is a different stream.
    CHECK(uniform_float(1, 20, 10, 0, 3) != base);

    // Histogram of 64k values over 16 bins, plus mean; all in [0, 1).
    constexpr int kBins = 16, kN = 1 << 16;
    std::array<int, kBins> bins{};
    double sum = 0.0;
    float lo = 1.0f, hi = 0.0f;
    std::set<float> distinct;
    for (int i = 0; i < kN; ++i) {
        const float u = uniform_float(42, static_cast<std::uint32_t>(i % 256),
                                      static_cast<std::uint32_t>(i / 256), 0, 0);
        lo = std::min(lo, u);
        hi = std::max(hi, u);
        sum += u;
        ++bins[static_cast<int>(u * kBins)];
        if (i < 1000) distinct.insert(u);
    }
    CHECK(lo >= 0.0f);
    CHECK(hi < 1.0f);
    CHECK(sum / kN == doctest::Approx(0.5).epsilon(0.01));
    for (int b : bins) CHECK(std::abs(b - kN / kBins) < 200);  // expected sd ~ 62
    CHECK(distinct.size() > 990);
    CHECK(to_unit_float(~0ull) < 1.0f);
}

TEST_CASE("workload sampling: pixel offsets stay in the pixel and fill the strata") {
    CHECK(pixel_offset(0, 1, 0.9f, 0.1f) == glm::vec2(0.5f, 0.5f));
    // spp 4: one sample per 2x2 stratum.
    std::set<std::pair<int, int>> strata;
    for (std::uint32_t s = 0; s < 4; ++s) {
        const glm::vec2 o = pixel_offset(s, 4, 0.3f, 0.7f);
        strata.insert({static_cast<int>(o.x * 2), static_cast<int>(o.y * 2)});
    }
    CHECK(strata.size() == 4);
    const glm::vec2 edge = pixel_offset(8, 9, 0x1.fffffep-1f, 0x1.fffffep-1f);
    CHECK(edge.x < 1.0f);
    CHECK(edge.y < 1.0f);
    // Sample beyond the k*k grid: uniform over the pixel.
    CHECK(pixel_offset(4, 5, 0.25f, 0.75f) == glm::vec2(0.25f, 0.75f));
}

TEST_CASE("workload sampling: cosine hemisphere is unit, upper and has E[cos] = 2/3") {
    const Vec3 n = glm::normalize(Vec3(0.3f, -0.8f, 0.5f));
    const Frame f = frame_around(n);
    CHECK(glm::dot(f.t, f.b) == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(glm::dot(f.t, n) == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(glm::length(f.t) == doctest::Approx(1.0f));
    double sum_cos = 0.0;
    constexpr int kN = 20000;
    for (int i = 0; i < kN; ++i) {
        const SampleRng rng(3, static_cast<std::uint32_t>(i), 0, 0);
        const Vec3 d = cosine_direction(n, rng.uniform(0), rng.uniform(1));
        REQUIRE(glm::length(d) == doctest::Approx(1.0f).epsilon(1e-5));
        REQUIRE(glm::dot(d, n) >= -1e-6f);
        sum_cos += glm::dot(d, n);
    }
    CHECK(sum_cos / kN == doctest::Approx(2.0 / 3.0).epsilon(0.01));
}

TEST_CASE("workload camera: spp 1 rays pass through pixel centres") {
    // 2x2 image, 90 degree fov, looking down -Z: the image plane at distance 1
    // spans [-1, 1]^2, so pixel centres are at (+-0.5, +-0.5, -1); row 0 is top.
    Camera c;
    c.position = Vec3(1.0f, 2.0f, 3.0f);
    c.target = Vec3(1.0f, 2.0f, 0.0f);
    c.up = Vec3(0.0f, 1.0f, 0.0f);
    c.fov_deg = 90.0f;
    c.width = 2;
    c.height = 2;
    const struct { std::uint32_t px, py; Vec3 through; } table[] = {
        {0, 0, {-0.5f, 0.5f, -1.0f}},
        {1, 0, {0.5f, 0.5f, -1.0f}},
        {0, 1, {-0.5f, -0.5f, -1.0f}},
        {1, 1, {0.5f, -0.5f, -1.0f}},
    };
    for (const auto& row : table) {
        const Ray r = primary_ray(c, row.px, row.py, 0, 1, 99);
        const Vec3 expect = glm::normalize(row.through);
        CHECK(r.origin == c.position);
        CHECK(r.tmin == 0.0f);
        CHECK(r.tmax == kInfinity);
        CHECK(r.direction.x == doctest::Approx(expect.x).epsilon(1e-6));
        CHECK(r.direction.y == doctest::Approx(expect.y).epsilon(1e-6));
        CHECK(r.direction.z == doctest::Approx(expect.z).epsilon(1e-6));
    }
    // Non-square: 4x2, fov 90 -> horizontal half-extent 2; pixel (3, 0) centre
    // at x = -2 + 3.5 = 1.5, y = 0.5.
    c.width = 4;
    const Ray r = primary_ray(c, 3, 0, 0, 1, 0);
    const Vec3 expect = glm::normalize(Vec3(1.5f, 0.5f, -1.0f));
    CHECK(r.direction.x == doctest::Approx(expect.x).epsilon(1e-6));
    CHECK(r.direction.y == doctest::Approx(expect.y).epsilon(1e-6));
}

TEST_CASE("workload camera: jittered samples stay in their pixel and are repeatable") {
    Camera c;
    c.position = Vec3(0.0f);
    c.target = Vec3(0.0f, 0.0f, -1.0f);
    c.fov_deg = 90.0f;
    c.width = 4;
    c.height = 4;
    // Pixel (1, 2) covers x in [-0.5, 0], y in [-0.5, 0] on the plane z = -1.
    bool any_off_centre = false;
    for (std::uint32_t s = 0; s < 16; ++s) {
        const Ray r = primary_ray(c, 1, 2, s, 16, 5);
        const Ray again = primary_ray(c, 1, 2, s, 16, 5);
        CHECK(r.direction == again.direction);
        const Vec3 p = r.direction / -r.direction.z;
        CHECK(p.x >= -0.5f);
        CHECK(p.x <= 0.0f);
        CHECK(p.y >= -0.5f);
        CHECK(p.y <= 0.0f);
        any_off_centre = any_off_centre || std::abs(p.x + 0.25f) > 1e-3f;
    }
    CHECK(any_off_centre);
    CHECK(primary_ray(c, 1, 2, 3, 16, 5).direction != primary_ray(c, 1, 2, 3, 16, 6).direction);
}

TEST_CASE("workload camera: frame_ray on lanes equals the glm reference bit for bit") {
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f), px(0.0f, 4000.0f);
    const auto same = [](const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        CameraFrame f{{u(gen), u(gen), u(gen)}, {u(gen), u(gen), u(gen)}, Vec3(u(gen)) * 1e-3f,
                      {u(gen) * 1e-3f, u(gen) * 1e-3f, u(gen) * 1e-3f}};
        if (i % 5 == 0) f.corner.x = 0.0f, f.right.x = -0.0f;  // signed zeros
        if (i % 7 == 0) f.down = Vec3(0.0f);
        const float x = i % 11 == 0 ? 0.0f : px(gen), y = px(gen);
        const Ray a = frame_ray(f, x, y), b = frame_ray_reference(f, x, y);
        CHECK(same(a.origin, b.origin));
        CHECK(same(a.direction, b.direction));
        CHECK(a.tmin == b.tmin);
        CHECK(a.tmax == b.tmax);
        ++checked;
    }
    // A zero direction normalizes to NaN either way (not the same NaN bits).
    const CameraFrame zero{Vec3(1.0f), Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};
    CHECK(std::isnan(frame_ray(zero, 1.0f, 1.0f).direction.x));
    CHECK(std::isnan(frame_ray_reference(zero, 1.0f, 1.0f).direction.x));
    CHECK(checked == 20000);
}

TEST_CASE("workload camera: auto_frame keeps every box corner in the image") {
    const Aabb box{Vec3(-3.0f, 1.0f, -0.5f), Vec3(5.0f, 2.0f, 0.5f)};
    const struct { int w, h; Vec3 from; } cases[] = {
        {800, 800, {0, 0, 1}}, {640, 360, {0, 0, 1}}, {200, 600, {1, 1, 1}}, {100, 100, {0, 1, 0}},
        {100, 100, {0, -1, 0}},
    };
    for (const auto& k : cases) {
        const Camera c = auto_frame(box, 40.0f, k.w, k.h, k.from);
        CHECK(glm::dot(glm::normalize(c.position - c.target), glm::normalize(k.from)) ==
              doctest::Approx(1.0f));
        const Vec3 w = glm::normalize(c.target - c.position);
        const Vec3 u = glm::normalize(glm::cross(w, c.up));
        const Vec3 v = glm::cross(u, w);
        const float half_h = std::tan(glm::radians(c.fov_deg) * 0.5f);
        const float half_w = half_h * static_cast<float>(k.w) / static_cast<float>(k.h);
        float max_fill = 0.0f;
        for (int i = 0; i < 8; ++i) {
            const Vec3 corner((i & 1) ? box.hi.x : box.lo.x, (i & 2) ? box.hi.y : box.lo.y,
                              (i & 4) ? box.hi.z : box.lo.z);
            const Vec3 d = corner - c.position;
            const float z = glm::dot(d, w);
            REQUIRE(z > 0.0f);
            const float x = glm::dot(d, u) / z / half_w, y = glm::dot(d, v) / z / half_h;
            CHECK(std::abs(x) < 1.0f);
            CHECK(std::abs(y) < 1.0f);
            max_fill = std::max({max_fill, std::abs(x), std::abs(y)});
        }
        CHECK(max_fill > 0.4f);  // the box fills a good part of the view
    }
    CHECK_THROWS_AS((void)auto_frame(Aabb{}, 40.0f, 10, 10), InputError);
    CHECK_THROWS_AS((void)auto_frame(box, 0.0f, 10, 10), InputError);
    Camera bad;
    bad.target = bad.position;
    CHECK_THROWS_AS((void)camera_frame(bad), InputError);
}

}  // namespace RTCSIM_TEST_FILE
