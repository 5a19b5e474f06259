// Follow hairs (see follow_hairs.h).
#include "scenes/generators/follow_hairs.h"

#include "scenes/generators/random.h"

#include <cmath>
#include <numbers>

namespace rtc {

namespace {
// A unit vector perpendicular to the unit vector d.
Vec3 perpendicular(const Vec3& d) {
    const Vec3 helper = std::abs(d.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    return glm::normalize(glm::cross(d, helper));
}
}  // namespace

Strands add_follow_hairs(const Strands& guides, const FollowHairDesc& d) {
    if (d.per_guide == 0) return guides;
    Strands out;
    out.basis = guides.basis;  // offsets grow linearly along the strand: a control polygon stays one
    const std::size_t copies = 1 + std::size_t{d.per_guide};
    out.points.reserve(guides.points.size() * copies);
    out.radii.reserve(guides.radii.size() * copies);
    out.offsets.reserve(guides.strand_count() * copies + 1);
    SceneRng rng(d.seed);
    for (std::size_t i = 0; i < guides.strand_count(); ++i) {
        const std::uint32_t first = guides.offsets[i], n = guides.offsets[i + 1] - first;
        Vec3 dir = n >= 2 ? guides.points[first + 1] - guides.points[first] : Vec3(0, 1, 0);
        dir = glm::length(dir) > 0.0f ? glm::normalize(dir) : Vec3(0, 1, 0);
        const Vec3 t1 = perpendicular(dir), t2 = glm::cross(dir, t1);
        for (std::size_t c = 0; c < copies; ++c) {
            Vec3 offset(0.0f);
            if (c > 0) {  // copy 0 is the guide itself
                const float rho = d.spread * static_cast<float>(std::sqrt(rng.uniform()));
                const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(rng.uniform());
                offset = rho * (std::cos(phi) * t1 + std::sin(phi) * t2);
            }
            for (std::uint32_t k = 0; k < n; ++k) {
                const float u = n > 1 ? static_cast<float>(k) / static_cast<float>(n - 1) : 0.0f;
                out.points.push_back(guides.points[first + k] + (1.0f + d.tip_separation * u) * offset);
                out.radii.push_back(guides.radii[first + k]);
            }
            out.offsets.push_back(static_cast<std::uint32_t>(out.points.size()));
        }
    }
    return out;
}

}  // namespace rtc
