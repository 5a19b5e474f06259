// The synthetic bundle, procedural hair, follow hairs and the sphere mesh.
#include "scenes/generators/bundle.h"
#include "scenes/generators/follow_hairs.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/generators/sphere_mesh.h"
#include "scenes/stats.h"

#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

TEST_CASE("scene bundle: lengths, radii, axes inside the bundle, tilt") {
    for (float tilt : {0.0f, 15.0f, 45.0f}) {
        CAPTURE(tilt);
        const BundleDesc d{1000, 0.002f, tilt, 42};
        const Scene sc = make_bundle(d);
        const Strands& s = sc.strands;
        REQUIRE(s.strand_count() == 1000);
        CHECK(s.segment_count() == 1000);
        const float a = tilt * 3.14159265f / 180.0f;
        const Vec3 axis_dir(-std::sin(a), std::cos(a), 0.0f);  // +Y rotated about +Z
        float max_dist = 0.0f;
        for (std::size_t i = 0; i < 1000; ++i) {
            const Vec3 p0 = s.points[2 * i], p1 = s.points[2 * i + 1];
            CHECK(glm::length(p1 - p0) == doctest::Approx(1.0f).epsilon(1e-5));
            CHECK(glm::length(glm::normalize(p1 - p0) - axis_dir) < 1e-5f);
            CHECK(s.radii[2 * i] == 0.002f);
            CHECK(s.radii[2 * i + 1] == 0.002f);
            // Centred at the origin along the axis; distance of the axis from the bundle's axis.
            const Vec3 mid = 0.5f * (p0 + p1);
            CHECK(std::abs(glm::dot(mid, axis_dir)) < 1e-5f);
            max_dist = std::max(max_dist, glm::length(mid));
        }
        CHECK(max_dist <= 0.5f - 0.002f + 1e-6f);
        CHECK(max_dist > 0.45f);  // uniform over the disk reaches near the rim
    }
    // Same seed, same bundle; another seed, another bundle.
    CHECK(make_bundle({10, 0.01f, 30.0f, 5}).strands.points == make_bundle({10, 0.01f, 30.0f, 5}).strands.points);
    CHECK(make_bundle({10, 0.01f, 30.0f, 5}).strands.points != make_bundle({10, 0.01f, 30.0f, 6}).strands.points);
    CHECK_THROWS_AS((void)make_bundle({0, 0.01f, 0.0f, 1}), std::invalid_argument);
    CHECK_THROWS_AS((void)make_bundle({1, 0.5f, 0.0f, 1}), std::invalid_argument);
}

TEST_CASE("scene bundle: uniform over the disk (inner half-radius disk holds ~1/4)") {
    const Scene sc = make_bundle({20000, 0.001f, 0.0f, 9});
    std::size_t inner = 0;
    for (std::size_t i = 0; i < 20000; ++i) {
        const Vec3 p = sc.strands.points[2 * i];
        inner += std::hypot(p.x, p.z) < 0.5f * (0.5f - 0.001f);
    }
    CHECK(static_cast<double>(inner) / 20000.0 == doctest::Approx(0.25).epsilon(0.05));
}

TEST_CASE("scene hair: roots on the sphere, counts, taper, styles") {
    for (HairStyle style : {HairStyle::Straight, HairStyle::Wavy, HairStyle::Curly}) {
        HairDesc d;
        d.style = style;
        d.strands = 500;
        d.points_per_strand = 12;
        d.length = 0.5f;
        d.radius = 0.01f;
        d.tip_radius = 0.002f;
        d.sphere_radius = 2.0f;
        d.with_mesh = true;
        const Scene sc = make_hair(d);
        const Strands& s = sc.strands;
        REQUIRE(s.strand_count() == 500);
        CHECK(s.segment_count() == 500 * 11);
        CHECK(sc.mesh.triangles.size() > 100);
        for (std::size_t i = 0; i < 500; ++i) {
            const Vec3 root = s.points[s.offsets[i]];
            CHECK(glm::length(root) == doctest::Approx(2.0f).epsilon(1e-5));
            CHECK(s.radii[s.offsets[i]] == doctest::Approx(0.01f));
            CHECK(s.radii[s.offsets[i + 1] - 1] == doctest::Approx(0.002f));
            // Tips stand outside the sphere, about `length` along the growth axis.
            const Vec3 tip = s.points[s.offsets[i + 1] - 1];
            CHECK(glm::length(tip) > 2.0f + 0.3f);
        }
        const SceneStats st = compute_stats(sc);
        if (style == HairStyle::Straight)
            CHECK(st.mean_segment_length == doctest::Approx(0.5 / 11).epsilon(1e-3));
        else  // waves and curls make strands longer than their axis
            CHECK(st.mean_segment_length > 0.5 / 11 * 1.05);
    }
}

