// Internal to the BVH builder: binned SAH (Wald 2007, "On fast construction
// of SAH-based bounding volume hierarchies"). Centroids are binned along each
// axis of the node's centroid box, and the sweep prices the planes between
// bins by the surface area heuristic.
#pragma once

#include "core/bvh.h"
#include "core/build/bvh_build_refs.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace rtc::bvh_detail {

constexpr int kMaxBins = 64;

// Maps a centroid to its bin along one axis of the node's centroid box.
struct BinMap {
    int bins;
    Vec3 lo, scale;
    std::array<bool, 3> active;  // axes along which the centroids spread
    V4 lo4, scale4;              // lo and scale in lanes, built once per node
    I4 last;                     // bins - 1 in every lane
    V4 lastf;                    // the same as floats
    BinMap(const Aabb& cbox, int n_bins) : bins(n_bins), lo(cbox.lo) {
        for (int axis = 0; axis < 3; ++axis) {
            active[axis] = cbox.hi[axis] > cbox.lo[axis];
            scale[axis] = static_cast<float>(bins) / (cbox.hi[axis] - cbox.lo[axis]);
        }
        lo4 = V4{lo.x, lo.y, lo.z, 0.0f};
        scale4 = V4{scale.x, scale.y, scale.z, 0.0f};
        last = I4{} + (bins - 1);
        lastf = V4{} + static_cast<float>(bins - 1);
    }
    // All three axes at once: clamp(int((c - lo) * scale), 0, bins - 1) in
    // each lane, with the conversion's quirks (NaN and |x| >= 2^31 give
    // INT_MIN, so bin 0). An axis without spread puts everything into bin 0.
    [[nodiscard]] I4 of(const Ref& r) const {
        const V4 x = (r.centroid_lanes() - lo4) * scale4;
#ifdef __SSE__
        // Clamped as floats (SSE2 has no integer min/max), to the same bins:
        // maxps picks 0 for NaN, and the mask sends x >= 2^31 to bin 0.
        const V4 y = _mm_min_ps(_mm_max_ps(x, V4{}), lastf);
        return __builtin_convertvector(y, I4) & (x < 2147483648.0f);
#else
        const I4 zero{};
        I4 b = __builtin_convertvector(x, I4);
        b = b < zero ? zero : b;
        return b > last ? last : b;
#endif
    }
};

// One bin: its box and its count side by side, a bin to a cache line, so that
// binning a reference reaches both from one offset per axis (as two arrays,
// box and count, each axis took two address computations: the big nodes'
// binning loop was 51 instructions per reference).
struct alignas(64) Bin {
    Box4 box;
    std::uint32_t count = 0;
};

struct Bins {
    std::array<std::array<Bin, kMaxBins>, 3> bin;

    void reset(int bins) {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < bins; ++b) bin[axis][b] = {};
    }
    // All three axes at once, branch-free (an axis without spread is never
    // priced).
    // The three bins' byte offsets come from one shift of the bin vector
    // (indexing bin[axis][b[axis]] costs a shift and an add per axis).
    void add(const Ref& r, I4 b) {
        const V4 rlo = r.lanes(r.lo), rhi = r.lanes(r.hi);
        const I4 offset = b * static_cast<std::int32_t>(sizeof(Bin));  // 0 .. (bins - 1) x 64
        for (int axis = 0; axis < 3; ++axis) {
            auto* const row = reinterpret_cast<unsigned char*>(bin[axis].data());
            Bin& into = *reinterpret_cast<Bin*>(row + static_cast<std::uint32_t>(offset[axis]));
            into.box.extend(rlo, rhi);
            ++into.count;
        }
    }
    void add(const Bins& o, int bins) {  // o's primitives come after ours
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < bins; ++b) {
                bin[axis][b].box.extend(o.bin[axis][b].box.lo, o.bin[axis][b].box.hi);
                bin[axis][b].count += o.bin[axis][b].count;
            }
    }
};

struct Split {
    int axis = -1;
    int bin = 0;  // primitives in bins [0, bin) go left
    float cost = kInfinity;
};
// The occupied bins of each axis, in order.
struct Occupied {
    std::array<std::array<int, kMaxBins>, 3> bin;
    std::array<int, 3> count{};
    Occupied() = default;
    Occupied(const Bins& bins, const BinMap& map) {
        for (int axis = 0; axis < 3; ++axis)
            for (int b = 0; b < map.bins; ++b)
                if (bins.bin[axis][b].count > 0) bin[axis][count[axis]++] = b;
    }
};

// The best split over all axes (axis -1 when no plane separates anything):
// lowest cost, ties to the smallest axis and bin.
[[nodiscard]] Split find_sah_split(const Bins& bins, const Occupied& used, const BinMap& map,
                                   float area_of_node, const BuildOptions& o);

// find_sah_split for a node of exactly two primitives, r0 and r1 in bins b0
// and b1 (from BinMap::of): the same split, bit for bit, without the bins.
[[nodiscard]] Split find_pair_split(const Ref& r0, const Ref& r1, I4 b0, I4 b1, const BinMap& map,
                                    float area_of_node, const BuildOptions& o);

}  // namespace rtc::bvh_detail
