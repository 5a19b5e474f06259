// The synthetic bundle (see bundle.h).
#include "scenes/generators/bundle.h"

#include "scenes/generators/random.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rtc {

Scene make_bundle(const BundleDesc& d) {
    if (d.count == 0) throw std::invalid_argument("bundle: count must be at least 1");
    if (!(d.radius > 0.0f) || !(d.radius < d.bundle_radius))
        throw std::invalid_argument("bundle: radius must lie in (0, bundle radius " +
                                    std::to_string(d.bundle_radius) + ")");
    Scene scene;
    scene.name = "bundle N=" + std::to_string(d.count) + " r=" + std::to_string(d.radius) +
                 " tilt=" + std::to_string(d.tilt_deg);
    Strands& s = scene.strands;
    s.points.reserve(2 * std::size_t{d.count});
    s.radii.assign(2 * std::size_t{d.count}, d.radius);
    s.offsets.reserve(std::size_t{d.count} + 1);

    const double alpha = d.tilt_deg * std::numbers::pi / 180.0;
    const double ca = std::cos(alpha), sa = std::sin(alpha);
    auto tilt = [&](double x, double y, double z) {
        return Vec3(static_cast<float>(ca * x - sa * y), static_cast<float>(sa * x + ca * y),
                    static_cast<float>(z));
    };
    const double disk = static_cast<double>(d.bundle_radius) - d.radius;
    const double half = 0.5 * d.length;
    SceneRng rng(d.seed);
    for (std::uint32_t i = 0; i < d.count; ++i) {
        // Uniform over the disk: sqrt of a uniform radius fraction.
        const double rho = disk * std::sqrt(rng.uniform());
        const double phi = 2.0 * std::numbers::pi * rng.uniform();
        const double x = rho * std::cos(phi), z = rho * std::sin(phi);
        s.points.push_back(tilt(x, -half, z));
        s.points.push_back(tilt(x, half, z));
        s.offsets.push_back(static_cast<std::uint32_t>(s.points.size()));
    }
    return scene;
}

}  // namespace rtc
