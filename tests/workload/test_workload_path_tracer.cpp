// Tests of the path-tracing workload against analytic scenes traced by hand:
// furnace tests with closed-form radiance, ray counts, determinism.
#include "sim/workload/path_tracer.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// Closest hit of a ray with the sphere |p - c| = r, t > ray.tmin.
TraceHit hit_sphere(const Ray& ray, Vec3 c, float r, GeometryId geom) {
    const Vec3 oc = ray.origin - c;
    const double a = glm::dot(ray.direction, ray.direction);
    const double b = glm::dot(oc, ray.direction);
    const double cc = static_cast<double>(glm::dot(oc, oc)) - static_cast<double>(r) * r;
    const double disc = b * b - a * cc;
    TraceHit h;
    if (disc < 0.0) return h;
    const double s = std::sqrt(disc);
    for (double t : {(-b - s) / a, (-b + s) / a}) {
        if (t > ray.tmin && t <= ray.tmax) {
            h.t = static_cast<float>(t);
            h.normal = glm::normalize(ray.at(h.t) - c);
            h.prim = 7;
            h.geom = geom;
            return h;
        }
    }
    return h;
}

// Closest hit with the plane y = 0 (normal +Y).
TraceHit hit_ground(const Ray& ray) {
    TraceHit h;
    if (ray.direction.y == 0.0f) return h;
    const float t = -ray.origin.y / ray.direction.y;
    if (t > ray.tmin && t <= ray.tmax) {
        h.t = t;
        h.normal = Vec3(0.0f, 1.0f, 0.0f);
        h.prim = 0;
        h.geom = GeometryId::Triangles;
    }
    return h;
}

Camera small_camera(Vec3 position, Vec3 target, int size) {
    Camera c;
    c.position = position;
    c.target = target;
    c.up = std::abs(glm::normalize(target - position).y) > 0.9f ? Vec3(0, 0, -1) : Vec3(0, 1, 0);
    c.fov_deg = 40.0f;
    c.width = size;
    c.height = size;
    return c;
}

bool same_bits(const Ray& a, const Ray& b) { return std::memcmp(&a, &b, sizeof(Ray)) == 0; }

}  // namespace

TEST_CASE("workload path tracer: furnace, convex sphere under a constant sky") {
    // Every bounce off a convex object escapes to the sky, so a hit pixel
    // sees exactly albedo * sky and traces two rays; a miss sees the sky.
    const Camera cam = small_camera(Vec3(0, 0, 5), Vec3(0), 9);
    PathOptions opt;
    opt.spp = 2;
    opt.bounces = 3;
    opt.curve_albedo = Vec3(0.7f, 0.5f, 1.0f);
    opt.environment = Environment::constant(Vec3(1.0f));
    int hits = 0, misses = 0;
    for (std::uint32_t py = 0; py < 9; ++py)
        for (std::uint32_t px = 0; px < 9; ++px)
            for (std::uint32_t s = 0; s < opt.spp; ++s) {
                const PathSample p = trace_path(cam, px, py, s, opt, [](const Ray& r, std::uint32_t) {
                    return hit_sphere(r, Vec3(0), 1.0f, GeometryId::Curves);
                });
                if (p.primary.hit()) {
                    ++hits;
                    CHECK(p.rays == 2);
                    CHECK(p.radiance.x == doctest::Approx(0.7f).epsilon(1e-6));
                    CHECK(p.radiance.y == doctest::Approx(0.5f).epsilon(1e-6));
                    CHECK(p.radiance.z == doctest::Approx(1.0f).epsilon(1e-6));
                } else {
                    ++misses;
                    CHECK(p.rays == 1);
                    CHECK(p.radiance == Vec3(1.0f));
                }
            }
    CHECK(hits > 20);
    CHECK(misses > 20);
}

