// Oriented-box BVHs: the BVH layout of core/bvh.h whose child boxes may be
// given in a rotated frame, in the two styles of hardware since Turing:
// - PerChild (Woop et al. 2014, "Exploiting Local Orientation Similarity for
//   Efficient Ray Traversal of Hair and Fur"; Embree bvh_node_obb.h): a node
//   is aligned or oriented; every child of an oriented node has its own frame
//   and is tested with its own transform (one ObbBoxTest per child).
// - PerNode (AMD RDNA4; RADV bvh.h `obb_matrix_index`, GPURT): a node has at
//   most one rotation, shared by all its children; the ray is rotated once
//   per node (NodeRotate) and the children are ordinary box tests in that frame.
//
// A rotated child box is an Aabb in its frame (local = rot * (world - origin)).
// The simulator tests rotated boxes in double, with boxes computed in double
// from the primitives and rounded outwards to float, so the test never culls a
// ray that reaches a primitive inside the box (the hardware keeps its float
// test conservative its own way: GPURT pads by 7.15e-7 of the longest extent).
#pragma once

#include "core/bvh.h"
#include "core/events.h"
#include "core/float_step.h"
#include "core/traverse.h"

#include <glm/mat3x3.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rtc {

// What an oriented-box builder knows of a primitive: it lies within `radius`
// of the convex hull of `points` (a segment repeats its end point; a cubic
// Bezier gives its control points), and `axis` is its direction (p3 - p0).
struct BoundProxy {
    std::array<Vec3, 4> points{};
    float radius = 0.0f;
    [[nodiscard]] Vec3 axis() const { return points[3] - points[0]; }
};

struct ObbFrame {
    glm::dmat3 rot{1.0};  // rows: the frame's unit axes (local = rot * (world - origin))
    DVec3 origin{0.0};
    [[nodiscard]] DVec3 local(const DVec3& p) const { return rot * (p - origin); }
};

// The frame whose z axis is `axis` (x, y from Duff et al. 2017's basis, as
// intersectors/frame.h), or the world axes when `axis` is zero or not finite.
[[nodiscard]] ObbFrame frame_from_axis(const DVec3& axis, const DVec3& origin);

// Bounds of proxies in a frame, accumulated in double, rounded outwards with a
// relative pad of 16 float ulps of the coordinates' magnitude.
struct LocalBounds {
    DVec3 lo{kInfinity}, hi{-kInfinity};
    void add(const ObbFrame& f, const BoundProxy& p);
    void add(const LocalBounds& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    [[nodiscard]] double half_area() const;  // of the unpadded box (SAH)
    [[nodiscard]] Aabb padded() const;
};

inline constexpr std::uint32_t kWorldFrame = 0xFFFFFFFFu;

enum class ObbStyle : std::uint8_t { PerChild, PerNode };

// The rotations of a BVH: per entry of Bvh::entries its frame (kWorldFrame =
// an ordinary world-space box). With PerNode all children of a node share one.
struct ObbFrames {
    ObbStyle style = ObbStyle::PerChild;
    std::vector<std::uint32_t> frame_of;
    std::vector<ObbFrame> frames;

