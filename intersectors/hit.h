// What an intersection program returns: the distance along the (unnormalized)
// ray and what shading needs.
#pragma once

#include "core/ray.h"

namespace rtc {

struct Hit {
    float t = kInfinity;
    Vec3 normal{0.0f};  // unit world-space geometric normal, facing any side
    float u = 0.0f;     // parameter along the primitive's axis/curve in [0, 1]
};

}  // namespace rtc
