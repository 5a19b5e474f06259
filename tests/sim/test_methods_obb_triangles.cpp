// Oriented boxes over triangles (bvh.oriented_triangles, issue 54): the
// oriented-node methods orient the triangle BLAS too. Every oriented box
// contains the triangles below it, every exact method returns ref's closest
// hit on a triangle scene (with and without custom primitives), and the
// oriented methods do rotate there.
#include "core/obb_build.h"
#include "sim/methods_test_util.h"

#include <doctest/doctest.h>

#include <bit>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using namespace rtc::test;

namespace {

// Long, thin, arbitrarily oriented triangles (grass blades), and a few
// ordinary ones.
std::vector<Triangle> thin_triangles(Rng& rng, int n) {
    std::vector<Triangle> v;
    for (int i = 0; i < n; ++i) {
        const Vec3 p = rng.point(-1, 1);
        const Vec3 along = rng.direction() * rng.uniform(0.1f, 0.5f);
        if (i % 8 == 7) {
            v.push_back({p, p + rng.point(-0.1f, 0.1f), p + rng.point(-0.1f, 0.1f)});
        } else {
            const Vec3 side = glm::normalize(glm::cross(along, rng.direction())) * rng.uniform(0.002f, 0.02f);
            v.push_back({p - side, p + side, p + along});
        }
    }
    return v;
}

Geometry triangle_geometry(Rng& rng, int prims) {
    Geometry g;
    g.kind = PrimitiveKind::Capsule;
    g.prims = random_prims(rng, PrimitiveKind::Capsule, prims);
    g.triangles = thin_triangles(rng, 400);
    return g;
}

MethodOptions oriented(int width) {
    MethodOptions o = options(width);
    o.oriented_triangles = true;
    return o;
}

// Checks that every entry's box (in its frame) holds every vertex of every
// triangle below it; returns how many entries were rotated.
std::size_t check_contains(const ObbBvh& t, const std::vector<Triangle>& tris) {
    std::size_t rotated = 0;
    const auto holds = [&](const BvhEntry& e, std::uint32_t frame, const Triangle& tri) {
        for (const Vec3& v : {tri.v0, tri.v1, tri.v2}) {
            const DVec3 p = frame == kWorldFrame ? DVec3(v) : t.frames.frames[frame].local(DVec3(v));
            for (int a = 0; a < 3; ++a)
                if (!(p[a] >= double(e.box.lo[a]) && p[a] <= double(e.box.hi[a]))) return false;
        }
        return true;
    };
    // Entries with the triangles below them, depth first.
    const auto below = [&](auto&& self, const BvhEntry& e, std::vector<std::uint32_t>& out) -> void {
        if (!e.is_inner()) {
            for (std::uint32_t k = 0; k < e.size(); ++k) out.push_back(t.bvh.prim_ids[e.first + k]);
            return;
        }
        for (std::uint32_t c = 0; c < e.size(); ++c) self(self, t.bvh.entries[e.first + c], out);
    };
    for (std::size_t i = 0; i < t.bvh.entries.size(); ++i) {
        std::vector<std::uint32_t> ids;
        below(below, t.bvh.entries[i], ids);
        const std::uint32_t frame = t.frames.frame_of[i];
        rotated += frame != kWorldFrame;
        for (const std::uint32_t id : ids) {
            CAPTURE(i);
            CAPTURE(id);
            REQUIRE(holds(t.bvh.entries[i], frame, tris[id]));
        }
    }
    return rotated;
}

bool same_hit(const TraceHit& a, const TraceHit& b) {
    return a.geom == b.geom && a.prim == b.prim &&
           std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t);
}

}  // namespace

TEST_CASE("obb triangles: oriented boxes over triangles contain their triangles") {
    Rng rng(5401);
    Geometry g;
    g.triangles = thin_triangles(rng, 600);
    const std::vector<BoundProxy> proxies = triangle_proxies(g);
    REQUIRE(proxies.size() == g.triangles.size());
    std::vector<Aabb> boxes;
    for (const Triangle& t : g.triangles) boxes.push_back(bounds(t));
    for (const int width : {2, 4, 8}) {
        CAPTURE(width);
        BuildOptions b;
        b.width = width;
        b.max_leaf_size = 4;
        const ObbBvh quantized = quantize_obb_bvh(build_bvh(boxes, b), proxies, QuantizeOptions{});
        CHECK(check_contains(quantized, g.triangles) > 0);
        ObbBuildOptions o;
        o.width = width;
        o.intersection = 2.0;
        const ObbBvh nodes = build_obb_bvh(boxes, proxies, o);
        CHECK(check_contains(nodes, g.triangles) > 0);
    }
}

TEST_CASE("obb triangles: every exact method returns ref's closest hit on triangle scenes") {
    for (const int prims : {0, 200}) {
        for (const int width : {4, 8}) {
            CAPTURE(prims);
            CAPTURE(width);
            Rng rng(5402 + prims + width);
            const Geometry g = triangle_geometry(rng, prims);
            const auto ref = build("ref", g, options(width));
            int hits = 0;
            std::vector<Ray> rays;
            for (int i = 0; i < 300; ++i) rays.push_back(scene_ray(rng));
            for (const MethodEntry& m : registered_methods()) {
                if (m.info.approximate || m.info.name == "ref" || m.info.name.rfind("test-", 0) == 0) continue;
                if (!not_applicable_reason(m, g).empty()) continue;
                for (const bool orient : {false, true}) {
                    CAPTURE(m.info.name);
                    CAPTURE(orient);
                    const auto built = m.build(g, orient ? oriented(width) : options(width));
                    int mismatches = 0;
                    for (const Ray& ray : rays) {
                        CountingSink sr, sm;
                        const TraceHit a = trace_any(ref, g, ray, sr, IsSchedule::Immediate);
                        const TraceHit b = trace_any(built, g, ray, sm, IsSchedule::Immediate);
                        mismatches += !same_hit(a, b);
                        hits += a.hit();
                    }
                    CHECK(mismatches == 0);
                }
            }
            CHECK(hits > 100);
        }
    }
}

TEST_CASE("obb triangles: the oriented methods rotate in the triangle BLAS and test fewer triangles") {
    Rng rng(5403);
    const Geometry g = triangle_geometry(rng, 0);
    const auto ref = build("ref", g, options(4));
    const auto quantized = build("obb-quantized", g, oriented(4));
    const auto nodes = build("obb-nodes", g, oriented(4));
    CHECK(nodes->structures().oriented_children > 0);
    CHECK(quantized->structures().oriented_children == 0);  // one table index per node: no extra bytes
    EventTotals r, q, n;
    for (int i = 0; i < 400; ++i) {
        const Ray ray = scene_ray(rng);
        CountingSink sr, sq, sn;
        (void)trace_any(ref, g, ray, sr, IsSchedule::Immediate);
        (void)trace_any(quantized, g, ray, sq, IsSchedule::Immediate);
        (void)trace_any(nodes, g, ray, sn, IsSchedule::Immediate);
        r.add(sr.ray), q.add(sq.ray), n.add(sn.ray);
    }
    CHECK(q[Event::NodeRotate] > 0);
    CHECK(n[Event::ObbBoxTest] > 0);
    CHECK(r[Event::NodeRotate] + r[Event::ObbBoxTest] == 0);
    CHECK(q[Event::TriangleTest] < r[Event::TriangleTest]);
    CHECK(n[Event::TriangleTest] < r[Event::TriangleTest]);
}

}  // namespace RTCSIM_TEST_FILE
