// Two levels: instancing with random affine transforms against the same
// scene flattened into world space.
#include "core/two_level.h"
#include "core_test_util.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <mutex>
#include <random>
#include <stdexcept>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using rtc::test::Rng;
using rtc::test::Tri;

namespace {

Affine random_affine(Rng& rng) {
    // Rotation (from a random orthonormal frame) * non-uniform scale, then translation.
    const Vec3 a = rng.direction();
    Vec3 b = glm::normalize(glm::cross(a, rng.direction()));
    const Vec3 c = glm::cross(a, b);
    const Vec3 s{rng.uniform(0.2f, 2.0f), rng.uniform(0.2f, 2.0f), rng.uniform(0.2f, 2.0f)};
    return Affine::from_columns(a * s.x, b * s.y, c * s.z, rng.point(-1.5f, 1.5f));
}

struct Found {
    float t = kInfinity;
    std::uint32_t instance = UINT32_MAX, prim = UINT32_MAX;
};

}  // namespace

TEST_CASE("two-level: instanced triangles equal the flattened world-space scene") {
    Rng rng(42);
    std::vector<std::vector<Tri>> meshes;
    std::vector<Bvh> blases;
    for (int m = 0; m < 3; ++m) {
        meshes.push_back(rtc::test::random_triangles(rng, 200, 0.2f));
        std::vector<Aabb> boxes;
        for (const Tri& t : meshes.back()) boxes.push_back(t.box());
        blases.push_back(build_bvh(boxes));
    }
    std::vector<Instance> instances;
    std::vector<Tri> flat;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> flat_id;
    for (std::uint32_t i = 0; i < 12; ++i) {
        const auto blas = i % 3;
        instances.push_back(make_instance(blas, i, random_affine(rng)));
        const Affine& m = instances.back().world_from_object;
        for (std::uint32_t k = 0; k < meshes[blas].size(); ++k) {
            const Tri& t = meshes[blas][k];
            flat.push_back({m.point(t.a), m.point(t.b), m.point(t.c)});
            flat_id.push_back({i, k});
        }
    }
    for (int width : {2, 4, 8}) {
        BuildOptions o;
        o.width = width;
        const TwoLevel scene = build_two_level(blases, instances, o);
        // The instances sit in the TLAS's leaf order: leaf slot k names
        // instance k, and each input instance appears once, as itself.
        REQUIRE(scene.instances.size() == instances.size());
        std::vector<int> seen(instances.size(), 0);
        for (std::uint32_t k = 0; k < scene.instances.size(); ++k) {
            CHECK(scene.tlas.prim_ids[k] == k);
            const TlasInstance& placed = scene.instances[k];
            REQUIRE(placed.id < instances.size());  // ids here are the input positions
            const Instance& in = instances[placed.id];
            ++seen[placed.id];
            CHECK(placed.blas == in.blas);
            CHECK(std::memcmp(&placed.object_from_world, &in.object_from_world, sizeof(CentredAffine)) == 0);
        }
        CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<long>(instances.size()));
        int same = 0, hits = 0, total = 0;
        for (int r = 0; r < 1000; ++r) {
            const Ray ray = rtc::test::random_ray(rng);
            Found inst;
            CountingSink sink;
            trace_two_level<TraversalMode::Closest>(scene, ray, sink, [&](const PrimitiveQuery& q) {
                Ray obj = q.object_ray;
                obj.tmax = q.tmax;
                const auto t = rtc::test::hit_triangle(meshes[q.instance.blas][q.prim], obj);
                if (!t) return kInfinity;
                if (*t < inst.t) inst = {*t, q.instance.id, q.prim};
                return *t;
            });
            Found ref;
            for (std::uint32_t k = 0; k < flat.size(); ++k) {
                const auto t = rtc::test::hit_triangle(flat[k], ray);
                if (t && *t < ref.t) ref = {*t, flat_id[k].first, flat_id[k].second};
            }
            ++total;
            hits += ref.instance != UINT32_MAX;
            // Transforming the ray and transforming the triangles round
            // differently, so a hit within float noise of an edge may flip;
            // everything else must agree, with t equal to rounding.
            if (inst.instance == ref.instance && inst.prim == ref.prim) {
                ++same;
                if (ref.instance != UINT32_MAX) CHECK(std::abs(inst.t - ref.t) <= 1e-4f * ref.t + 1e-6f);
            }
            CHECK(sink.ray[Event::TlasNodeVisit] >= 1);
            CHECK(sink.ray[Event::InstanceTransform] <= instances.size());
        }
        CAPTURE(width);
        CHECK(hits > 200);
        CHECK(same >= total - 3);
    }
}

