// RDNA4-style oriented nodes on a built AABB tree: one rotation per node from
// a fixed table, chosen bottom up as AMD's GPURT does (core/obb_build.h).
//
// The rotation table. GPURT (src/shadersClean/common/ObbCommon.hlsli) packs
// 104 rotations as 9 six-bit codes into 26 magnitudes plus a sign; the
// hardware node stores a 7-bit index (0x7F = no rotation; RADV bvh.h). Its
// entries are AMD's and are not copied here. This stand-in has the same size
// and a similar coverage: entry k is the Duff et al. frame whose z axis is the
// k-th point of a Fibonacci spiral over the upper hemisphere (a frame's axes
// are lines, so a hemisphere suffices). Measured over 20,000 random
// directions, the angle to the nearest axis of any entry is at most 11.0
// degrees (mean 3.9) here, and at most 9.8 (mean 4.5) for the rows of AMD's
// decoded table: for a thin primitive only that angle matters.
//
// Choosing an entry: GPURT converts a primitive's frame to axis-angle, bins
// it and looks the index up (OrientedBoundingBoxes.hlsl); here the entry
// whose best-aligned axis is closest to the primitive's direction is taken.
#include "core/obb_build.h"

#include <cmath>
#include <numbers>

namespace rtc {

std::vector<glm::dmat3> rotation_table(int count) {
    std::vector<glm::dmat3> table;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < count; ++k) {
        const double z = 1.0 - (k + 0.5) / count;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * k;
        table.push_back(frame_from_axis({r * std::cos(phi), r * std::sin(phi), z}, DVec3(0.0)).rot);
    }
    return table;
}

int nearest_rotation(const std::vector<glm::dmat3>& table, const DVec3& axis) {
    const double len = glm::length(axis);
    if (!(len > 0.0) || !std::isfinite(len)) return -1;
    const DVec3 a = axis / len;
    int best = -1;
    double best_dot = -1.0;
    for (std::size_t k = 0; k < table.size(); ++k) {
        const DVec3 l = table[k] * a;  // the axis in the entry's frame: components = dots with its rows
        const double d = std::max({std::abs(l.x), std::abs(l.y), std::abs(l.z)});
        if (d > best_dot) best_dot = d, best = static_cast<int>(k);
    }
    return best;
}

namespace {

double half_area(const Aabb& b) {
    if (b.empty()) return 0.0;
    const DVec3 e(b.extent());
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Rounds the children's boxes outwards onto a grid of 2^bits - 1 steps of the
// node's extent per axis (the step a power of two, as RDNA4's per-axis exponent).
void quantize_children(BvhEntry* child, std::uint32_t n, int bits) {
    Aabb all;
    for (std::uint32_t i = 0; i < n; ++i) all.extend(child[i].box);
    if (all.empty()) return;
    for (int axis = 0; axis < 3; ++axis) {
        const double lo0 = all.lo[axis], extent = double(all.hi[axis]) - lo0;
        if (!(extent > 0.0)) continue;
        const double step = std::exp2(std::ceil(std::log2(extent / double((1 << bits) - 1))));
        for (std::uint32_t i = 0; i < n; ++i) {
            Aabb& b = child[i].box;
            if (b.empty()) continue;
            const double lo = lo0 + std::floor((double(b.lo[axis]) - lo0) / step) * step;
            const double hi = lo0 + std::ceil((double(b.hi[axis]) - lo0) / step) * step;
            float l = static_cast<float>(lo), h = static_cast<float>(hi);
            if (double(l) > lo) l = float_step_down(l);
            if (double(h) < hi) h = float_step_up(h);
            b.lo[axis] = std::min(l, b.lo[axis]);
            b.hi[axis] = std::max(h, b.hi[axis]);
        }
    }
}

class Quantizer {
public:
    Quantizer(ObbBvh& out, std::span<const BoundProxy> proxies, const QuantizeOptions& o)
        : out_(out), proxies_(proxies), o_(o), table_(rotation_table(o.rotations)) {
        leaf_rot_.resize(proxies.size());
        for (std::size_t i = 0; i < proxies.size(); ++i)
            leaf_rot_[i] = nearest_rotation(table_, DVec3(proxies[i].axis()));
    }

    // Processes the node whose children are entries [first, first + n);
    // appends the primitives below it to `prims`; returns its candidate rotation.
    int visit(std::uint32_t first, std::uint32_t n, const Aabb& node_box, std::vector<std::uint32_t>& prims) {
        std::vector<std::vector<std::uint32_t>> below(n);
        std::vector<int> candidate(n, -1);
        int largest = -1;
        double largest_area = -1.0, aabb_area = 0.0;
        for (std::uint32_t c = 0; c < n; ++c) {
            const BvhEntry e = out_.bvh.entries[first + c];
            if (e.is_inner()) {
                candidate[c] = visit(e.first, e.size(), e.box, below[c]);
            } else {
                for (std::uint32_t k = 0; k < e.size(); ++k) below[c].push_back(out_.bvh.prim_ids[e.first + k]);
                if (!below[c].empty()) candidate[c] = leaf_rot_[below[c].front()];
            }
            const double a = half_area(e.box);
            aabb_area += a;
            if (a > largest_area) largest_area = a, largest = static_cast<int>(c);
        }
        int rotation = largest >= 0 ? candidate[static_cast<std::size_t>(largest)] : -1;
        BvhEntry* child = out_.bvh.entries.data() + first;
        if (rotation >= 0) {
            ObbFrame f;
            f.rot = table_[static_cast<std::size_t>(rotation)];
            f.origin = DVec3(node_box.center());
            std::vector<Aabb> boxes(n);
            double obb_area = 0.0;
            for (std::uint32_t c = 0; c < n; ++c) {
                LocalBounds b;
                for (const std::uint32_t p : below[c]) b.add(f, proxies_[p]);
                boxes[c] = b.padded();
                obb_area += half_area(boxes[c]);
            }
            if (obb_area < o_.accept * aabb_area) {
                const auto index = static_cast<std::uint32_t>(out_.frames.frames.size());
                out_.frames.frames.push_back(f);
                for (std::uint32_t c = 0; c < n; ++c) {
                    child[c].box = boxes[c];
                    out_.frames.frame_of[first + c] = index;
                }
            } else {
                rotation = -1;  // GPURT: a rejected node passes INVALID_OBB up
            }
        }
        if (o_.quantize_bits > 0) quantize_children(child, n, o_.quantize_bits);
        for (const auto& v : below) prims.insert(prims.end(), v.begin(), v.end());
        return rotation;
    }

private:
    ObbBvh& out_;
    std::span<const BoundProxy> proxies_;
    QuantizeOptions o_;
    std::vector<glm::dmat3> table_;
    std::vector<int> leaf_rot_;
};

}  // namespace

ObbBvh quantize_obb_bvh(Bvh tree, std::span<const BoundProxy> proxies, const QuantizeOptions& options) {
    ObbBvh out;
    out.bvh = std::move(tree);
    out.frames.style = ObbStyle::PerNode;
    out.frames.frame_of.assign(out.bvh.entries.size(), kWorldFrame);
    Quantizer q(out, proxies, options);
    std::vector<std::uint32_t> all;
    (void)q.visit(out.bvh.root.first, out.bvh.root.size(), out.bvh.root.box, all);
    return out;
}

}  // namespace rtc
