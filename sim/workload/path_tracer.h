// The path-tracing workload: camera paths bouncing on diffuse surfaces under
// an environment light, in the spirit of the paper's set-up (a path tracer,
// 800 x 800 pixels, 4 paths per pixel; see docs/method.md).
//
// Tracing is the caller's: every ray of every path goes through `trace(ray,
// depth) -> TraceHit`, so the same paths run through either method. Paths are
// deterministic per (seed, pixel, sample, bounce) via the counter-based RNG,
// and a path only depends on the hits it receives: two methods that report the
// same hits trace the same rays, ray for ray. Bounce counts are fixed (Russian
// roulette is off by default), so ray counts match between methods too.
#pragma once

#include "core/box_lanes.h"
#include "core/ray.h"
#include "sim/workload/camera.h"
#include "sim/workload/rng.h"
#include "sim/workload/sampling.h"
#include "sim/hardware/trace_hit.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>

namespace rtc {

// Sky light seen by escaping rays: a vertical gradient from `bottom` (looking
// straight down) to `top` (straight up), linear in the direction's y; a
// constant sky is top == bottom.
struct Environment {
    Vec3 top{1.0f};
    Vec3 bottom{1.0f};

    [[nodiscard]] static Environment constant(Vec3 radiance) { return {radiance, radiance}; }
    // Inline: as a call it cost about 12 instructions per escaping ray.
    [[nodiscard, gnu::always_inline]] Vec3 radiance(const Vec3& direction) const {
        const float len = glm::length(direction);
        const float y = len > 0.0f ? direction.y / len : 0.0f;
        return glm::mix(bottom, top, std::clamp(0.5f * (y + 1.0f), 0.0f, 1.0f));
    }
};

enum class Shading : std::uint8_t {
    Path,     // diffuse path tracing with `bounces` bounces
    Primary,  // camera rays only, shaded |n.d| gray (quick looks)
};

struct PathOptions {
    Shading shading = Shading::Path;
    std::uint32_t spp = 4;      // samples per pixel (for the stratified pixel jitter)
    std::uint32_t bounces = 3;  // secondary rays per path when every ray hits
    std::uint32_t seed = 0;
    Vec3 curve_albedo{0.6f};     // diffuse albedo of curve-like primitives (hair)
    Vec3 triangle_albedo{0.8f};  // diffuse albedo of triangles (mesh)
    Environment environment{};
    // The next ray starts this far off the surface (along the normal facing the
    // incoming ray), relative to max(|hit point| coordinate, hit distance).
    float ray_offset = 1e-5f;
    // Russian roulette from this bounce on; off by default, so that fixed
    // bounce counts give identical ray counts in every run.
    bool russian_roulette = false;
    std::uint32_t roulette_min_bounce = 2;
};

// One camera path: its radiance estimate, how many rays it traced and what the
// camera ray hit (for depth / ID images).
struct PathSample {
    Vec3 radiance{0.0f};
    std::uint32_t rays = 0;
    TraceHit primary{};
};

[[nodiscard]] inline Vec3 albedo_of(const PathOptions& o, GeometryId geom) {
    return geom == GeometryId::Triangles ? o.triangle_albedo : o.curve_albedo;
}

// Origin of the ray leaving a hit, pushed off the surface along `facing` (the
// normal turned towards the incoming ray) by an offset that scales with the
// float precision of the hit position and of the hit distance.
[[nodiscard]] inline Vec3 offset_origin(const Vec3& p, const Vec3& facing, float distance,
                                        float ray_offset) {
    const float scale =
        std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), distance, 1e-6f});
    return p + facing * (ray_offset * scale);
}

// ray = (origin, tmin 0, direction, tmax +inf), with SSE in two 16-byte
// stores (core/box_lanes.h's store_ray: the trace loads it as RayLanes).
[[gnu::always_inline]] inline void set_ray(Ray& ray, const Vec3& origin, const Vec3& direction) {
#if defined(__SSE2__)
    store_ray(_mm_setr_ps(origin.x, origin.y, origin.z, 0.0f),
              _mm_setr_ps(direction.x, direction.y, direction.z, kInfinity), ray);
#else
    ray = {origin, 0.0f, direction, kInfinity};
#endif
}

// Traces one path from the camera ray of (px, py, sample). `trace(ray, depth)`
// returns the closest hit (depth 0 = camera ray).
template <class TraceFn>
[[nodiscard]] PathSample trace_path(const CameraLanes& frame, std::uint32_t px,
                                    std::uint32_t py, std::uint32_t sample,
                                    const PathOptions& opt, TraceFn&& trace) {
    PathSample out;
    Ray ray = primary_ray(frame, px, py, sample, opt.spp, opt.seed);
    // The bounces' random stream, made at the first bounce (camera rays that
    // end the path, as all primary-only workloads do, never need it).
    std::optional<SampleRng> rng;
    Vec3 throughput{1.0f};
    // One call of `trace` (not a camera ray's apart from the bounces'): with
    // two, GCC stopped inlining a method's trace into the frame's loop
    // (case 2 ref 31 more instructions per ray).
    for (std::uint32_t depth = 0;; ++depth) {
        const TraceHit hit = trace(std::as_const(ray), depth);
        ++out.rays;
        if (depth == 0) out.primary = hit;
        if (!hit.hit()) {
            out.radiance += throughput * opt.environment.radiance(ray.direction);
            break;
        }
        const float cos_in = glm::dot(hit.normal, ray.direction);
        if (opt.shading == Shading::Primary) {
            out.radiance = Vec3(std::abs(cos_in) / std::max(glm::length(ray.direction), 1e-30f));
            break;
        }
        if (depth >= opt.bounces) break;
        if (!rng) rng.emplace(opt.seed, px, py, sample);
        const Vec3 facing = cos_in > 0.0f ? -hit.normal : hit.normal;
        throughput *= albedo_of(opt, hit.geom);
        if (opt.russian_roulette && depth + 1 >= opt.roulette_min_bounce) {
            const float survive =
                std::clamp(std::max({throughput.x, throughput.y, throughput.z}), 0.05f, 1.0f);
            if (rng->uniform(rng_dim::bounce(depth, 2)) >= survive) break;
            throughput /= survive;
        }
        const Vec3 p = ray.at(hit.t);
        const float distance = hit.t * glm::length(ray.direction);
        set_ray(ray, offset_origin(p, facing, distance, opt.ray_offset),
                cosine_direction(facing, rng->uniform(rng_dim::bounce(depth, 0)),
                                 rng->uniform(rng_dim::bounce(depth, 1))));
    }
    return out;
}

template <class TraceFn>
[[nodiscard]] PathSample trace_path(const Camera& camera, std::uint32_t px, std::uint32_t py,
                                    std::uint32_t sample, const PathOptions& opt,
                                    TraceFn&& trace) {
    return trace_path(CameraLanes(camera_frame(camera)), px, py, sample, opt, std::forward<TraceFn>(trace));
}

}  // namespace rtc
