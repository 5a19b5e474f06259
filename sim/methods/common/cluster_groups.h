// The geometry behind the clustered masquerade (cluster.cpp): which
// primitives share an instance, and the frame each group's BLAS is built in.
//
// Grouping (ClusterStrategy), `size` = k primitives per cluster:
// - Strand: each strand cut into runs of k consecutive segments (its last
//   run takes the rest), so a cluster is a piece of one strand; strands of
//   fewer than k segments are clusters of their own (the fur and bear models
//   have 3 segments per strand). O(N), no geometry read.
// - Orientation: top-down splitting in the spirit of Woop et al. 2014
//   (Embree's hair builder): each group of more than k primitives is split in
//   two, either spatially (object median along the principal axis of its
//   points) or by orientation (Embree's strand split: the dominant direction
//   against the direction least aligned with it, each primitive to the closer
//   one), whichever gives the smaller sum over both halves of (primitives x
//   surface area of the half's box in its own principal frame). Cuts fall on
//   multiples of k, so every cluster has exactly k primitives except the last
//   (the remainder) and there are ceil(N / k) of them. Per level, two passes
//   for the keys and per candidate a selection (std::nth_element), a gather,
//   a moments pass and a box pass, all over members held in order in their
//   group's slice of a buffer; log2(N / k) levels. Scratch: three copies of
//   the primitives with their indices and two keys per primitive (120 B per
//   capsule). The 20 M-segment fur at k = 256: 25 CPU-s, 6.1x less than with
//   indices into the scene (docs/benchmark.md).
//
// A strand that ends and starts again (Geometry::strand_first) is never
// bridged by Strand runs: consecutive strands of a file can be far apart
// (Sintel's are), and one such run makes a cluster box across the head.
//
// Frames (ClusterFrame) of a cluster of two or more primitives, each a
// rotation about the mean of the primitives' sphere centres:
// - Principal: x = the dominant direction of the primitives (largest
//   eigenvector of sum length * d d^T over their unit chords d), y = the
//   principal axis of their points across x.
// - Best: the smallest of four candidates by the sum of the member boxes'
//   areas plus the cluster box's area: Principal, the principal axes of the
//   points, the world axes, and the cluster's chord (its first point to its
//   last) with y as in Principal.
#pragma once

#include "core/affine.h"
#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "sim/methods/method.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rtc {

// A primitive as up to four spheres whose convex hull contains it: the end
// spheres of a capsule or link, of a cylinder (it lies in the capsule of its
// radius), the control points of a phantom curve grown by its largest radius
// (the convex hull property, as phantom.h bounds it).
struct Spheres {
    std::array<Vec3, 4> center{};
    std::array<float, 4> radius{};
    int count = 0;
};

[[nodiscard]] inline Spheres spheres(const Cylinder& c) {
    const float r = std::max(c.radius, 0.0f);
    return {{c.p0, c.p1}, {r, r}, 2};
}
[[nodiscard]] inline Spheres spheres(const Capsule& c) {
    const float r = std::max(c.radius, 0.0f);
    return {{c.p0, c.p1}, {r, r}, 2};
}
[[nodiscard]] inline Spheres spheres(const Link& k) {
    return {{k.p0, k.p1}, {std::max(k.r0, 0.0f), std::max(k.r1, 0.0f)}, 2};
}
[[nodiscard]] inline Spheres spheres(const PhantomCurve& c) {
    const float r = max_radius(c);
    return {c.cp, {r, r, r, r}, 4};
}

struct Clusters {
    std::vector<std::uint32_t> members;  // primitive indices, cluster after cluster, ascending in each
    std::vector<std::uint32_t> first;    // cluster c is members[first[c] .. first[c + 1])
    [[nodiscard]] std::size_t count() const { return first.empty() ? 0 : first.size() - 1; }
};

// How many clusters group_strand makes (sum over strands of ceil(n / k)).
[[nodiscard]] std::uint64_t strand_cluster_count(std::size_t primitives,
                                                 std::span<const std::uint32_t> strand_first, int size);
[[nodiscard]] Clusters group_strand(std::size_t primitives, std::span<const std::uint32_t> strand_first,
                                    int size);
template <class Prim>
[[nodiscard]] Clusters group_orientation(std::span<const Prim> prims, int size, unsigned threads);

// A cluster's BLAS frame and its members' boxes in that frame, padded as
// segment_obb pads an OBB (intersectors/frame.h): by 2^-10 of each half-extent
// and by kObbSlack of the member's distance from the frame's origin, so the
// hardware's float ray transform never culls a ray that touches a member.
struct FramedCluster {
    Affine world_from_frame;  // a rotation and a translation
    std::vector<Aabb> boxes;  // one per member, in member order
};

template <class Prim>
[[nodiscard]] FramedCluster frame_cluster(std::span<const Prim> prims,
                                          std::span<const std::uint32_t> members, ClusterFrame choice);

}  // namespace rtc