// The generator's speed is not asserted here: a wall-time threshold fails on
// a loaded machine (it did, at 2.0 s, while a fuzz build ran); the time is
// printed for reading, and speed targets live in bench and bench_build.
TEST_CASE("scene hair: millions of segments, deterministic") {
    HairDesc d;
    d.style = HairStyle::Curly;
    d.strands = 250000;
    d.points_per_strand = 9;  // 2,000,000 segments
    const auto t0 = std::chrono::steady_clock::now();
    const Scene sc = make_hair(d);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(sc.strands.segment_count() == 2000000);
    MESSAGE("2M curly segments in " << seconds << " s");
    HairDesc small = d;
    small.strands = 100;
    CHECK(make_hair(small).strands.points == make_hair(small).strands.points);
}

namespace {

// Radius of the circle through three points.
float circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
    const float ab = glm::length(b - a), bc = glm::length(c - b), ca = glm::length(a - c);
    return ab * bc * ca / (2.0f * glm::length(glm::cross(b - a, c - a)));
}

}  // namespace

TEST_CASE("scene hair: curly lock: counts, determinism, curl radius and pitch as configured") {
    HairDesc d;
    d.emitter = HairEmitter::Lock;
    d.style = HairStyle::Curly;
    d.strands = 300;
    d.points_per_strand = 121;  // 120 segments, 12 turns: 10 points per turn
    d.length = 0.3f;
    d.curl_radius = 0.03f;      // 9 mm helix radius
    d.curl_turns = 12.0f;
    d.lock_center = Vec3(0.0f, 1.0f, 0.0f);
    d.lock_radius = 0.005f;
    d.lean = 0.0f;
    d.seed = 11;
    const Scene sc = make_hair(d);
    const Strands& s = sc.strands;
    REQUIRE(s.strand_count() == 300);
    CHECK(s.segment_count() == 300 * 120);
    CHECK(sc.mesh.triangles.empty());
    CHECK(sc.name == "procedural curly hair lock");
    // Deterministic for a seed; another seed, another lock.
    CHECK(make_hair(d).strands.points == s.points);
    HairDesc other = d;
    other.seed = 12;
    CHECK(make_hair(other).strands.points != s.points);
    const float helix = d.curl_radius * d.length;
    for (std::size_t i = 0; i < 300; ++i) {
        const std::uint32_t b = s.offsets[i];
        const Vec3 root = s.points[b];
        // Roots in the disk across the axis (-Y by default).
        CHECK(root.y == doctest::Approx(1.0f));
        CHECK(glm::length(Vec3(root.x, 0.0f, root.z)) <= d.lock_radius * 1.0001f);
        // The helix: every three consecutive points, seen down the axis, lie
        // on a circle of the configured radius; one turn drops length/turns.
        for (std::uint32_t k = 0; k + 2 < 121; k += 17) {
            auto across = [&](std::uint32_t j) { return Vec3(s.points[b + j].x, 0.0f, s.points[b + j].z); };
            CHECK(circumradius(across(k), across(k + 1), across(k + 2)) ==
                  doctest::Approx(helix).epsilon(1e-3));
        }
        CHECK(root.y - s.points[b + 10].y == doctest::Approx(d.length / d.curl_turns).epsilon(1e-4));
        // A ringlet: with no lean, every strand is its root plus the same curl.
        for (std::uint32_t k = 0; k < 121; k += 30)
            CHECK(glm::length((s.points[b + k] - root) - (s.points[k] - s.points[0])) < 1e-5f);
    }
    // Lean spreads the lock's strands but keeps them curling together.
    d.lean = 0.1f;
    const Strands leaning = make_hair(d).strands;
    CHECK(leaning.points != s.points);
    CHECK_THROWS_AS((void)make_hair([&] { HairDesc e = d; e.lock_radius = 0.0f; return e; }()),
                    std::invalid_argument);
    CHECK_THROWS_AS((void)make_hair([&] { HairDesc e = d; e.with_mesh = true; return e; }()),
                    std::invalid_argument);
}

