// The two ways of putting thin primitives on RT hardware (Wald et al. 2020),
// built from the same geometry:
//
// ref: one custom-primitive BLAS over the primitives' AABBs (+ an optional
//      triangle BLAS) under a tiny TLAS; the intersection program gets the
//      object-space ray and the primitive index.
// obb: the masquerade. One BLAS holding a single custom primitive whose box is
//      the unit box; one TLAS instance per primitive mapping the unit box onto
//      the primitive's OBB (+ one instance of the triangle BLAS). The hardware's
//      instance transform + unit-box test is then an OBB test, and the program
//      gets the world-space ray and the instance index.
#pragma once

#include "core/two_level.h"
#include "intersectors/kinds.h"
#include "intersectors/triangle.h"
#include "scenes/convert.h"
#include "scenes/scene.h"

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace rtc {

enum class Method : std::uint8_t { Ref, Obb };
inline constexpr std::array<std::string_view, 2> kMethodNames = {"ref", "obb"};
[[nodiscard]] constexpr std::string_view method_name(Method m) {
    return kMethodNames[static_cast<std::size_t>(m)];
}
[[nodiscard]] std::optional<Method> method_from_name(std::string_view s);

// What both methods are built from: primitives of one kind and a mesh.
struct Geometry {
    PrimitiveKind kind = PrimitiveKind::Capsule;
    PrimitiveArray prims;
    std::vector<Triangle> triangles;

    [[nodiscard]] std::size_t primitive_count() const;
};

// Converts a scene's strands into primitives of one kind (pre-subdivided for
// phantom curves) and its mesh into triangles.
[[nodiscard]] Geometry make_geometry(const Scene& scene, PrimitiveKind kind, int subdivision);

// World bounds of every primitive and triangle (for camera framing).
[[nodiscard]] Aabb geometry_bounds(const Geometry& geometry);

struct MethodOptions {
    BuildOptions custom_blas;     // leaf size 1: one box per custom primitive
    BuildOptions triangle_blas;   // triangles may share leaves
    BuildOptions tlas;            // leaf size 1: one box per instance
    ObbVariant obb = ObbVariant::Paper;
};

enum class BlasKind : std::uint8_t { Custom, Triangles };

struct MethodAccel {
    Method method = Method::Ref;
    TwoLevel accel;
    std::vector<BlasKind> blas_kind;  // per BLAS
};

// Builds a method's structures. Throws std::invalid_argument on a primitive
// whose bounds are not finite (scene loading rejects those earlier).
[[nodiscard]] MethodAccel build_method(Method method, const Geometry& geometry,
                                       const MethodOptions& options);

// Number of TLAS instances a method needs (checked against the instance limit
// before building).
[[nodiscard]] std::uint64_t instance_count(Method method, const Geometry& geometry);

}  // namespace rtc
