// A UV sphere as a triangle mesh: the "head" under procedural hair, so the
// mesh path (triangles in the reference BLAS, an instance in the TLAS) is
// exercised without any data file.
#pragma once

#include "scenes/scene.h"

namespace rtc {

// `rings` >= 2 latitude bands, `sectors` >= 3 longitude bands; triangles wind
// counter-clockwise seen from outside.
[[nodiscard]] TriangleMesh make_sphere_mesh(const Vec3& center, float radius, int rings = 24,
                                            int sectors = 48);

}  // namespace rtc
