// Pinhole camera: frame set-up, primary rays and automatic framing of a scene
// (see camera.h for the conventions).
#include "sim/workload/camera.h"

#include "core/input_error.h"
#include "sim/workload/rng.h"
#include "sim/workload/sampling.h"

#include <glm/trigonometric.hpp>

#include <cmath>
#include <string>

namespace rtc {
namespace {

bool finite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void validate(const Camera& c) {
    if (!finite(c.position) || !finite(c.target) || !finite(c.up))
        throw InputError("camera: position, target and up must be finite");
    const Vec3 forward = c.target - c.position;
    if (!(glm::length(forward) > 0.0f)) throw InputError("camera: position equals target");
    if (!(glm::length(glm::cross(glm::normalize(forward), c.up)) > 1e-6f))
        throw InputError("camera: up is zero or parallel to the view direction");
    if (!(c.fov_deg > 0.0f && c.fov_deg < 180.0f))
        throw InputError("camera: fov_deg must be in (0, 180), got " + std::to_string(c.fov_deg));
    if (c.width <= 0 || c.height <= 0)
        throw InputError("camera: width and height must be positive");
}

CameraFrame camera_frame(const Camera& c) {
    validate(c);
    const Vec3 w = glm::normalize(c.target - c.position);
    const Vec3 u = glm::normalize(glm::cross(w, c.up));
    const Vec3 v = glm::cross(u, w);
    const float half_h = std::tan(glm::radians(c.fov_deg) * 0.5f);
    const float half_w = half_h * static_cast<float>(c.width) / static_cast<float>(c.height);
    CameraFrame f;
    f.origin = c.position;
    f.corner = w - half_w * u + half_h * v;
    f.right = u * (2.0f * half_w / static_cast<float>(c.width));
    f.down = -v * (2.0f * half_h / static_cast<float>(c.height));
    return f;
}

Ray jittered_ray(const CameraLanes& frame, std::uint32_t px, std::uint32_t py,
                 std::uint32_t sample, std::uint32_t spp, std::uint32_t seed) {
    const SampleRng rng(seed, px, py, sample);
    const glm::vec2 o = pixel_offset(sample, spp, rng.uniform(rng_dim::kPixelX), rng.uniform(rng_dim::kPixelY));
    return frame_ray(frame, static_cast<float>(px) + o.x, static_cast<float>(py) + o.y);
}

Ray primary_ray(const Camera& camera, std::uint32_t px, std::uint32_t py, std::uint32_t sample,
                std::uint32_t spp, std::uint32_t seed) {
    return primary_ray(CameraLanes(camera_frame(camera)), px, py, sample, spp, seed);
}

Camera auto_frame(const Aabb& bounds, float fov_deg, int width, int height, Vec3 from,
                  float margin) {
    if (bounds.empty() || !bounds.finite())
        throw InputError("camera auto: scene bounds are empty or not finite");
    if (!(fov_deg > 0.0f && fov_deg < 180.0f))
        throw InputError("camera auto: fov_deg must be in (0, 180), got " +
                         std::to_string(fov_deg));
    if (width <= 0 || height <= 0)
        throw InputError("camera auto: width and height must be positive");
    if (!finite(from) || !(glm::length(from) > 0.0f))
        throw InputError("camera auto: view direction must be finite and non-zero");
    const Vec3 dir = glm::normalize(from);
    const Vec3 center = bounds.center();
    float radius = 0.5f * glm::length(bounds.extent());
    if (!(radius > 0.0f)) radius = 1e-3f * std::fmax(1.0f, glm::length(center));  // a point
    // Half-angle of the narrower field of view.
    const float half_v = glm::radians(fov_deg) * 0.5f;
    const float half_h =
        std::atan(std::tan(half_v) * static_cast<float>(width) / static_cast<float>(height));
    const float half = std::fmin(half_v, half_h);
    const float distance = radius * margin / std::sin(half);
    Camera c;
    c.position = center + dir * distance;
    c.target = center;
    c.up = std::abs(dir.y) > 0.999f ? Vec3(0.0f, 0.0f, dir.y > 0.0f ? -1.0f : 1.0f)
                                    : Vec3(0.0f, 1.0f, 0.0f);
    c.fov_deg = fov_deg;
    c.width = width;
    c.height = height;
    return c;
}

}  // namespace rtc
