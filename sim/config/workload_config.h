// The "workload" section of a run config: which rays are traced (camera paths,
// primary rays only, or a ray file) and how they are generated. Plain data
// with a documented default per field; parsing is separate and strict
// (unknown keys and bad values are InputErrors naming the file and JSON path).
// Every key is documented in docs/workload-config.md.
#pragma once

#include "core/aabb.h"
#include "sim/workload/camera.h"
#include "sim/util/json_reader.h"
#include "sim/workload/path_tracer.h"

#include <cstdint>
#include <string>

namespace rtc {

enum class WorkloadType : std::uint8_t {
    Camera,   // "camera": diffuse path tracer (default)
    Primary,  // "primary": camera rays only, |n.d| shading
    Rays,     // "rays": the rays of a ray file (sim/ray_file.h), no shading
};

[[nodiscard]] const char* workload_type_name(WorkloadType t);

struct CameraDesc {
    bool automatic = true;               // "auto": frame the scene bounds (auto_frame)
    Vec3 from{0.0f, 0.0f, 1.0f};         // auto: direction from the scene centre to the eye
    Vec3 position{0.0f, 0.0f, 5.0f};     // explicit camera only
    Vec3 target{0.0f};                   // explicit camera only
    Vec3 up{0.0f, 1.0f, 0.0f};           // explicit camera only
    float fov_deg = 45.0f;               // vertical field of view, degrees
};

struct WorkloadDesc {
    WorkloadType type = WorkloadType::Camera;
    CameraDesc camera{};
    int width = 800;            // the paper's 800 x 800
    int height = 800;
    std::uint32_t spp = 4;      // the paper's 4 paths per pixel
    std::uint32_t bounces = 3;  // type camera: secondary rays per path
    std::uint32_t seed = 0;
    Vec3 curve_albedo{0.6f};     // type camera: curves, capsules, links, cylinders (hair)
    Vec3 triangle_albedo{0.8f};  // type camera: triangles (mesh)
    Environment environment{};   // constant 1 (white sky)
    bool russian_roulette = false;
    std::string rays_file;  // type rays: absolute (given relative to the config file's directory)
};

// Parses the workload object that `r` points at (e.g. path "/workload").
[[nodiscard]] WorkloadDesc parse_workload(const JsonReader& r);

// The path tracer's options for a camera or primary workload.
[[nodiscard]] PathOptions path_options(const WorkloadDesc& w);

// The camera of a camera or primary workload: explicit, or framing
// `scene_bounds` (auto). Throws InputError if the camera is unusable.
[[nodiscard]] Camera make_camera(const WorkloadDesc& w, const Aabb& scene_bounds);

}  // namespace rtc