TEST_CASE("scene hair: mesh emitter grows along triangle normals") {
    TriangleMesh plane;  // the square [0,1]^2 at z = 0, facing +z
    plane.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    plane.triangles = {{0, 1, 2}, {0, 2, 3}};
    HairDesc d;
    d.emitter = HairEmitter::Mesh;
    d.strands = 300;
    d.points_per_strand = 4;
    d.lean = 0.0f;
    d.with_mesh = true;
    const Scene sc = make_hair_on_mesh(d, plane);
    CHECK(sc.mesh.triangles.size() == 2);
    for (std::size_t i = 0; i < 300; ++i) {
        const Vec3 root = sc.strands.points[sc.strands.offsets[i]];
        const Vec3 tip = sc.strands.points[sc.strands.offsets[i + 1] - 1];
        CHECK(root.z == 0.0f);
        CHECK((root.x >= 0.0f && root.x <= 1.0f && root.y >= 0.0f && root.y <= 1.0f));
        CHECK(tip.z == doctest::Approx(d.length));
    }
}

TEST_CASE("scene sphere mesh: closed, outward-facing") {
    const TriangleMesh m = make_sphere_mesh(Vec3(1, 2, 3), 0.5f, 8, 12);
    CHECK(m.triangles.size() == 2 * 12 * (8 - 1));
    double volume = 0.0;  // divergence theorem: positive iff outward winding
    for (const auto& t : m.triangles) {
        const Vec3 a = m.vertices[t[0]] - Vec3(1, 2, 3), b = m.vertices[t[1]] - Vec3(1, 2, 3),
                   c = m.vertices[t[2]] - Vec3(1, 2, 3);
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    CHECK(volume > 0.9 * 4.0 / 3.0 * 3.14159 * 0.125);
    CHECK(volume < 4.0 / 3.0 * 3.14159 * 0.125);
}

TEST_CASE("scene follow hairs: copies around each guide, fanning out") {
    Strands g;
    g.points = {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 2, 0), Vec3(5, 0, 0), Vec3(5, 1, 0)};
    g.radii = {0.1f, 0.1f, 0.1f, 0.2f, 0.2f};
    g.offsets = {0, 3, 5};
    const Strands f = add_follow_hairs(g, {4, 0.05f, 1.0f, 3});
    REQUIRE(f.strand_count() == 10);
    CHECK(f.segment_count() == 5 * 2 + 5 * 1);
    CHECK(f.points[0] == g.points[0]);  // guide first
    for (std::size_t c = 1; c < 5; ++c) {
        const Vec3 root_offset = f.points[f.offsets[c]] - g.points[0];
        const Vec3 tip_offset = f.points[f.offsets[c] + 2] - g.points[2];
        CHECK(glm::length(root_offset) <= 0.05f + 1e-6f);
        CHECK(std::abs(root_offset.y) < 1e-6f);  // perpendicular to the first segment
        CHECK(glm::length(tip_offset) == doctest::Approx(2.0f * glm::length(root_offset)));
        CHECK(f.radii[f.offsets[c]] == 0.1f);
    }
    CHECK(add_follow_hairs(g, {}).points == g.points);
}

}  // namespace RTCSIM_TEST_FILE
