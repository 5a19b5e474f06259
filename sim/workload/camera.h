// Pinhole camera and the generation of its primary rays.
//
// Primary rays are a pure function of (camera, pixel, sample, spp, seed), so
// every method traces bit-identical camera rays whatever the thread count.
// Image convention: pixel (0, 0) is the top-left corner, x grows to the right,
// y grows downwards; the vertical field of view spans the image height.
#pragma once

#include "core/aabb.h"
#include "core/ray.h"

#include <cstdint>

namespace rtc {

struct Camera {
    Vec3 position{0.0f, 0.0f, 5.0f};
    Vec3 target{0.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float fov_deg = 45.0f;  // vertical field of view, degrees, in (0, 180)
    int width = 800;
    int height = 800;
};

// Throws InputError unless the camera can generate rays: finite vectors,
// position != target, up not parallel to the view direction, fov in (0, 180),
// width and height positive.
void validate(const Camera& camera);

// The world-space frame of a camera, computed once per image rather than per
// ray. `right` and `down` span one pixel each; `corner` is the direction to
// the top-left corner of the image plane at unit distance along `forward`.
struct CameraFrame {
    Vec3 origin;
    Vec3 corner;
    Vec3 right;  // direction offset of one pixel to the right
    Vec3 down;   // direction offset of one pixel downwards
};

[[nodiscard]] CameraFrame camera_frame(const Camera& camera);

// Ray through the point (px + ox, py + oy) of the image plane, offsets in
// [0, 1) pixels; unit direction (t in world units), tmin 0, tmax +inf.
[[nodiscard]] inline Ray frame_ray(const CameraFrame& f, float x, float y) {
    return {f.origin, 0.0f, glm::normalize(f.corner + x * f.right + y * f.down), kInfinity};
}

// Primary ray of sample `sample` of `spp` in pixel (px, py). With spp == 1 the
// ray passes through the pixel centre; otherwise it is stratified-jittered
// inside the pixel by the counter-based RNG (sim/rng.h).
[[nodiscard]] Ray primary_ray(const CameraFrame& frame, std::uint32_t px, std::uint32_t py,
                              std::uint32_t sample, std::uint32_t spp, std::uint32_t seed);
[[nodiscard]] Ray primary_ray(const Camera& camera, std::uint32_t px, std::uint32_t py,
                              std::uint32_t sample, std::uint32_t spp, std::uint32_t seed);

// A camera that frames `bounds`: it looks at the box centre from the direction
// `from` (centre to eye, default +Z), with +Y up (+Z when `from` is along Y),
// at the distance where the bounding sphere, enlarged by `margin`, just fits
// the narrower of the vertical and horizontal fields of view. Throws
// InputError on empty or non-finite bounds.
inline constexpr float kAutoFrameMargin = 1.05f;
[[nodiscard]] Camera auto_frame(const Aabb& bounds, float fov_deg, int width, int height,
                                Vec3 from = Vec3(0.0f, 0.0f, 1.0f),
                                float margin = kAutoFrameMargin);

}  // namespace rtc
