// The numerical range of scene geometry, one constant for every loader,
// generator and config key (issue 38, item 8): what the loaders accept, every
// method can build and trace.
//
// Why 1e12. The binding limit is the OBB methods' instance transform, a float
// 3x3 whose columns are an OBB's axes times its half-extents: its determinant
// (the product of the half-extents) must stay finite for the transform to be
// inverted, so half-extents must stay below cbrt(FLT_MAX) ~ 7e12. Measured
// with `simulate` on one segment (obb, leaf-obb, cluster): radius 1e12
// works, 1e13 fails ("transform is singular or not finite", exit 3); with
// radius 1, length 1e16 works, 1e17 fails (the transform's error bound, added
// to the small half-extents, grows with the length). Coordinates and radii
// within +-1e12 keep a cluster's OBB around the whole scene (half-extents up
// to sqrt(3) 1e12 plus the radius) finite, and were measured to build and
// trace under every method, as were radii down to 1e-18 (the smallest
// length a config accepts). Squared distances (1e24) and camera framing stay
// far from float overflow.
#pragma once

namespace rtc {

inline constexpr double kMaxCoordinate = 1e12;  // |coordinate| and radius
inline constexpr const char* kMaxCoordinateText = "1e12";  // for messages

}  // namespace rtc
