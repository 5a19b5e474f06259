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
// This header is the data: the frames, a tree with them, and what the
// builders bound (core/obb_build.h builds them; core/obb_nodes.h traverses them).
#pragma once

#include "core/bvh.h"

#include <glm/mat3x3.hpp>

#include <array>
#include <cstdint>
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

}  // namespace rtc
