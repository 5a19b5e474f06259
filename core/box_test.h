// The ray/box test of a node's children (BvhLaneBlock lanes), behind one
// interface in two implementations that give the same bits:
// - ScalarBoxTest: intersect_box() (core/aabb.h) per child.
// - SseBoxTest: four children per SSE instruction, the same float operations
//   in the same order, min/max with the same operand order, so NaNs and
//   signed zeros resolve alike.
// BlockBoxTest is the one the traversal uses: SseBoxTest where SSE2 is, else
// ScalarBoxTest. Every build compiles ScalarBoxTest, and
// tests/core/test_core_box_test.cpp checks both agree, so the fallback of a
// target without SSE2 is the code the tests ran.
//
// The interface (AabbNodes, core/aabb_nodes.h, uses nothing else):
//   Ray(origin, inv_dir, tmin)   the ray as the tests use it (set up once)
//   Tmax, tmax(float)            tmax as the tests use it (set up per change)
//   children(block, n, ray, tmax, tnear) -> mask of hit children (bit i for
//       child i, n <= 8), their entry distances in tnear[i]
#pragma once

#include "core/aabb.h"
#include "core/bvh.h"

#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace rtc {

struct ScalarBoxTest {
    struct Ray {
        Vec3 origin, inv_dir;
        float tmin;
        Ray(const Vec3& o, const Vec3& i, float t0) : origin(o), inv_dir(i), tmin(t0) {}
    };
    using Tmax = float;
    [[nodiscard]] static Tmax tmax(float t) { return t; }

    [[nodiscard]] static unsigned children(const BvhLaneBlock* block, std::uint32_t n, const Ray& r,
                                           Tmax tmax, float* tnear) {
        unsigned mask = 0;
        for (std::uint32_t i = 0; i < n; ++i) {
            const BvhLaneBlock& b = block[i / 4];
            const std::uint32_t l = i % 4;
            const Aabb box{{b.lo_x[l], b.lo_y[l], b.lo_z[l]}, {b.hi_x[l], b.hi_y[l], b.hi_z[l]}};
            tnear[i] = intersect_box(box, r.origin, r.inv_dir, r.tmin, tmax);
            if (tnear[i] != kInfinity) mask |= 1u << i;
        }
        return mask;
    }
};

#if defined(__SSE2__)
// Constants of the lane box test, in memory where the compiler cannot see
// their values: it reads them as operands of the instructions that use them.
// As known values they were rebuilt in a register at every node (a load and a
// shuffle each: every register holds the ray or the box's products).
// (core/box_test.cpp; two_level.h's passes_identity reads minus_zero.)
struct alignas(16) LaneConstants {
    float slab_pad[4];
    float infinity[4];
    float minus_zero[4];  // -0.0f: its bits (0x80000000) for integer compares
};
extern const LaneConstants kLaneConstants;

struct SseBoxTest {
    // Broadcast once per traversal.
    struct Ray {
        __m128 ox, oy, oz, ix, iy, iz, tmin;
        Ray(const Vec3& origin, const Vec3& inv_dir, float t0)
            : ox(_mm_set1_ps(origin.x)), oy(_mm_set1_ps(origin.y)), oz(_mm_set1_ps(origin.z)),
              ix(_mm_set1_ps(inv_dir.x)), iy(_mm_set1_ps(inv_dir.y)), iz(_mm_set1_ps(inv_dir.z)),
              tmin(_mm_set1_ps(t0)) {}
    };
    // Broadcast once per change (a hit), not at every node.
    using Tmax = __m128;
    [[nodiscard, gnu::always_inline]] static Tmax tmax(float t) { return _mm_set1_ps(t); }

    // The four children of one block: the hit mask (bit i for lane i) and
    // their entry distances in tnear[0, 4).
    [[nodiscard, gnu::always_inline]] static unsigned block(const BvhLaneBlock& b, const Ray& r, __m128 vtmax,
                                                            float* tnear) {
        const __m128 tx0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_x), r.ox), r.ix);
        const __m128 tx1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_x), r.ox), r.ix);
        const __m128 ty0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_y), r.oy), r.iy);
        const __m128 ty1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_y), r.oy), r.iy);
        const __m128 tz0 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.lo_z), r.oz), r.iz);
        const __m128 tz1 = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(b.hi_z), r.oz), r.iz);
        // std::min(a, b) is _mm_min_ps(b, a) and std::max(a, b) is _mm_max_ps(b, a).
        const auto mn = [](__m128 a, __m128 c) { return _mm_min_ps(c, a); };
        const auto mx = [](__m128 a, __m128 c) { return _mm_max_ps(c, a); };
        const __m128 near = mx(mx(mn(tx0, tx1), mn(ty0, ty1)), mx(mn(tz0, tz1), r.tmin));
        const __m128 far = mn(mn(mx(tx0, tx1), mx(ty0, ty1)), mn(mx(tz0, tz1), vtmax));
        _mm_storeu_ps(tnear, near);
        // A hit: near <= far * pad, and near finite (intersect_box's +inf is a miss).
        const __m128 pad = _mm_load_ps(kLaneConstants.slab_pad), inf = _mm_load_ps(kLaneConstants.infinity);
        const __m128 hit = _mm_and_ps(_mm_cmple_ps(near, _mm_mul_ps(far, pad)), _mm_cmpneq_ps(near, inf));
        return static_cast<unsigned>(_mm_movemask_ps(hit));
    }

    [[nodiscard, gnu::always_inline]] static unsigned children(const BvhLaneBlock* block, std::uint32_t n,
                                                               const Ray& r, Tmax vtmax, float* tnear) {
        // Nodes of one to four children (the default width) in one block, no
        // loop; an empty root (a BVH over no primitives) has no block to read.
        if (n - 1u < 4u) return SseBoxTest::block(*block, r, vtmax, tnear) & ((1u << n) - 1u);
        unsigned mask = 0;
        for (std::uint32_t base = 0; base < n; base += 4)
            mask |= SseBoxTest::block(block[base / 4], r, vtmax, tnear + base) << base;
        return mask & ((1u << n) - 1u);
    }
};

using BlockBoxTest = SseBoxTest;
#else
using BlockBoxTest = ScalarBoxTest;
#endif

}  // namespace rtc
