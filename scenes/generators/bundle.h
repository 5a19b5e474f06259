// The paper's synthetic experiment: a bundle of N parallel cylinders of
// length 1 and radius r inside a bundle of radius R = 0.5 around the Y axis,
// centred at the origin, then tilted by `tilt_deg` about the Z axis (in the
// X-Y plane, away from Y). Each cylinder is a 2-point strand with radius r at
// both ends, so convert.h turns it into exactly one Cylinder.
#pragma once

#include "scenes/scene.h"

#include <cstdint>

namespace rtc {

struct BundleDesc {
    std::uint32_t count = 1000;    // N cylinders (>= 1)
    float radius = 0.002f;         // r of every cylinder (0 < r < bundle_radius)
    float tilt_deg = 0.0f;         // rotation about +Z, degrees (alpha in the paper)
    std::uint64_t seed = 1;        // placement is a pure function of the seed
    float bundle_radius = 0.5f;    // R (paper: 0.5)
    float length = 1.0f;           // cylinder length (paper: 1)
};

// Axes are uniform over the disk of radius R - r (so that every cylinder lies
// wholly inside the bundle; the paper does not say whether they may poke out)
// and may overlap one another (the paper does not say they don't).
// Throws std::invalid_argument for count 0 or r outside (0, R).
[[nodiscard]] Scene make_bundle(const BundleDesc& desc);

}  // namespace rtc
