// The two curve bases (scenes/scene.h: CurveBasis). The B-spline basis, the
// default, gives bit for bit the primitives it gave before the Bezier basis
// existed (checksums computed with that code, commit 8c18e26); the Bezier
// basis makes one cubic per three links of the control polygon, with a
// degree-elevated remainder, and the generators' Bezier control polygons lie
// on their centreline; every phantom bound (AABB, paper and tight OBBs)
// contains its curve with its radius in both bases.
#include "core/input_error.h"
#include "intersectors/bezier.h"
#include "scenes/convert.h"
#include "scenes/generators/follow_hairs.h"
#include "scenes/generators/hair_gen.h"
#include "scenes/generators/random.h"

#include <doctest/doctest.h>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;

namespace {

// FNV-1a over the bytes of every primitive and its source strand.
std::uint64_t checksum(const Strands& s, PrimitiveKind kind, int subdivision) {
    std::uint64_t h = 1469598103934665603ull;
    auto eat = [&](const void* data, std::size_t n) {
        const auto* b = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
    };
    std::visit([&](const auto& v) { eat(v.data(), v.size() * sizeof(v[0])); }, to_primitives(s, kind, subdivision));
    const std::vector<std::uint32_t> strands = primitive_strands(s, kind, subdivision);
    eat(strands.data(), strands.size() * sizeof(strands[0]));
    return h;
}

HairDesc small_hair(HairStyle style, HairEmitter emitter, std::uint32_t points) {
    HairDesc d;
    d.style = style;
    d.emitter = emitter;
    d.strands = 40;
    d.points_per_strand = points;
    d.length = 0.3f;
    d.radius = 4e-3f;
    d.tip_radius = 2e-3f;
    d.curl_radius = 0.05f;
    d.curl_turns = 3.0f;
    d.lean = 0.1f;
    return d;
}

}  // namespace

TEST_CASE("curve basis: the B-spline basis gives exactly the primitives it gave before") {
    struct Case {
        HairStyle style;
        HairEmitter emitter;
        std::uint32_t points;
        PrimitiveKind kind;
        int subdivision;
        std::uint64_t expected;
    };
    const Case cases[] = {
        {HairStyle::Curly, HairEmitter::Lock, 26, PrimitiveKind::Capsule, 1, 0xb9040043e1363be8ull},
        {HairStyle::Curly, HairEmitter::Lock, 26, PrimitiveKind::Link, 1, 0x44772f9f3fe885fcull},
        {HairStyle::Curly, HairEmitter::Lock, 26, PrimitiveKind::Phantom, 1, 0x3e846036b58e989full},
        {HairStyle::Curly, HairEmitter::Lock, 26, PrimitiveKind::Phantom, 8, 0xdc05f4c1f647c57eull},
        {HairStyle::Curly, HairEmitter::Sphere, 9, PrimitiveKind::Phantom, 2, 0x11752c6082e2d97eull},
        {HairStyle::Wavy, HairEmitter::Sphere, 12, PrimitiveKind::Cylinder, 1, 0x50a2ba2766835a83ull},
        {HairStyle::Wavy, HairEmitter::Sphere, 12, PrimitiveKind::Phantom, 4, 0x54a05069ee078935ull},
        {HairStyle::Straight, HairEmitter::Sphere, 2, PrimitiveKind::Phantom, 1, 0x2fafcc18e72f902aull},
    };
    for (const Case& c : cases) {
        const Strands s = make_hair(small_hair(c.style, c.emitter, c.points)).strands;
        CHECK(s.basis == CurveBasis::BSpline);
        const std::uint64_t got = checksum(s, c.kind, c.subdivision);
        MESSAGE(c.points << " points, " << kind_name(c.kind) << " /" << c.subdivision << ": " << got);
        CHECK(got == c.expected);
    }
}

