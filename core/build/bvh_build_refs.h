// Internal to the BVH builder (core/bvh_build*.cpp): how primitives travel
// through the build (packed references) and the four-lane box arithmetic the
// per-primitive loops use.
#pragma once

#include "core/aabb.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

#ifdef __SSE__
#include <immintrin.h>
#endif

namespace rtc::bvh_detail {

// Four-lane float vectors (GCC/Clang vector extensions: SSE on x86-64, plain
// code elsewhere) for the per-primitive loops; lane 3 is ignored.
using V4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));

// A box in lanes, extended with exactly the comparisons of Aabb::extend (so
// ties between -0 and +0 resolve the same way).
struct Box4 {
    V4 lo = {kInfinity, kInfinity, kInfinity, kInfinity};
    V4 hi = -lo;
    void extend(V4 blo, V4 bhi) {
#ifdef __SSE__
        // minps(a, b) is a < b ? a : b and maxps(a, b) is a > b ? a : b, the
        // same selections; GCC does not see that and emits compare-and-blend.
        lo = _mm_min_ps(blo, lo);
        hi = _mm_max_ps(bhi, hi);
#else
        lo = blo < lo ? blo : lo;
        hi = hi < bhi ? bhi : hi;
#endif
    }
    [[nodiscard]] Aabb aabb() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
};

// Trivial, so that the large reference buffers are allocated, not zeroed.
// Each vector starts a 16-byte lane group. 32 bytes: the centroid is the
// box's centre, Aabb::center()'s operations worked out where it is used
// rather than stored (every split streams all references of its node from
// one buffer into the other; with a stored centroid a reference was 48 bytes).
struct alignas(16) Ref {
    Vec3 lo;
    std::uint32_t id;
    Vec3 hi;
    float zero;  // so that arithmetic on hi's spare lane never meets a denormal
    [[nodiscard]] Aabb box() const { return {lo, hi}; }
    [[nodiscard]] V4 lanes(const Vec3& member) const {  // member of this Ref and the word after it
        V4 v;
        std::memcpy(&v, &member, sizeof v);
        return v;
    }
    [[nodiscard]] Vec3 centroid() const { return 0.5f * (lo + hi); }  // Aabb::center()
    // centroid() in lanes 0-2, lane 3 zero (the id in lo's spare lane is masked).
    [[nodiscard]] V4 centroid_lanes() const {
        const V4 l = reinterpret_cast<V4>(reinterpret_cast<I4>(lanes(lo)) & I4{-1, -1, -1, 0});
        return 0.5f * (l + lanes(hi));
    }
};
static_assert(sizeof(Ref) == 32);

static_assert(std::is_trivially_default_constructible_v<Ref>);

// The bounds of a set of references: of their boxes and of their centroids.
struct Bounds {
    Aabb box, cbox;  // of the primitives' boxes, of their centroids
    void add(const Ref& r) {
        box.extend(r.box());
        cbox.extend(r.centroid());
    }
    void add(const Bounds& b) {
        box.extend(b.box);
        cbox.extend(b.cbox);
    }
};

}  // namespace rtc::bvh_detail
