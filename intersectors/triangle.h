// Triangle, tested "in hardware" with the watertight test (Woop et al. 2013).
// TODO(intersectors): intersect, bounds.
#pragma once

#include "core/aabb.h"
#include "intersectors/hit.h"

namespace rtc {

struct Triangle {
    Vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
};

}  // namespace rtc
