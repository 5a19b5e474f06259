#include "core/two_level.h"

#include <doctest/doctest.h>

using namespace rtc;

TEST_CASE("smoke: a single box is hit") {
    std::vector<Aabb> boxes{{Vec3(-1), Vec3(1)}};
    const Bvh bvh = build_bvh(boxes);
    CountingSink sink;
    const Ray ray{Vec3(0, 0, -5), 0.0f, Vec3(0, 0, 1), kInfinity};
    const float t = traverse<TraversalMode::Closest, kBlasEvents>(
        bvh, ray.origin, safe_inverse(ray.direction), ray.tmin, ray.tmax, sink,
        [](std::uint32_t, std::uint32_t, float) { return 4.0f; });
    CHECK(t == 4.0f);
    CHECK(sink.ray[Event::BlasNodeVisit] == 1);
    CHECK(sink.ray[Event::BlasBoxTest] == 1);
}