TEST_CASE("workload path tracer: gradient sky over a ground plane, E = albedo * 5/6") {
    // Sky radiance 0.5 (1 + cos theta) above a diffuse plane: with cosine
    // sampling E[cos theta] = 2/3, so the pixel value is albedo * 5/6.
    const Camera cam = small_camera(Vec3(0, 3, 0.01f), Vec3(0), 16);
    PathOptions opt;
    opt.spp = 16;
    opt.bounces = 2;
    opt.seed = 11;
    opt.triangle_albedo = Vec3(0.8f);
    opt.environment = {Vec3(1.0f), Vec3(0.0f)};
    double sum = 0.0;
    int n = 0;
    for (std::uint32_t py = 0; py < 16; ++py)
        for (std::uint32_t px = 0; px < 16; ++px)
            for (std::uint32_t s = 0; s < opt.spp; ++s) {
                const PathSample p = trace_path(cam, px, py, s, opt,
                                                [](const Ray& r, std::uint32_t) { return hit_ground(r); });
                REQUIRE(p.primary.hit());
                CHECK(p.rays == 2);
                sum += p.radiance.x;
                ++n;
            }
    CHECK(sum / n == doctest::Approx(0.8 * 5.0 / 6.0).epsilon(0.01));
}

TEST_CASE("workload path tracer: closed sphere from inside, 1 + bounces rays, deterministic") {
    const Camera cam = small_camera(Vec3(0.5f, -0.25f, 0.0f), Vec3(0, 0, -1), 4);
    for (std::uint32_t bounces : {0u, 1u, 3u, 6u}) {
        PathOptions opt;
        opt.bounces = bounces;
        opt.seed = 3;
        std::vector<Ray> first, second;
        std::vector<std::uint32_t> depths;
        auto run = [&](std::vector<Ray>& log) {
            std::uint32_t total = 0;
            for (std::uint32_t s = 0; s < opt.spp; ++s) {
                const PathSample p = trace_path(cam, 2, 1, s, opt, [&](const Ray& r, std::uint32_t d) {
                    log.push_back(r);
                    if (&log == &first) depths.push_back(d);
                    return hit_sphere(r, Vec3(0), 10.0f, GeometryId::Curves);
                });
                CHECK(p.rays == 1 + bounces);
                CHECK(p.radiance == Vec3(0.0f));  // no path escapes
                CHECK(p.primary.hit());
                total += p.rays;
            }
            return total;
        };
        CHECK(run(first) == opt.spp * (1 + bounces));
        run(second);
        REQUIRE(first.size() == second.size());
        for (std::size_t i = 0; i < first.size(); ++i) CHECK(same_bits(first[i], second[i]));
        for (std::size_t i = 0; i < depths.size(); ++i) CHECK(depths[i] == i % (1 + bounces));
        // Bounce rays leave from just inside the sphere (offset towards the
        // camera side), pointing inwards.
        for (std::size_t i = 0; i < first.size(); ++i) {
            if (depths[i] == 0) continue;
            CHECK(glm::length(first[i].origin) < 10.0f);
            CHECK(glm::length(first[i].origin) > 9.99f);
            CHECK(glm::dot(first[i].direction, first[i].origin) <= 0.0f);
        }
    }
}

TEST_CASE("workload path tracer: primary shading and russian roulette") {
    const Camera cam = small_camera(Vec3(0, 0, 5), Vec3(0), 5);
    PathOptions opt;
    opt.shading = Shading::Primary;
    opt.spp = 1;
    const PathSample centre = trace_path(cam, 2, 2, 0, opt, [](const Ray& r, std::uint32_t) {
        return hit_sphere(r, Vec3(0), 1.0f, GeometryId::Curves);
    });
    CHECK(centre.rays == 1);
    CHECK(centre.primary.t == doctest::Approx(4.0f));
    CHECK(centre.radiance.x == doctest::Approx(1.0f).epsilon(1e-5));  // head-on

    // With roulette on, paths inside a closed dark sphere end early sometimes,
    // never trace more than 1 + bounces rays, and are still repeatable.
    opt.shading = Shading::Path;
    opt.spp = 64;
    opt.bounces = 8;
    opt.russian_roulette = true;
    opt.curve_albedo = Vec3(0.3f);
    std::uint32_t total = 0, total_again = 0;
    for (std::uint32_t s = 0; s < opt.spp; ++s) {
        auto trace = [](const Ray& r, std::uint32_t) {
            return hit_sphere(r, Vec3(0), 10.0f, GeometryId::Curves);
        };
        const PathSample p = trace_path(cam, 1, 3, s, opt, trace);
        CHECK(p.rays <= 1 + opt.bounces);
        CHECK(p.rays >= opt.roulette_min_bounce);
        total += p.rays;
        total_again += trace_path(cam, 1, 3, s, opt, trace).rays;
    }
    CHECK(total < opt.spp * (1 + opt.bounces));
    CHECK(total == total_again);
}

}  // namespace RTCSIM_TEST_FILE