TEST_CASE("two-level: the direction stays unnormalized so t is shared across levels") {
    // A BLAS with one unit box, instanced scaled by 10 and moved to z = 20.
    std::vector<Bvh> blases{build_bvh(std::vector<Aabb>{{Vec3(-1), Vec3(1)}})};
    const auto inst = make_instance(0, 7, Affine::translate({0, 0, 20}) * Affine::scale(Vec3(10)));
    const TwoLevel scene = build_two_level(blases, {inst}, BuildOptions{});
    const Ray ray{Vec3(0, 0, 0), 0.0f, Vec3(0, 0, 2), kInfinity};  // |d| = 2
    CountingSink sink;
    float seen_t = -1.0f;
    const float t = trace_two_level<TraversalMode::Closest>(scene, ray, sink, [&](const PrimitiveQuery& q) {
        CHECK(q.instance.id == 7);
        // Object space: origin at z = -2, direction 0.2 per unit t; box entry at t = 5.
        const float t_obj = (-1.0f - q.object_ray.origin.z) / q.object_ray.direction.z;
        seen_t = t_obj;
        return t_obj;
    });
    CHECK(seen_t == doctest::Approx(5.0f));
    CHECK(t == doctest::Approx(5.0f));
    CHECK(ray.at(t).z == doctest::Approx(10.0f));  // world entry point: z = 20 - 10
    CHECK(sink.ray[Event::InstanceTransform] == 1);
    CHECK(sink.ray[Event::BlasBoxTest] == 1);
}

TEST_CASE("two-level: singular transforms and dangling BLAS indices are rejected") {
    CHECK_THROWS_AS((void)make_instance(0, 0, Affine::scale({1, 0, 1})), std::invalid_argument);
    std::vector<Bvh> blases{build_bvh(std::vector<Aabb>{{Vec3(-1), Vec3(1)}})};
    CHECK_THROWS_AS((void)build_two_level(blases, {make_instance(3, 0, Affine{})}, BuildOptions{}),
                    std::invalid_argument);
    // An empty TLAS traces to nothing.
    const TwoLevel none = build_two_level({}, std::vector<Instance>{}, BuildOptions{});
    NullSink sink;
    const Ray ray{Vec3(0), 0.0f, Vec3(0, 0, 1), kInfinity};
    CHECK(trace_two_level<TraversalMode::Closest>(none, ray, sink, [](const PrimitiveQuery&) {
              return 0.0f;
          }) == kInfinity);
}