TEST_CASE("curve basis: Bezier conversion counts and the remainder rule") {
    SceneRng rng(5);
    for (std::uint32_t n = 2; n <= 11; ++n) {
        CAPTURE(n);
        Strands s;
        s.basis = CurveBasis::Bezier;
        for (std::uint32_t i = 0; i < n; ++i) {
            s.points.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            s.radii.push_back(static_cast<float>(rng.uniform(0.01, 0.1)));
        }
        s.offsets.push_back(n);
        const std::size_t links = n - 1, cubics = (links + 2) / 3;
        CHECK(curve_count(n, CurveBasis::Bezier) == cubics);
        CHECK(curve_count(n, CurveBasis::BSpline) == links);
        // The straight kinds: one per link, as in the B-spline basis.
        for (const PrimitiveKind k : {PrimitiveKind::Cylinder, PrimitiveKind::Capsule, PrimitiveKind::Link}) {
            CHECK(primitive_count(to_primitives(s, k)) == links);
            CHECK(primitive_count(s, k) == links);
            CHECK(primitive_strands(s, k).size() == links);
        }
        const auto curves = std::get<std::vector<PhantomCurve>>(to_primitives(s, PrimitiveKind::Phantom));
        REQUIRE(curves.size() == cubics);
        CHECK(primitive_count(s, PrimitiveKind::Phantom) == cubics);
        for (std::size_t i = 0; i < cubics; ++i) {
            const std::uint32_t first = static_cast<std::uint32_t>(3 * i), span = std::min<std::uint32_t>(3, n - 1 - first);
            const Vec3* p = &s.points[first];
            const float* r = &s.radii[first];
            CHECK(curves[i].cp[0] == p[0]);          // end points exactly: consecutive curves share one
            CHECK(curves[i].cp[3] == p[span]);
            CHECK(curves[i].radius[0] == r[0]);
            CHECK(curves[i].radius[3] == r[span]);
            for (float t = 0.0f; t <= 1.0f; t += 0.125f) {
                // What the piece traces: the cubic itself, or the line / quadratic it elevates.
                const float u = 1.0f - t;
                const Vec3 want = span == 3 ? u * u * u * p[0] + 3 * u * u * t * p[1] + 3 * u * t * t * p[2] + t * t * t * p[3]
                                : span == 2 ? u * u * p[0] + 2 * u * t * p[1] + t * t * p[2]
                                            : u * p[0] + t * p[1];
                const float want_r = span == 3 ? u * u * u * r[0] + 3 * u * u * t * r[1] + 3 * u * t * t * r[2] + t * t * t * r[3]
                                     : span == 2 ? u * u * r[0] + 2 * u * t * r[1] + t * t * r[2]
                                                 : u * r[0] + t * r[1];
                CHECK(glm::length(bspline::bezier_point(curves[i], t) - want) < 1e-5f);
                CHECK(bspline::bezier_radius(curves[i], t) == doctest::Approx(want_r).epsilon(1e-5));
            }
        }
        for (const int k : {2, 4, 8}) {
            CHECK(primitive_count(to_primitives(s, PrimitiveKind::Phantom, k)) == cubics * k);
            CHECK(primitive_count(s, PrimitiveKind::Phantom, k) == cubics * k);
            CHECK(primitive_strands(s, PrimitiveKind::Phantom, k) == std::vector<std::uint32_t>(cubics * k, 0));
        }
    }
    // Strand ids across strands: 7 points (2 cubics), 2 points (1), 5 points (2: one and a remainder of 1).
    Strands s;
    s.basis = CurveBasis::Bezier;
    for (int i = 0; i < 14; ++i) {
        s.points.emplace_back(float(i), 0.0f, 0.0f);
        s.radii.push_back(0.1f);
    }
    s.offsets = {0, 7, 9, 14};
    CHECK(primitive_strands(s, PrimitiveKind::Phantom) == std::vector<std::uint32_t>{0, 0, 1, 2, 2});
    CHECK(primitive_strands(s, PrimitiveKind::Phantom, 2) ==
          std::vector<std::uint32_t>{0, 0, 0, 0, 1, 1, 2, 2, 2, 2});
    CHECK(primitive_strands(s, PrimitiveKind::Capsule).size() == 11);
    CHECK_THROWS_AS((void)to_primitives(s, PrimitiveKind::Capsule, 2), InputError);
}

