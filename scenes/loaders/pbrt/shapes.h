// pbrt-v4 shapes -> the scene's plain data, in the shape's object space
// (the loader applies the transform). What is exact and what approximated:
// - `trianglemesh`: exact. `bilinearmesh`: each patch as two triangles
//   (exact for planar patches). `loopsubdiv`: its control mesh (the limit
//   surface is not computed).
// - `curve`: one strand per shape. Each segment (bezier: 3n+1 or 2n+1 points;
//   bspline: n - degree segments, converted to Bezier form as pbrt-v4 does)
//   is sampled at `degree` equal parameter steps, so the strand's points lie
//   on pbrt's curve and a bezier curve gives as many points as it has
//   control points; consecutive segments share their end point. Cylinder,
//   capsule and link primitives inscribe the curve with these straight
//   pieces; the phantom kind fits its own B-spline through them (close to,
//   but not exactly, pbrt's curve). Radius = width / 2, interpolated from
//   width0 to width1 along the whole curve as in pbrt-v4.
// - curve types: `cylinder` is a tube of that radius (exact); `flat` (a
//   ribbon facing the ray) has the same silhouette as that tube and becomes
//   one; `ribbon` (oriented by the normals N, which are checked and then
//   ignored) also becomes the tube, which is wider than the ribbon seen at
//   a grazing angle. `splitdepth` (pbrt's refinement at render time) is
//   checked and ignored: the config's `subdivision` plays that role.
#pragma once

#include "scenes/loaders/pbrt/params.h"
#include "scenes/scene.h"

namespace rtc::pbrt {

// Appends one strand (curve) or triangles (meshes), untransformed.
void add_curve(const ParamList& params, Strands& out);
void add_triangle_mesh(const ParamList& params, TriangleMesh& out);
void add_bilinear_mesh(const ParamList& params, TriangleMesh& out);

}  // namespace rtc::pbrt
