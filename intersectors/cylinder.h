// Cylinder with flat caps (the synthetic experiment's primitive).
// TODO(intersectors): derivation, bounds, oriented_bounds, intersect.
#pragma once

#include "core/obb.h"
#include "intersectors/hit.h"
#include "intersectors/kinds.h"

namespace rtc {

struct Cylinder {
    Vec3 p0{0.0f};
    Vec3 p1{0.0f};
    float radius = 0.0f;
};

}  // namespace rtc
