// The binned SAH sweep (see core/bvh_build_sah.h).
#include "core/bvh_build_sah.h"

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

}  // namespace

// The binned SAH sweep: for every axis and plane, the cost of splitting there.
// Only planes just after an occupied bin are priced: a plane after an empty
// bin splits the same primitives as the one before it, so it has bit for bit
// the same cost and would lose the tie anyway. This keeps small nodes cheap.
Split find_sah_split(const Bins& bins, const Occupied& used, const BinMap& map, float area_of_node,
                     const BuildOptions& o) {
    const float inv_area = area_of_node > 0.0f ? 1.0f / area_of_node : 0.0f;
    Split best;
    for (int axis = 0; axis < 3; ++axis) {
        if (!map.active[axis]) continue;
        const auto& box = bins.box[axis];
        const auto& count = bins.count[axis];
        const auto& u = used.bin[axis];
        const int m = used.count[axis];
        // Right-to-left sweep stores the cost of each right part.
        std::array<float, kMaxBins> right_cost;
        Box4 acc;
        std::uint32_t n = 0;
        for (int j = m - 1; j > 0; --j) {
            acc.extend(box[u[j]].lo, box[u[j]].hi);
            n += count[u[j]];
            right_cost[j] = area(acc) * static_cast<float>(n);
        }
        acc = {};
        n = 0;
        for (int j = 1; j < m; ++j) {  // plane after bin u[j - 1]
            acc.extend(box[u[j - 1]].lo, box[u[j - 1]].hi);
            n += count[u[j - 1]];
            const float cost =
                o.traversal_cost +
                o.intersection_cost * (area(acc) * static_cast<float>(n) + right_cost[j]) * inv_area;
            if (cost < best.cost) best = {axis, u[j - 1] + 1, cost};  // strict: ties keep the first
        }
    }
    return best;
}

}  // namespace rtc::bvh_detail
