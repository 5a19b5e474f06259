// Internal to the BVH builder: the binary SAH tree collapsed into nodes of the
// requested width by repeatedly opening the child with the largest surface
// area (the usual collapse for wide hardware BVHs; Ylitie et al. 2017 use a
// cost-based variant).
#pragma once

#include "core/build/bvh_build_binary.h"

namespace rtc::bvh_detail {

// Fills bvh.root's link and bvh.entries from `tree` (whose root is inner),
// `primitives` the primitive count, on `threads` threads; the entries are the
// same for any thread count. Consumes the tree: its spare memory and binary
// nodes are freed as soon as the collapse is done with them, so that the
// entries, and then the caller's next arrays, take their pages.
void collapse_tree(BinaryTree tree, std::size_t primitives, int width, unsigned threads, Bvh& bvh);

}  // namespace rtc::bvh_detail
