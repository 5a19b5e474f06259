// Phantom curve (Reshetov & Luebke 2018): cubic Bezier swept by a sphere of
// varying radius.
// TODO(intersectors): derivation, bounds, oriented_bounds, intersect, subdivide.
#pragma once

#include "core/obb.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"

#include <array>

namespace rtc {

struct PhantomCurve {
    std::array<Vec3, 4> cp{};        // Bezier control points
    std::array<float, 4> radius{};   // radius as a cubic Bezier in the same parameter
};

}  // namespace rtc
