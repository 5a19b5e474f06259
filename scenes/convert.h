// Strands -> primitives of one kind, the input of both methods' builds.
//
// - Cylinder, Capsule: one per segment, constant radius = the mean of the two
//   point radii (these primitives have a single radius).
// - Link: one per segment with the two point radii.
// - Phantom, by the strands' basis (scenes/scene.h: CurveBasis):
//   BSpline: the strand's points are the control points of a uniform cubic
//   B-spline; each window of four consecutive points is one curve segment,
//   converted to Bezier form (radius likewise, as a 1-D spline). Phantom end
//   points p[-1] = 2 p0 - p1 and p[n] = 2 p[n-1] - p[n-2] are added so that
//   the n - 1 curves of an n-point strand run exactly from p0 to p[n-1] (the
//   curve approximates, does not interpolate, the interior points).
//   Bezier: the points are a cubic Bezier control polygon; curve i has
//   points 3i..3i+3 as its control points (radii likewise), so an n-point
//   strand gives ceil((n - 1) / 3) curves, each spanning three of the links
//   the straight kinds make. When n - 1 is not a multiple of 3, the trailing
//   one or two links are a line or a quadratic Bezier, degree-elevated to
//   the cubic that traces exactly it (a two-point strand is its segment).
//   Either way, each curve may then be split into 2, 4 or 8 sub-curves
//   (de Casteljau at t = 1/2, recursively), as in the paper's
//   pre-subdivision.
// Order: strand by strand, segment by segment, sub-curves in parameter order.
#pragma once

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/kinds.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "scenes/scene.h"

#include <array>
#include <cstdint>
#include <utility>
#include <variant>
#include <vector>

namespace rtc {

using PrimitiveArray = std::variant<std::vector<Cylinder>, std::vector<Capsule>, std::vector<Link>,
                                    std::vector<PhantomCurve>>;

// `subdivision` must be 1, 2, 4 or 8, and 1 for every kind but Phantom;
// anything else throws InputError.
[[nodiscard]] PrimitiveArray to_primitives(const Strands& strands, PrimitiveKind kind,
                                           int subdivision = 1);
// The source strand of each primitive to_primitives would make, same order.
[[nodiscard]] std::vector<std::uint32_t> primitive_strands(const Strands& strands, PrimitiveKind kind,
                                                           int subdivision = 1);
[[nodiscard]] std::size_t primitive_count(const PrimitiveArray& prims);
// How many primitives to_primitives would make, without making them.
[[nodiscard]] std::size_t primitive_count(const Strands& strands, PrimitiveKind kind, int subdivision = 1);
// The phantom curves (before pre-subdivision) of one strand of `points`
// points: points - 1 (BSpline) or ceil((points - 1) / 3) (Bezier); 0 below 2.
[[nodiscard]] std::size_t curve_count(std::size_t points, CurveBasis basis);

// The curve arithmetic, exposed for tests and for other tools.
namespace bspline {
// Uniform cubic B-spline segment (control points p, radii r) in Bezier form.
[[nodiscard]] PhantomCurve to_bezier(const std::array<Vec3, 4>& p, const std::array<float, 4>& r);
// The B-spline segment itself at t in [0, 1] (for checking to_bezier).
[[nodiscard]] Vec3 eval(const std::array<Vec3, 4>& p, float t);
// The Bezier curve's position and radius at t in [0, 1].
[[nodiscard]] Vec3 bezier_point(const PhantomCurve& c, float t);
[[nodiscard]] float bezier_radius(const PhantomCurve& c, float t);
// de Casteljau split at t = 1/2: the halves [0, 1/2] and [1/2, 1].
[[nodiscard]] std::pair<PhantomCurve, PhantomCurve> split_half(const PhantomCurve& c);
}  // namespace bspline

}  // namespace rtc
