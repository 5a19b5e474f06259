// Link (Han et al. 2019): convex hull of two spheres (p0, r0) and (p1, r1).
// TODO(intersectors): derivation, bounds, oriented_bounds, intersect.
#pragma once

#include "core/obb.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"

namespace rtc {

struct Link {
    Vec3 p0{0.0f};
    float r0 = 0.0f;
    Vec3 p1{0.0f};
    float r1 = 0.0f;
};

}  // namespace rtc
