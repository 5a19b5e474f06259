// Follow hairs around guide strands, as TressFX generates them at load time
// (TressFX files hold guides only; e.g. the bear asks for 4 per guide). Each
// follow hair copies its guide shifted by a random offset chosen in the disk
// of radius `spread` perpendicular to the guide's first segment; the offset
// grows linearly from root to tip by the factor (1 + tip_separation), so
// follow hairs fan out towards the tips. This is a simplified version of
// TressFX's scheme, not a bit-exact copy.
#pragma once

#include "scenes/scene.h"

#include <cstdint>

namespace rtc {

struct FollowHairDesc {
    std::uint32_t per_guide = 0;   // follow hairs per guide (0: none)
    float spread = 0.0f;           // offset disk radius at the root (same units as the file)
    float tip_separation = 1.0f;   // extra offset factor at the tip
    std::uint64_t seed = 1;
};

// Guides and follow hairs, in the order guide 0, its follow hairs, guide 1, ...
// Radii are copied from the guide.
[[nodiscard]] Strands add_follow_hairs(const Strands& guides, const FollowHairDesc& desc);

}  // namespace rtc
