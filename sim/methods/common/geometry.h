// What every method is built from: the scene's strands converted into
// primitives of one kind (pre-subdivided for phantom curves) and its mesh as
// triangles.
#pragma once

#include "core/aabb.h"
#include "core/obb_frames.h"
#include "intersectors/kinds.h"
#include "intersectors/triangle.h"
#include "scenes/convert.h"
#include "scenes/scene.h"

#include <vector>

namespace rtc {

struct Geometry {
    PrimitiveKind kind = PrimitiveKind::Capsule;
    PrimitiveArray prims;
    std::vector<Triangle> triangles;
    // Where each strand's primitives start (ascending, from 0); empty when
    // unknown (then all primitives count as one strand).
    std::vector<std::uint32_t> strand_first;

    [[nodiscard]] std::size_t primitive_count() const;
};

[[nodiscard]] Geometry make_geometry(const Scene& scene, PrimitiveKind kind, int subdivision);

// Per primitive what the oriented-box builders bound (core/obb_build.h):
// segments as their end points with the largest radius (a flat-capped
// cylinder lies inside the capsule of its radius), curves as their control
// points with the largest radius (convex hull property).
[[nodiscard]] std::vector<BoundProxy> bound_proxies(const Geometry& geometry);

// The same for the mesh's triangles: the three vertices (radius 0), ordered
// so that the proxy's axis is the triangle's longest edge, the direction a
// thin triangle (a grass blade's, a hair card's) runs along. GPURT frames a
// triangle by its first edge and normal (FetchTriKdopObbMatrixIndex); the
// builders here take one axis, and the longest edge is the one a sliver
// needs.
[[nodiscard]] std::vector<BoundProxy> triangle_proxies(const Geometry& geometry);

// The largest radius of primitive `index` (a strand's thickness at its
// thickest: what hit distances are compared against).
[[nodiscard]] float primitive_radius(const Geometry& geometry, std::uint32_t index);

// World bounds of every primitive and triangle (for camera framing).
[[nodiscard]] Aabb geometry_bounds(const Geometry& geometry);

}  // namespace rtc