TEST_CASE("two-level: the lone identity instance's shortcut equals the instance step bit for bit") {
    // The reference method's shape: one identity instance over a BLAS with
    // inner nodes. trace_two_level skips the transform for rays that
    // passes_identity(); the general path (lone_identity cleared) is the
    // reference: every program call (primitive, object ray bits, tmax), every
    // event count and the result must agree.
    Rng rng(7);
    const std::vector<Tri> tris = rtc::test::random_triangles(rng, 300, 0.2f);
    std::vector<Aabb> boxes;
    for (const Tri& t : tris) boxes.push_back(t.box());
    std::vector<Bvh> blases{build_bvh(boxes)};
    // make_instance inverts the identity: its inverse may hold -0 entries.
    Affine minus_zero;
    minus_zero.linear[0][1] = -0.0f, minus_zero.linear[2][0] = -0.0f, minus_zero.translation.y = -0.0f;
    for (const Affine& a : {Affine{}, minus_zero}) {
        const TwoLevel fast = build_two_level(blases, {make_instance(0, 3, a)}, BuildOptions{});
        REQUIRE(fast.lone_identity);
        TwoLevel general = fast;
        general.lone_identity = false;
        const auto run = [&](const TwoLevel& scene, const Ray& ray, CountingSink& sink,
                             std::vector<std::array<std::uint32_t, 8>>& calls) {
            return trace_two_level<TraversalMode::Closest>(scene, ray, sink, [&](const PrimitiveQuery& q) {
                std::array<std::uint32_t, 8> c{q.prim};
                std::memcpy(&c[1], &q.object_ray.origin, 12);
                std::memcpy(&c[4], &q.object_ray.direction, 12);
                std::memcpy(&c[7], &q.tmax, 4);
                calls.push_back(c);
                Ray obj = q.object_ray;
                obj.tmax = q.tmax;
                const auto t = rtc::test::hit_triangle(tris[q.prim], obj);
                return t ? *t : kInfinity;
            });
        };
        std::vector<Ray> rays;
        for (int r = 0; r < 3000; ++r) rays.push_back(rtc::test::random_ray(rng));
        // Zeros of either sign, infinities and NaN in origin and direction.
        const float specials[] = {0.0f, -0.0f, kInfinity, -kInfinity, std::nanf("")};
        for (int r = 0; r < 3000; ++r) {
            Ray ray = rtc::test::random_ray(rng);
            float* f[] = {&ray.origin.x, &ray.origin.y, &ray.origin.z,
                          &ray.direction.x, &ray.direction.y, &ray.direction.z};
            *f[r % 6] = specials[(r / 6) % 5];
            if (r % 3 == 0) *f[(r / 30) % 6] = specials[(r / 7) % 5];
            // tmin and tmax share the 16-byte loads of origin and direction
            // (RayLanes): their values must not change which path a ray takes.
            if (r % 4 == 1) ray.tmin = specials[(r / 4) % 5];
            if (r % 5 == 2) ray.tmax = specials[(r / 5) % 5];
            rays.push_back(ray);
        }
        int shortcut = 0, hits = 0;
        for (const Ray& ray : rays) {
            CountingSink a, b;
            std::vector<std::array<std::uint32_t, 8>> ca, cb;
            const float ta = run(fast, ray, a, ca), tb = run(general, ray, b, cb);
            shortcut += passes_identity(ray);
            CHECK(passes_identity(ray) == passes_identity_reference(ray));
            hits += ta < kInfinity;
            CHECK(std::memcmp(&ta, &tb, sizeof ta) == 0);
            CHECK(a.ray.n == b.ray.n);
            CHECK(ca == cb);
        }
        CHECK(shortcut >= 3000);
        CHECK(shortcut < static_cast<int>(rays.size()) - 1000);
        CHECK(hits > 300);
    }
    // Not the shape: two instances, or a transform that is not the identity.
    std::vector<Bvh> two{blases[0], blases[0]};
    CHECK_FALSE(build_two_level(two, {make_instance(0, 0, Affine{}), make_instance(1, 1, Affine{})},
                                BuildOptions{}).lone_identity);
    CHECK_FALSE(build_two_level(blases, {make_instance(0, 0, Affine::translate({0, 0, 1e-7f}))},
                                BuildOptions{}).lone_identity);
}

TEST_CASE("two-level: an instance's world box from the extreme corners equals the eight corners' bit for bit") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    const auto same = [](const Aabb& a, const Aabb& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
    std::size_t differ = 0, checked = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        Affine a;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) a.linear[c][r] = u(rng);
        a.translation = {u(rng) * 100.0f, u(rng), u(rng) * 1e-3f};
        // Zeros and signed zeros in the matrix, the translation and the box
        // (axis-aligned rotations, instances at the origin): the fallback's cases.
        if (trial % 3 == 0) a.linear[trial % 9 / 3][trial % 3] = trial % 2 ? 0.0f : -0.0f;
        if (trial % 5 == 0) a.translation[trial % 3] = trial % 2 ? 0.0f : -0.0f;
        if (trial % 7 == 0) a.linear = glm::mat3(0.0f);
        if (trial % 11 == 0) a.linear[0][0] = 3e38f;  // products overflow
        Aabb box{{u(rng), u(rng), u(rng)}, {}};
        box.hi = box.lo + Vec3(std::abs(u(rng)), std::abs(u(rng)), trial % 4 == 0 ? 0.0f : std::abs(u(rng)));
        if (trial % 13 == 0) box = {{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}};  // the masquerade's unit box
        differ += !same(a.box(box), a.box_by_corners(box));
        ++checked;
    }
    CHECK(checked == 20000);
    CHECK(differ == 0);
}