TEST_CASE("curve basis: Bezier hair puts curve ends on the centreline and joins curves smoothly") {
    for (const HairStyle style : {HairStyle::Curly, HairStyle::Wavy, HairStyle::Straight}) {
        for (const std::uint32_t points : {31u, 29u}) {  // 10 cubics; 9 and a remainder of 1 link
            CAPTURE(static_cast<int>(style));
            CAPTURE(points);
            HairDesc d = small_hair(style, HairEmitter::Lock, points);
            d.curl_turns = 1.2f;  // 43 deg of a turn per cubic, as the curly stand-ins
            d.waves = 1.0f;       // 36 deg of a period per cubic
            const Strands polyline = make_hair(d).strands;
            d.basis = CurveBasis::Bezier;
            const Strands bez = make_hair(d).strands;
            CHECK(bez.basis == CurveBasis::Bezier);
            REQUIRE(bez.points.size() == polyline.points.size());
            CHECK(bez.radii == polyline.radii);
            // The same random draws: end points (every third point) and the
            // points past the last full cubic are the B-spline strand's.
            for (std::size_t i = 0; i < bez.strand_count(); ++i)
                for (std::uint32_t k = 0; k < points; ++k) {
                    const std::uint32_t at = bez.offsets[i] + k;
                    if (k % 3 == 0 || k - k % 3 + 3 > points - 1) CHECK(bez.points[at] == polyline.points[at]);
                }
            // A centreline sampled 6 times as densely: its point 6i + 3 is
            // the middle of cubic i, where the cubic must pass.
            HairDesc dense = d;
            dense.basis = CurveBasis::BSpline;
            dense.points_per_strand = 6 * (points - 1) + 1;
            const Strands fine = make_hair(dense).strands;
            const auto curves = std::get<std::vector<PhantomCurve>>(to_primitives(bez, PrimitiveKind::Phantom));
            REQUIRE(curves.size() == bez.strand_count() * curve_count(points, CurveBasis::Bezier));
            const std::size_t per_strand = curve_count(points, CurveBasis::Bezier);
            float worst = 0.0f;
            for (std::size_t i = 0; i < bez.strand_count(); ++i)
                for (std::size_t c = 0; c < per_strand; ++c) {
                    const PhantomCurve& cv = curves[i * per_strand + c];
                    const std::size_t links = std::min<std::size_t>(3, points - 1 - 3 * c);
                    const Vec3 mid = fine.points[fine.offsets[i] + 6 * 3 * c + 3 * links];
                    if (links == 3) worst = std::max(worst, glm::length(bspline::bezier_point(cv, 0.5f) - mid));
                    if (c + 1 < per_strand && links == 3) {
                        // G1 and C1: the next cubic leaves along the same tangent, equally fast.
                        const PhantomCurve& next = curves[i * per_strand + c + 1];
                        const Vec3 in = cv.cp[3] - cv.cp[2], out = next.cp[1] - next.cp[0];
                        if (3 * (c + 1) + 3 <= points - 1) CHECK(glm::length(in - out) <= 1e-4f * glm::length(in) + 1e-6f);
                    }
                }
            // Cubic Hermite on a 43 deg arc of the helix: 8e-4 of the curl
            // radius at worst (1.1e-3 at 46 deg, 29 points); on 36 deg of the
            // sine, 4e-4 of its amplitude.
            const float size = style == HairStyle::Curly ? d.curl_radius : style == HairStyle::Wavy ? d.wave_amplitude : 0.0f;
            MESSAGE("worst distance from the centreline " << worst << " (curl or wave " << size * d.length << ")");
            CHECK(worst <= 2e-3f * size * d.length + 1e-6f);
        }
    }
}

