// The oriented-box BVH builders (core/build/obb_bvh_build.cpp,
// obb_bvh_quantize.cpp): Woop et al. 2014's per-child frames and GPURT's
// per-node table rotations, into the trees of core/obb_frames.h.
#pragma once

#include "core/obb_frames.h"

#include <glm/mat3x3.hpp>

#include <span>
#include <vector>

namespace rtc {

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

}  // namespace rtc
