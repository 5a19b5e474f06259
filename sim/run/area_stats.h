// The paper's figure-9 metric: total surface area of all primitive AABBs
// against all OBBs. The speedup of the masquerade tracks their ratio.
#pragma once

#include "scenes/convert.h"

namespace rtc {

struct AreaStats {
    double aabb = 0.0;        // sum of primitive AABB surface areas
    double obb_paper = 0.0;   // sum of OBB surface areas, paper rule
    double obb_tight = 0.0;   // sum of OBB surface areas, tight variant
    [[nodiscard]] double ratio_paper() const { return obb_paper > 0 ? aabb / obb_paper : 0.0; }
    [[nodiscard]] double ratio_tight() const { return obb_tight > 0 ? aabb / obb_tight : 0.0; }
};

// On `threads` threads (0 = all cores); the sums do not depend on it.
[[nodiscard]] AreaStats area_stats(const PrimitiveArray& prims, unsigned threads = 0);

}  // namespace rtc
