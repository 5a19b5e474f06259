// pbrt-v4 shapes -> the scene's plain data, in the shape's object space
// (the loader applies the transform). What is exact and what approximated:
// - `trianglemesh`: exact. `bilinearmesh`: each patch as two triangles
//   (exact for planar patches). `loopsubdiv`: its control mesh (the limit
//   surface is not computed).
// - `curve`: one strand per shape. Each segment (bezier: 3n+1 or 2n+1 points;
//   bspline: n - degree segments) is converted to cubic Bezier form as
//   pbrt-v4 does (quadratics degree-elevated). With the Bezier basis (the
//   default) the strand's points are those cubic control points, so the
//   phantom curves are exactly pbrt's curve and cylinders, capsules and links
//   lie on its control polygon, three per cubic (as Wald et al. 2020 built
//   theirs). With the BSpline basis each segment is sampled at `degree`
//   equal parameter steps instead (a cubic bezier curve gives as many points
//   as control points): the straight kinds inscribe the curve and the
//   phantom kind fits its own B-spline through the samples (close to, not
//   exactly, pbrt's curve). Consecutive segments share their end point.
//   Radius = width / 2, interpolated from width0 to width1 along the whole
//   curve as in pbrt-v4.
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

// Appends one strand (curve) or triangles (meshes), untransformed; a curve's
// points as `basis` reads them (above).
void add_curve(const ParamList& params, Strands& out, CurveBasis basis);
void add_triangle_mesh(const ParamList& params, TriangleMesh& out);
void add_bilinear_mesh(const ParamList& params, TriangleMesh& out);

}  // namespace rtc::pbrt
