#include "sim/run/area_stats.h"

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"

namespace rtc {

AreaStats area_stats(const PrimitiveArray& prims) {
    AreaStats s;
    std::visit(
        [&](const auto& v) {
            for (const auto& p : v) {
                s.aabb += bounds(p).surface_area();
                s.obb_paper += oriented_bounds(p, ObbVariant::Paper).surface_area();
                s.obb_tight += oriented_bounds(p, ObbVariant::Tight).surface_area();
            }
        },
        prims);
    return s;
}

}  // namespace rtc
