// The oriented node styles of the traversal kernel (core/traverse.h): a
// BLAS whose child boxes may be given in a rotated frame (core/obb_frames.h),
// PerChild (one ObbBoxTest per rotated child) or PerNode (one NodeRotate per
// node with rotated children, then ordinary box tests in its frame).
//
// The kernel's loop, order and culling are the axis-aligned style's; only
// the child tests differ. Children are read from Bvh::entries (whose boxes
// are in their entry's frame; an oriented tree's lanes are not kept in step)
// and tested one by one: world boxes by intersect_box() (core/aabb.h), rotated
// boxes in double, with boxes computed in double from the primitives and
// rounded outwards to float, so the test never culls a ray that reaches a
// primitive inside the box (the hardware keeps its float test conservative
// its own way: GPURT pads by 7.15e-7 of the longest extent).
#pragma once

#include "core/aabb.h"
#include "core/bvh.h"
#include "core/child_hit.h"
#include "core/events.h"
#include "core/float_step.h"
#include "core/obb_frames.h"
#include "core/traverse.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rtc {

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

class ObbNodes {
public:
    ObbNodes(const Bvh& bvh, const ObbFrames& frames, const Ray& ray)
        : entries_(bvh.entries.data()), frame_of_(frames.frame_of.data()), frames_(frames.frames.data()),
          style_(frames.style), root_{bvh.root.first, bvh.root.count}, origin_(ray.origin),
          inv_dir_(safe_inverse(ray.direction)), tmin_(ray.tmin), o_(ray.origin),
          d_(ray.direction) {}

    [[nodiscard]] BvhLaneBlock::Child root() const { return root_; }

    // The children of the node at entries [first, first + n), in order. A
    // rotated frame's ray is made once per run of children sharing it.
    using Tmax = float;
    [[nodiscard]] static Tmax tmax(float t) { return t; }

    template <Event kBoxTest, class Sink>
    [[nodiscard]] unsigned test(std::uint32_t first, std::uint32_t n, Sink& sink, float tmax, float* tnear) const {
        const BvhEntry* child = entries_ + first;
        const std::uint32_t* frame = frame_of_ + first;
        std::uint32_t current = kWorldFrame;
        obb_detail::DRay local{};
        unsigned mask = 0;
        for (std::uint32_t i = 0; i < n; ++i) {
            float t;
            if (frame[i] == kWorldFrame) {
                sink.on(kBoxTest);
                t = intersect_box(child[i].box, origin_, inv_dir_, tmin_, tmax);
            } else {
                if (style_ == ObbStyle::PerChild) {
                    sink.on(Event::ObbBoxTest);
                } else {
                    sink.on(kBoxTest);
                    if (current == kWorldFrame) sink.on(Event::NodeRotate);
                }
                if (frame[i] != current) {
                    const ObbFrame& f = frames_[frame[i]];
                    local = {f.local(o_), obb_detail::safe_inverse(f.rot * d_)};
                    current = frame[i];
                }
                t = obb_detail::intersect_box(child[i].box, local, tmin_, tmax);
            }
            tnear[i] = t;
            if (t != kInfinity) mask |= 1u << i;
        }
        return mask;
    }


    template <class Descend>
    [[nodiscard]] ChildHit children(std::uint32_t first, std::uint32_t, const float* tnear,
                                    Descend&& descend) const {
        const BvhEntry* child = entries_ + first;
        return descend([&](std::uint32_t i) { return ChildHit{child_word(child[i]), tnear[i]}; });
    }

private:
    const BvhEntry* entries_;
    const std::uint32_t* frame_of_;
    const ObbFrame* frames_;
    ObbStyle style_;
    BvhLaneBlock::Child root_;
    Vec3 origin_, inv_dir_;
    float tmin_;
    DVec3 o_, d_;
};

// The kernel over an oriented-box BLAS (BLAS events).
template <TraversalMode Mode, class Sink, class LeafFn>
float traverse_obb(const Bvh& bvh, const ObbFrames& frames, const Ray& ray, float tmax, Sink& sink,
                   LeafFn&& on_leaf) {
    return traverse_nodes<Mode, kBlasEvents>(ObbNodes(bvh, frames, ray), ray.tmin, tmax, sink, on_leaf);
}

}  // namespace rtc
