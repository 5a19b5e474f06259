// The binned SAH sweep (see core/bvh_build_sah.h).
#include "core/build/bvh_build_sah.h"

namespace rtc::bvh_detail {
namespace {

// Aabb::surface_area() of a non-empty box, with the same operations in the
// same order; lane 3 of lo (a primitive id) is masked so no denormal meets
// the arithmetic.
float area(const Box4& b) {
    const V4 lo = reinterpret_cast<V4>(reinterpret_cast<I4>(b.lo) & I4{-1, -1, -1, 0});
    const V4 e = b.hi - lo;
    const V4 p = e * __builtin_shufflevector(e, e, 1, 2, 0, 3);  // xy, yz, zx
    return 2.0f * (p[0] + p[1] + p[2]);
}

// The SAH cost of a plane, given area x count of each side; one function so
// that the sweep and the two-primitive split round (and contract) alike.
float plane_cost(const BuildOptions& o, float left, float right, float inv_area) {
    return o.traversal_cost + o.intersection_cost * (left + right) * inv_area;
}

float inverse_area(float area_of_node) { return area_of_node > 0.0f ? 1.0f / area_of_node : 0.0f; }

// Eight lanes for the sweep (not in a function's signature: without AVX
// that would change the calling convention, which GCC warns about).
using V8 = float __attribute__((vector_size(32)));
using I8 = std::int32_t __attribute__((vector_size(32)));

}  // namespace

// The binned SAH sweep: for every axis and plane, the cost of splitting there.
// Only planes just after an occupied bin are priced: a plane after an empty
// bin splits the same primitives as the one before it, so it has bit for bit
// the same cost and would lose the tie anyway. This keeps small nodes cheap.
// The left parts (growing rightwards) and the right parts (growing leftwards)
// are grown together in the two halves of eight lanes, each in the order of
// a separate sweep, so each part's box and area are those of its own sweep;
// then the planes are priced in order.
Split find_sah_split(const Bins& bins, const Occupied& used, const BinMap& map, float area_of_node,
                     const BuildOptions& o) {
    const float inv_area = inverse_area(area_of_node);
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
        if (!map.active[axis]) continue;
        const auto& bin = bins.bin[axis];
        const auto& u = used.bin[axis];
        const int m = used.count[axis];
        // Area x count of the bins left of plane j (u[0, j)) and right of it (u[j, m)).
        std::array<float, kMaxBins> left_cost, right_cost;
        // The left part in lanes 0-3, the right part in lanes 4-7.
        V8 lo = V8{} + kInfinity, hi = -lo;
        std::uint32_t n_left = 0, n_right = 0;
        for (int k = 1; k < m; ++k) {
            const Bin& l = bin[u[k - 1]];
            const Bin& r = bin[u[m - k]];
            const V8 blo = __builtin_shufflevector(l.box.lo, r.box.lo, 0, 1, 2, 3, 4, 5, 6, 7);
            const V8 bhi = __builtin_shufflevector(l.box.hi, r.box.hi, 0, 1, 2, 3, 4, 5, 6, 7);
#ifdef __AVX__
            lo = _mm256_min_ps(blo, lo);  // Box4::extend's selections
            hi = _mm256_max_ps(bhi, hi);
#else
            lo = blo < lo ? blo : lo;
            hi = hi < bhi ? bhi : hi;
#endif
            n_left += l.count;
            n_right += r.count;
            // area() of each half, the same operations in the same order:
            // ((xy + yz) + zx) x 2, lo's lane 3 (an id) masked.
            const V8 e = hi - reinterpret_cast<V8>(reinterpret_cast<I8>(lo) & I8{-1, -1, -1, 0, -1, -1, -1, 0});
            const V8 p = e * __builtin_shufflevector(e, e, 1, 2, 0, 3, 5, 6, 4, 7);
            const V8 xy_yz = p + __builtin_shufflevector(p, p, 1, 1, 1, 1, 5, 5, 5, 5);
            const V8 a = 2.0f * (xy_yz + __builtin_shufflevector(p, p, 2, 2, 2, 2, 6, 6, 6, 6));
            left_cost[k] = a[0] * static_cast<float>(n_left);
            right_cost[m - k] = a[4] * static_cast<float>(n_right);
        }
        for (int j = 1; j < m; ++j) {  // plane after bin u[j - 1]
            const float cost = plane_cost(o, left_cost[j], right_cost[j], inv_area);
            if (cost < best.cost) best = {axis, u[j - 1] + 1, cost};  // strict: ties keep the first
        }
    }
    return best;
}

// Two primitives: an axis whose bins differ has exactly two occupied bins and
// one plane, priced area(lower) * 1 + area(upper) * 1. That sum is the same
// on every such axis (the primitives' own boxes; addition commutes exactly),
// so the first such axis wins the tie and the rest need no pricing. An axis
// whose bins agree has no plane at all. A NaN or infinite cost is never below
// the initial infinity, as in the sweep.
Split find_pair_split(const Ref& r0, const Ref& r1, I4 b0, I4 b1, const BinMap& map,
                      float area_of_node, const BuildOptions& o) {
    for (int axis = 0; axis < 3; ++axis) {
        if (!map.active[axis] || b0[axis] == b1[axis]) continue;
        const bool first_lower = b0[axis] < b1[axis];
        const Ref& lower = first_lower ? r0 : r1;
        const Ref& upper = first_lower ? r1 : r0;
        const float cost = plane_cost(o, area({lower.lanes(lower.lo), lower.lanes(lower.hi)}) * 1.0f,
                                      area({upper.lanes(upper.lo), upper.lanes(upper.hi)}) * 1.0f,
                                      inverse_area(area_of_node));
        Split best;
        if (cost < best.cost) best = {axis, std::min(b0[axis], b1[axis]) + 1, cost};
        return best;
    }
    return {};
}

}  // namespace rtc::bvh_detail
