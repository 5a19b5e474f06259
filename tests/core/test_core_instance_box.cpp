// The instance step on SIMD lanes (core/instance_box.h) against the scalar
// path it replaces: transform the ray with CentredAffine::point / vector,
// take safe_inverse, test the box with intersect_box; and object_ray() and
// the box test's own object ray against CentredAffine::ray. Results must be equal bit for
// bit, for ordinary rays and for the inputs where float rules bite: zero
// direction components of either sign (the +-1e30 mapping), axis-aligned and
// degenerate transforms, rays starting on a slab, infinite and NaN tmax.
#include "core/instance_box.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;

namespace {

float scalar_path(const CentredAffine& a, const Aabb& box, const Ray& r, float tmax) {
    return intersect_box(box, a.point(r.origin), safe_inverse(a.vector(r.direction)), r.tmin, tmax);
}

// Counts the cases compared and fails on the first that differs in any bit.
struct Compare {
    int compared = 0, hits = 0;
    void operator()(const CentredAffine& a, const Aabb& box, const Ray& r, float tmax) {
        const float want = scalar_path(a, box, r, tmax);
        ObjectRayParts entered{r.origin, r.direction};  // left alone on a miss
        const float got = intersect_instance_box(a, box, LaneRay(r), tmax, entered);
        // The object ray on the lanes against CentredAffine::ray, every float's bits.
        // NaNs only as NaNs: where two NaNs meet in a sum (0 * inf in one
        // term, a NaN input in another) the result's sign is the operand
        // order's, which the compiler may swap in either path (a + b as
        // b + a), so neither defines it; -O2 and -O3 builds differ there.
        Ray want_ray = a.ray(r);
        want_ray.tmax = tmax;
        const Ray got_ray = object_ray(a, LaneRay(r), tmax);
        const auto bits = [](const Ray& x) {
            std::array<std::uint32_t, 8> out{};
            const float f[8] = {x.origin.x,    x.origin.y,    x.origin.z,    x.tmin,
                                x.direction.x, x.direction.y, x.direction.z, x.tmax};
            for (int k = 0; k < 8; ++k)
                out[k] = std::isnan(f[k]) ? 0x7FC00000u : std::bit_cast<std::uint32_t>(f[k]);
            return out;
        };
        if (bits(got_ray) != bits(want_ray)) CHECK(bits(got_ray) == bits(want_ray));
        // The box test's own transform, as the one-leaf path takes it on an
        // entry; a miss leaves the ray alone.
        const Ray& box_want = got != kInfinity ? want_ray : r;
        const Ray box_ray{entered.origin, box_want.tmin, entered.direction, box_want.tmax};
        if (bits(box_ray) != bits(box_want)) CHECK(bits(box_ray) == bits(box_want));
        ++compared;
        if (want != kInfinity) ++hits;
        if (std::bit_cast<std::uint32_t>(want) != std::bit_cast<std::uint32_t>(got)) {
            INFO("origin " << r.origin.x << " " << r.origin.y << " " << r.origin.z << ", direction "
                           << r.direction.x << " " << r.direction.y << " " << r.direction.z << ", tmin "
                           << r.tmin << ", tmax " << tmax);
            CHECK(std::bit_cast<std::uint32_t>(got) == std::bit_cast<std::uint32_t>(want));
        }
    }
};

Affine random_affine(Rng& rng) {
    // Long thin OBB-like frames: a scaled rotation and an offset.
    const Vec3 x = rng.direction() * rng.uniform(0.01f, 2.0f);
    Vec3 y = glm::cross(x, rng.direction());
    if (glm::length(y) < 1e-3f) y = Vec3(0, 1, 0);
    y = glm::normalize(y) * rng.uniform(1e-4f, 0.1f);
    const Vec3 z = glm::normalize(glm::cross(x, y)) * rng.uniform(1e-4f, 0.1f);
    return Affine::from_columns(x, y, z, rng.point(-2.0f, 2.0f));
}

}  // namespace

TEST_CASE("instance box: lanes equal the scalar transform, safe_inverse and slab test bit for bit") {
    Rng rng(19);
    Compare cmp;
    const Aabb unit{Vec3(0.0f), Vec3(1.0f)};
    const Aabb centred{Vec3(-1.0f), Vec3(1.0f)};
    for (int i = 0; i < 20000; ++i) {
        const Affine world_from_object = random_affine(rng);
        const auto object_from_world = centred_inverse(world_from_object);
        REQUIRE(object_from_world);
        // Rays aimed near the box so that hits, misses and grazes all occur.
        const Vec3 target = world_from_object.point(rng.point(-0.2f, 1.2f));
        Ray r;
        r.origin = target - rng.direction() * rng.uniform(0.1f, 5.0f);
        r.direction = target - r.origin;
        r.tmin = (i % 7 == 0) ? rng.uniform(0.0f, 1.0f) : 0.0f;
        const float tmax = (i % 5 == 0) ? kInfinity : rng.uniform(0.2f, 3.0f);
        cmp(*object_from_world, (i & 1) ? unit : centred, r, tmax);
    }
    CHECK(cmp.hits > 2000);
    CHECK(cmp.hits < cmp.compared - 2000);
}

TEST_CASE("instance box: zeros of either sign, axis-aligned frames, infinities and NaN agree with the scalar path") {
    const Aabb unit{Vec3(0.0f), Vec3(1.0f)};
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 1e-38f, -1e-38f, 3e38f,
                             std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                             std::numeric_limits<float>::quiet_NaN()};
    const std::vector<Affine> frames{Affine{}, Affine::translate(Vec3(-0.5f, 0.0f, 2.0f)),
                                     Affine::scale(Vec3(2.0f, 0.5f, -1.0f)),
                                     Affine::from_columns(Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0.25f))};
    Compare cmp;
    for (const Affine& frame : frames)
        for (float dx : special)
            for (float dy : special)
                for (float dz : {0.0f, -0.0f, 1.0f, -1.0f}) {
                    Ray r;
                    r.origin = Vec3(0.5f, 0.0f, -1.0f);  // on the y = 0 slab
                    r.direction = Vec3(dx, dy, dz);
                    const CentredAffine a = *centred_inverse(frame);
                    for (float tmax : {kInfinity, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
                        cmp(a, unit, r, tmax);
                        r.origin = Vec3(-0.0f, 0.5f, 0.5f);
                        cmp(a, unit, r, tmax);
                        r.origin = Vec3(0.5f, 0.0f, -1.0f);
                    }
                }
    CHECK(cmp.compared == 4 * 11 * 11 * 4 * 3 * 2);
    CHECK(cmp.hits > 0);
}

}  // namespace RTCSIM_TEST_FILE
