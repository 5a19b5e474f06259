// The closest hit of one traced ray, as both methods must report it.
#pragma once

#include "core/ray.h"

#include <cstdint>

namespace rtc {

enum class GeometryId : std::uint32_t { Curves = 0, Triangles = 1, None = 0xFFFFFFFFu };

struct TraceHit {
    float t = kInfinity;
    Vec3 normal{0.0f};                      // unit geometric normal (world space)
    float u = 0.0f;                         // curve/axis parameter, 0 for triangles
    std::uint32_t prim = 0xFFFFFFFFu;       // primitive (or triangle) index
    GeometryId geom = GeometryId::None;

    [[nodiscard]] bool hit() const { return geom != GeometryId::None; }
    // Order-independent closest-hit rule: nearer wins, equal distances go to the
    // smaller (geometry, primitive), so every traversal order agrees.
    [[nodiscard]] bool closer_than(const TraceHit& o) const {
        if (t != o.t) return t < o.t;
        if (geom != o.geom) return geom < o.geom;
        return prim < o.prim;
    }
};

}  // namespace rtc
