// Pinhole camera and the generation of its primary rays.
//
// Primary rays are a pure function of (camera, pixel, sample, spp, seed), so
// every method traces bit-identical camera rays whatever the thread count.
// Image convention: pixel (0, 0) is the top-left corner, x grows to the right,
// y grows downwards; the vertical field of view spans the image height.
#pragma once

#include "core/aabb.h"
#include "core/box_lanes.h"
#include "core/ray.h"

#include <cstdint>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

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

// A CameraFrame as ray generation reads it: with SSE, each vector on the
// lanes (x, y, z, 0) of one register, made once per frame. As Vec3s each was
// three loads and a shuffle per camera ray.
struct CameraLanes {
#if defined(__SSE2__)
    __m128 origin, corner, right, down;
    explicit CameraLanes(const CameraFrame& f)
        : origin(load3(f.origin)), corner(load3(f.corner)), right(load3(f.right)), down(load3(f.down)) {}
#else
    CameraFrame frame;
    explicit CameraLanes(const CameraFrame& f) : frame(f) {}
#endif
};

// Ray through the point (px + ox, py + oy) of the image plane, offsets in
// [0, 1) pixels; unit direction (t in world units), tmin 0, tmax +inf.
// frame_ray_reference() is the definition; frame_ray() computes the same
// floats with x, y, z on SSE lanes (about half the instructions per camera
// ray): glm's (corner + x * right) + y * down, then v * (1 / sqrt(dot(v, v)))
// with dot(v, v) = (vx vx + vy vy) + vz vz, each operation the same per lane.
// tests/workload/test_workload_rays.cpp compares the two bit for bit.
[[nodiscard]] inline Ray frame_ray_reference(const CameraFrame& f, float x, float y) {
    return {f.origin, 0.0f, glm::normalize(f.corner + x * f.right + y * f.down), kInfinity};
}

[[nodiscard, gnu::always_inline]] inline Ray frame_ray(const CameraLanes& f, float x, float y) {
#if defined(__SSE2__)
    const __m128 v = _mm_add_ps(_mm_add_ps(f.corner, _mm_mul_ps(_mm_set1_ps(x), f.right)),
                                _mm_mul_ps(_mm_set1_ps(y), f.down));
    const __m128 sq = _mm_mul_ps(v, v);
    const __m128 dot =
        _mm_add_ss(_mm_add_ss(sq, _mm_shuffle_ps(sq, sq, _MM_SHUFFLE(1, 1, 1, 1))), _mm_movehl_ps(sq, sq));
    const __m128 inv = _mm_div_ss(_mm_set_ss(1.0f), _mm_sqrt_ss(dot));
    const __m128 dir = _mm_mul_ps(v, _mm_shuffle_ps(inv, inv, _MM_SHUFFLE(0, 0, 0, 0)));
    // The ray in two 16-byte stores: (origin, tmin = the origin's lane 3,
    // 0) and (direction, tmax = +inf in lane 3).
    const __m128 inf_w = _mm_set_ps(kInfinity, 0.0f, 0.0f, 0.0f);
#if defined(__SSE4_1__)
    const __m128 dir_tmax = _mm_blend_ps(dir, inf_w, 0x8);
#else
    const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
    const __m128 dir_tmax = _mm_or_ps(_mm_and_ps(dir, xyz), inf_w);
#endif
    Ray r;
    store_ray(f.origin, dir_tmax, r);
    return r;
#else
    return frame_ray_reference(f.frame, x, y);
#endif
}

[[nodiscard]] inline Ray frame_ray(const CameraFrame& f, float x, float y) { return frame_ray(CameraLanes(f), x, y); }

// The jittered camera ray of sample `sample` of `spp` > 1 (primary_ray's out-of-line part).
[[nodiscard]] Ray jittered_ray(const CameraLanes& frame, std::uint32_t px, std::uint32_t py,
                               std::uint32_t sample, std::uint32_t spp, std::uint32_t seed);

// Primary ray of sample `sample` of `spp` in pixel (px, py). With spp == 1 the
// ray passes through the pixel centre; otherwise it is stratified-jittered
// inside the pixel by the counter-based RNG (sim/rng.h). The centre's ray is
// made inline (as a call, its saved registers and arguments cost about 20
// instructions per camera ray), the jittered one out of line.
[[nodiscard, gnu::always_inline]] inline Ray primary_ray(const CameraLanes& frame, std::uint32_t px,
                                                          std::uint32_t py, std::uint32_t sample,
                                                          std::uint32_t spp, std::uint32_t seed) {
    if (spp > 1) return jittered_ray(frame, px, py, sample, spp, seed);
    return frame_ray(frame, static_cast<float>(px) + 0.5f, static_cast<float>(py) + 0.5f);
}
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