TEST_CASE("two-level: instances made on demand build what the same instances in an array build") {
    Rng rng(7);
    std::vector<Bvh> blases{build_bvh(std::vector<Aabb>{{Vec3(-0.5f), Vec3(0.5f)}}),
                            build_bvh(std::vector<Aabb>{{Vec3(-1), Vec3(0.5f)}, {Vec3(0), Vec3(2)}})};
    std::vector<Instance> instances;
    for (std::uint32_t i = 0; i < 500; ++i) instances.push_back(make_instance(i % 7 == 0 ? 1 : 0, 1000 + i, random_affine(rng)));
    BuildOptions o;
    o.threads = 2;
    const TwoLevel from_array = build_two_level(blases, instances, o);
    std::vector<int> calls(instances.size(), 0);
    std::mutex m;
    const TwoLevel on_demand = build_two_level(blases, instances.size(), [&](std::size_t i) {
        const std::lock_guard<std::mutex> lock(m);
        ++calls[i];
        return instances[i];
    }, o);
    // Twice per instance: its TLAS box, then its leaf slot.
    CHECK(std::count(calls.begin(), calls.end(), 2) == static_cast<long>(instances.size()));
    REQUIRE(on_demand.instances.size() == from_array.instances.size());
    for (std::size_t k = 0; k < from_array.instances.size(); ++k) {  // field by field: a TlasInstance has padding
        const TlasInstance &a = on_demand.instances[k], &b = from_array.instances[k];
        CHECK(std::memcmp(&a.object_from_world, &b.object_from_world, sizeof(CentredAffine)) == 0);
        CHECK(a.blas == b.blas);
        CHECK(a.id == b.id);
    }
    CHECK(on_demand.tlas.prim_ids == from_array.tlas.prim_ids);
    REQUIRE(on_demand.tlas.entries.size() == from_array.tlas.entries.size());
    CHECK(std::memcmp(on_demand.tlas.entries.data(), from_array.tlas.entries.data(),
                      from_array.tlas.entries.size() * sizeof(BvhEntry)) == 0);
    CHECK(on_demand.lone_identity == from_array.lone_identity);
    // Both entry points share one implementation, so also against a TLAS built
    // here: a BVH over the instances' world boxes, the instances in its leaf order.
    std::vector<Aabb> world_boxes;
    for (const Instance& in : instances) world_boxes.push_back(in.world_from_object.box(blases[in.blas].bounds()));
    const Bvh expected = build_bvh(world_boxes, o);
    REQUIRE(on_demand.tlas.entries.size() == expected.entries.size());
    CHECK(std::memcmp(on_demand.tlas.entries.data(), expected.entries.data(),
                      expected.entries.size() * sizeof(BvhEntry)) == 0);
    for (std::size_t k = 0; k < expected.prim_ids.size(); ++k) {
        const Instance& in = instances[expected.prim_ids[k]];
        const TlasInstance& placed = on_demand.instances[k];
        CHECK(std::memcmp(&placed.object_from_world, &in.object_from_world, sizeof(CentredAffine)) == 0);
        CHECK(placed.blas == in.blas);
        CHECK(placed.id == in.id);
        CHECK(on_demand.tlas.prim_ids[k] == k);
    }
    // A maker that throws, and an instance of a BLAS that is not there, stop the build.
    CHECK_THROWS_AS((void)build_two_level(blases, 3, [](std::size_t i) -> Instance {
        if (i == 2) throw std::invalid_argument("instance 2: made badly");
        return make_instance(0, 0, Affine{});
    }, o), std::invalid_argument);
    CHECK_THROWS_WITH_AS((void)build_two_level(blases, 3, [](std::size_t i) {
        return make_instance(i == 1 ? 5 : 0, 0, Affine{});
    }, o), "instance 1: no BLAS 5", std::invalid_argument);
}

}  // namespace RTCSIM_TEST_FILE