TEST_CASE("curve basis: follow hairs keep the basis") {
    HairDesc d = small_hair(HairStyle::Curly, HairEmitter::Sphere, 10);
    d.basis = CurveBasis::Bezier;
    const Strands guides = make_hair(d).strands;
    FollowHairDesc f;
    f.per_guide = 2;
    f.spread = 0.01f;
    const Strands all = add_follow_hairs(guides, f);
    CHECK(all.basis == CurveBasis::Bezier);
    CHECK(primitive_count(all, PrimitiveKind::Phantom) == 3 * 40 * 3);
}

namespace {

// Exactly inside (in double) an OBB as the hardware stores it: its float
// inverse about its float centre (as tests/intersectors/test_intersect_bounds.cpp).
bool obb_contains(const CentredAffine& unit_from_world, const DVec3& p) {
    const DVec3 q = glm::dmat3(unit_from_world.linear) * (p - DVec3(unit_from_world.origin));
    return std::abs(q.x) <= 1.0 && std::abs(q.y) <= 1.0 && std::abs(q.z) <= 1.0;
}

}  // namespace

TEST_CASE("curve basis: every phantom bound contains its curve with its radius, both bases, pre-subdivided") {
    SceneRng rng(21);
    long samples = 0, outside = 0;
    for (int trial = 0; trial < 12; ++trial) {
        HairDesc d = small_hair(trial % 3 == 2 ? HairStyle::Wavy : HairStyle::Curly,
                                trial % 2 ? HairEmitter::Lock : HairEmitter::Sphere,
                                static_cast<std::uint32_t>(rng.uniform(4, 40)));
        d.strands = 6;
        d.curl_radius = static_cast<float>(rng.uniform(0.01, 0.2));
        d.curl_turns = static_cast<float>(rng.uniform(1, 12));
        d.radius = static_cast<float>(rng.uniform(1e-4, 1e-2));
        d.tip_radius = d.radius * static_cast<float>(rng.uniform(0, 1));
        d.seed = 100 + trial;
        for (const CurveBasis basis : {CurveBasis::BSpline, CurveBasis::Bezier}) {
            d.basis = basis;
            const Strands s = make_hair(d).strands;
            for (const int k : {1, 2, 4, 8}) {
                const PrimitiveArray prims = to_primitives(s, PrimitiveKind::Phantom, k);
                for (const PhantomCurve& c : std::get<std::vector<PhantomCurve>>(prims)) {
                    const Aabb box = bounds(c);
                    const auto paper = centred_inverse(oriented_bounds(c, ObbVariant::Paper).world_from_unit);
                    const auto tight = centred_inverse(oriented_bounds(c, ObbVariant::Tight).world_from_unit);
                    REQUIRE((paper && tight));
                    const std::array<DVec3, 4> q{DVec3(c.cp[0]), DVec3(c.cp[1]), DVec3(c.cp[2]), DVec3(c.cp[3])};
                    const std::array<double, 4> r{c.radius[0], c.radius[1], c.radius[2], c.radius[3]};
                    for (int i = 0; i <= 24; ++i) {
                        const double t = i / 24.0;
                        const DVec3 centre = bezier(q, t);
                        for (int j = 0; j < 4; ++j, ++samples) {
                            const DVec3 dir = glm::normalize(DVec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) +
                                                             DVec3(1e-9));
                            const DVec3 p = centre + bezier(r, t) * dir;
                            const bool in_box = glm::all(glm::lessThanEqual(DVec3(box.lo), p)) &&
                                                glm::all(glm::lessThanEqual(p, DVec3(box.hi)));
                            outside += !(in_box && obb_contains(*paper, p) && obb_contains(*tight, p));
                        }
                    }
                }
            }
        }
    }
    MESSAGE(outside << " of " << samples << " surface samples outside a bound");
    CHECK(samples > 100000);
    CHECK(outside == 0);
}

}  // namespace RTCSIM_TEST_FILE
