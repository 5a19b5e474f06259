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
// that both sweeps round (and contract) alike.
float plane_cost(const BuildOptions& o, float left, float right, float inv_area) {
    return o.traversal_cost + o.intersection_cost * (left + right) * inv_area;
}

float inverse_area(float area_of_node) { return area_of_node > 0.0f ? 1.0f / area_of_node : 0.0f; }

}  // namespace

// The binned SAH sweep: for every axis and plane, the cost of splitting there.
// Only planes just after an occupied bin are priced: a plane after an empty
// bin splits the same primitives as the one before it, so it has bit for bit
// the same cost and would lose the tie anyway. This keeps small nodes cheap.
Split find_sah_split(const Bins& bins, const Occupied& used, const BinMap& map, float area_of_node,
                     const BuildOptions& o) {
    const float inv_area = inverse_area(area_of_node);
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
        if (!map.active[axis]) continue;
        const auto& bin = bins.bin[axis];
        const auto& u = used.bin[axis];
        const int m = used.count[axis];
        // Right-to-left sweep stores the cost of each right part.
        std::array<float, kMaxBins> right_cost;
        Box4 acc;
        std::uint32_t n = 0;
        for (int j = m - 1; j > 0; --j) {
            acc.extend(bin[u[j]].box.lo, bin[u[j]].box.hi);
            n += bin[u[j]].count;
            right_cost[j] = area(acc) * static_cast<float>(n);
        }
        acc = {};
        n = 0;
        for (int j = 1; j < m; ++j) {  // plane after bin u[j - 1]
            acc.extend(bin[u[j - 1]].box.lo, bin[u[j - 1]].box.hi);
            n += bin[u[j - 1]].count;
            const float cost = plane_cost(o, area(acc) * static_cast<float>(n), right_cost[j], inv_area);
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
