// Oriented bounding box as the affine image of the unit box [-1, 1]^3.
//
// This is exactly what the masquerade method hands to the hardware: an
// instance whose `world_from_object` maps the unit box of a one-primitive BLAS
// onto the OBB, so the hardware's instance transform + box test is an OBB test.
#pragma once

#include "core/affine.h"

namespace rtc {

inline const Aabb kUnitBox{Vec3(-1.0f), Vec3(1.0f)};

struct Obb {
    Affine world_from_unit;  // maps [-1,1]^3 onto the box

    // Box with the given centre, orthonormal axes and half-extents.
    [[nodiscard]] static Obb from_frame(const Vec3& center, const Vec3& axis_x, const Vec3& axis_y,
                                        const Vec3& axis_z, const Vec3& half_extent) {
        return {Affine::from_columns(axis_x * half_extent.x, axis_y * half_extent.y,
                                     axis_z * half_extent.z, center)};
    }

    [[nodiscard]] Vec3 center() const { return world_from_unit.translation; }
    [[nodiscard]] Vec3 half_axis(int i) const { return world_from_unit.linear[i]; }
    [[nodiscard]] Aabb bounds() const { return world_from_unit.box(kUnitBox); }
    [[nodiscard]] float surface_area() const {
        const float a = 2.0f * glm::length(half_axis(0)), b = 2.0f * glm::length(half_axis(1)),
                    c = 2.0f * glm::length(half_axis(2));
        return 2.0f * (a * b + b * c + c * a);
    }
    // Containment up to a relative slack `eps` in unit-box coordinates (for
    // sampling tests); a degenerate (singular) box contains nothing.
    [[nodiscard]] bool contains(const Vec3& p, float eps = 1e-5f) const {
        const auto unit_from_world = centred_inverse(world_from_unit);
        if (!unit_from_world) return false;
        const Vec3 q = unit_from_world->point(p);
        return std::abs(q.x) <= 1.0f + eps && std::abs(q.y) <= 1.0f + eps &&
               std::abs(q.z) <= 1.0f + eps;
    }
    // The same box grown by a relative margin on every half-axis, so rounding in
    // the hardware's ray transform never culls a ray that touches the primitive.
    [[nodiscard]] Obb padded(float relative) const {
        Obb o = *this;
        for (int i = 0; i < 3; ++i) o.world_from_unit.linear[i] *= 1.0f + relative;
        return o;
    }
};

}  // namespace rtc