    [[nodiscard]] std::size_t rotated_entries() const;
    [[nodiscard]] std::size_t memory_bytes() const {
        return frame_of.capacity() * sizeof(std::uint32_t) + frames.capacity() * sizeof(ObbFrame);
    }
};

struct ObbBvh {
    Bvh bvh;  // root box in world space; child boxes in their entry's frame
    ObbFrames frames;
};

// Woop et al. 2014 / Embree `bvh_builder_hair.h`: top down, each wide node
// filled by splitting its largest child; per split the lowest SAH of (a) a
// binned object split in world space, (b) the same in the frame of the first
// primitive's direction, (c) a strand split (two direction clusters, each
// side bounded in its own frame); (b) and (c) are tried only while (a) costs
// more than `try_oriented` x the leaf SAH. Unlike Embree, whether a node is
// oriented is then decided by the SAH of its own terms (its child tests and
// its children's box areas), bottom up; each child of an oriented node gets
// the frame of its primitives' mean direction and its box in that frame.
// One primitive per leaf, as for custom primitives on the hardware. The
// costs are in units of one aligned box test; defaults are estimates for an
// RT unit (turing-per-ray-guess: a hand-over plus a program is ~350 cycles, a box test
// 4, a node fetch 8), not Embree's CPU constants (1, 5, 6).
struct ObbBuildOptions {
    int width = 4;
    int bins = 16;
    double traversal_aligned = 1.0;   // one aligned child box test
    double traversal_oriented = 2.0;  // one oriented child test (transform + box)
    double node = 2.0;                // a node fetch
    double intersection = 50.0;       // a hand-over + the intersection program
    double try_oriented = 0.7;        // Embree: oriented splits only if bestSAH > 0.7 leafSAH
};
[[nodiscard]] ObbBvh build_obb_bvh(std::span<const Aabb> boxes, std::span<const BoundProxy> proxies,
                                   const ObbBuildOptions& options);

// A fixed table of `count` rotations (RDNA4's hardware reads a 7-bit index
// into 104 of them; see obb_bvh_quantize.cpp for how this stand-in is made).
[[nodiscard]] std::vector<glm::dmat3> rotation_table(int count);
// The entry with an axis closest to `axis` (largest |dot|), or -1 for a zero axis.
[[nodiscard]] int nearest_rotation(const std::vector<glm::dmat3>& table, const DVec3& axis);

// AMD RDNA4 / GPURT (RefitOrientedBounds3_1.hlsl) on a built AABB tree: bottom
// up, a node's candidate rotation is that of its child with the largest AABB
// area (a leaf's: its primitive's nearest table rotation); the children are
// bounded in that frame and the rotation kept when the sum of their areas is
// below `accept` x the sum of their AABB areas (GPURT: 1.12); a rejected node
// passes no candidate up. `quantize_bits` > 0 then rounds every node's child
// boxes outwards to that many bits of the node's extent (RDNA4: 12).
struct QuantizeOptions {
    int rotations = 104;
    double accept = 1.12;
    int quantize_bits = 12;
};
[[nodiscard]] ObbBvh quantize_obb_bvh(Bvh tree, std::span<const BoundProxy> proxies,
                                      const QuantizeOptions& options);

namespace obb_detail {

struct DRay {
    DVec3 origin, inv_dir;
};

[[nodiscard]] inline DVec3 safe_inverse(const DVec3& d) {
    auto inv = [](double x) { return x == 0.0 ? (std::signbit(x) ? -1e300 : 1e300) : 1.0 / x; };
    return {inv(d.x), inv(d.y), inv(d.z)};
}

// Slab test in double; the entry distance rounded down to float, or +inf.
[[nodiscard]] inline float intersect_box(const Aabb& b, const DRay& r, double tmin, double tmax) {
    const DVec3 lo(b.lo), hi(b.hi);
    const DVec3 t0 = (lo - r.origin) * r.inv_dir, t1 = (hi - r.origin) * r.inv_dir;
    const DVec3 tn = glm::min(t0, t1), tf = glm::max(t0, t1);
    const double tnear = std::max({tn.x, tn.y, tn.z, tmin});
    const double tfar = std::min({tf.x, tf.y, tf.z, tmax});
    if (!(tnear <= tfar + std::abs(tfar) * 1e-12)) return kInfinity;
    float t = static_cast<float>(tnear);
    if (static_cast<double>(t) > tnear) t = float_step_down(t);
    return t;
}

}  // namespace obb_detail

// traverse() (core/traverse.h) over an oriented-box BLAS, with its events.
template <TraversalMode Mode, class Sink, class LeafFn>
float traverse_obb(const Bvh& bvh, const ObbFrames& fr, const Ray& ray, float tmax, Sink& sink,
                   LeafFn&& on_leaf) {
    struct Pending { std::uint32_t first, count; float tnear; };
    Pending stack[kTraversalStackSize];
    int top = 0;
    const float tmin = ray.tmin;
    const Vec3 inv_dir = safe_inverse(ray.direction);
    const DVec3 o(ray.origin), d(ray.direction);
    stack[top++] = {bvh.root.first, bvh.root.count, tmin};
    float nearest = kInfinity;
    while (top > 0) {
        const Pending p = stack[--top];
        if (Mode == TraversalMode::Closest && p.tnear > tmax) continue;
        if (!(p.count & BvhEntry::kInnerBit)) {
            const float t = on_leaf(p.first, p.count, tmax);
            if (t < nearest) nearest = t;
            if (Mode == TraversalMode::Closest && t < tmax) tmax = t;
            if (Mode == TraversalMode::AnyHit && t < kInfinity) return t;
            continue;
        }
        sink.on(Event::BlasNodeVisit);
        const std::uint32_t n = p.count & ~BvhEntry::kInnerBit;
        const BvhEntry* child = bvh.entries.data() + p.first;
        const std::uint32_t* frame = fr.frame_of.data() + p.first;
        std::uint32_t current = kWorldFrame;
        obb_detail::DRay local{};
        const int base = top;
        for (std::uint32_t i = 0; i < n; ++i) {
            float t;
            if (frame[i] == kWorldFrame) {
                sink.on(Event::BlasBoxTest);
                t = intersect_box(child[i].box, ray.origin, inv_dir, tmin, tmax);
            } else {
                if (fr.style == ObbStyle::PerChild) {
                    sink.on(Event::ObbBoxTest);
                } else {
                    sink.on(Event::BlasBoxTest);
                    if (current == kWorldFrame) sink.on(Event::NodeRotate);
                }
                if (frame[i] != current) {
                    const ObbFrame& f = fr.frames[frame[i]];
                    local = {f.local(o), obb_detail::safe_inverse(f.rot * d)};
                    current = frame[i];
                }
                t = obb_detail::intersect_box(child[i].box, local, tmin, tmax);
            }
            if (t == kInfinity) continue;
            int j = top++;
            for (; j > base && stack[j - 1].tnear < t; --j) stack[j] = stack[j - 1];
            stack[j] = {child[i].first, child[i].count, t};
        }
    }
    return nearest;
}

}  // namespace rtc
