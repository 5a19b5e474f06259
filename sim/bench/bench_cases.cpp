#include "sim/bench/bench_cases.h"

#include <filesystem>

namespace rtc {

namespace {

using nlohmann::json;

// Case 1's camera: 800 x 800 primary rays from (0, 0, 2) at the origin, +Y up,
// 45 degrees vertical fov, one ray per pixel through the pixel centre (spp 1).
json bundle_camera() {
    return {{"type", "primary"},
            {"camera", {{"position", {0.0, 0.0, 2.0}}, {"target", {0.0, 0.0, 0.0}},
                        {"up", {0.0, 1.0, 0.0}}, {"fov_deg", 45.0}}},
            {"width", 800},
            {"height", 800},
            {"spp", 1}};
}

json bundle_run(int count, double radius, double tilt, json methods, int pixels = 800) {
    json workload = bundle_camera();
    workload["width"] = workload["height"] = pixels;
    return {{"scene", {{"type", "bundle"}, {"count", count}, {"radius", radius}, {"tilt_deg", tilt}}},
            {"primitives", {{"kind", "capsule"}}},
            {"methods", std::move(methods)},
            {"workload", workload}};
}

}  // namespace

std::vector<BenchCase> standard_cases(const std::string& data_dir) {
    std::vector<BenchCase> cases;
    const json both = {"ref", "obb"};
    cases.push_back({1, "bundle N=1000 r=0.002 tilt 45, capsules", "",
                     {{"capsules", bundle_run(1000, 0.002, 45.0, both)}}, ""});
    cases.push_back({2, "bundle N=1000 r=0.002 tilt 0, capsules", "",
                     {{"capsules", bundle_run(1000, 0.002, 0.0, both)}}, ""});
    // Case 3 at 200 x 200 (case 1's camera otherwise): the tilted instances'
    // world AABBs overlap so much that a ray tests ~10,000 TLAS boxes, and
    // 800 x 800 would take minutes per trace.
    cases.push_back({3, "bundle N=100000 r=0.0005 tilt 30, capsules, obb only",
                     "200 x 200; the reference method needs thousands of IS calls per ray here",
                     {{"capsules", bundle_run(100000, 0.0005, 30.0, {"obb"}, 200)}}, ""});

    // Case 4: Sintel's 11,400 strands (16 points each, metres) stand for a full
    // head of hair, so each is a clump: radius 0.1 mm (0.2 mm thick, ~2-3x a
    // real hair). The camera looks at the hair's bounding-box centre from the
    // front, 0.55 m away, so the 0.28 m tall hair fills the 45 degree view.
    const std::filesystem::path hair = std::filesystem::path(data_dir) / "hair";
    const std::string tfx = (hair / "sintel_hair_16pts.tfx").string();
    const std::string obj = (hair / "sintel_head.obj").string();
    BenchCase sintel{4, "Sintel hair (171,000 segments) + head mesh",
                     "radius 0.0001 m; 800 x 800 primary rays from (-0.007, 1.535, 0.55) at the hair's centre",
                     {}, ""};
    if (!std::filesystem::exists(tfx) || !std::filesystem::exists(obj)) {
        sintel.missing_data = "needs " + tfx + " and " + obj + " (run scripts/fetch-data, or set --data DIR)";
    } else {
        const json scene = {{"type", "file"},
                            {"curves", {{"path", tfx}, {"radius", 0.0001}}},
                            {"mesh", {{"path", obj}}}};
        const json workload = {
            {"type", "primary"},
            {"camera", {{"position", {-0.007, 1.535, 0.55}}, {"target", {-0.007, 1.535, 0.0}},
                        {"up", {0.0, 1.0, 0.0}}, {"fov_deg", 45.0}}},
            {"width", 800}, {"height", 800}, {"spp", 1}};
        for (const char* kind : {"capsule", "phantom"})
            sintel.runs.push_back({std::string(kind) + "s",
                                   {{"scene", scene},
                                    {"primitives", {{"kind", kind}}},
                                    {"methods", both},
                                    {"workload", workload}}});
    }
    cases.push_back(std::move(sintel));

    // Case 5: 250,000 straight strands of 9 points = 2,000,000 capsules on a
    // unit sphere (with the sphere mesh), traced by the diffuse path tracer at
    // 256 x 256, 2 paths per pixel, 2 bounces: up to 393,216 rays, enough for
    // stable rates while both 2 M-primitive builds keep the case near a minute.
    const json fur = {{"type", "hair"}, {"emitter", "sphere"}, {"style", "straight"},
                      {"strands", 250000}, {"points_per_strand", 9}, {"length", 0.3},
                      {"radius", 0.001}, {"tip_radius", 0.0002}, {"seed", 3},
                      {"with_mesh", true}};
    cases.push_back({5, "procedural fur, 2,000,000 capsules + sphere mesh, path tracing",
                     "256 x 256, spp 2, 2 bounces, auto camera",
                     {{"capsules",
                       {{"scene", fur},
                        {"primitives", {{"kind", "capsule"}}},
                        {"methods", both},
                        {"workload",
                         {{"type", "camera"}, {"camera", "auto"}, {"width", 256},
                          {"height", 256}, {"spp", 2}, {"bounces", 2}}}}}},
                     ""});
    return cases;
}

BenchCase scale_case() {
    // 2^24 capsules of radius 0.00005 in the bundle of radius 0.5 (mean axis
    // spacing ~2e-4, so they rarely overlap), one masquerade instance each.
    // Untilted: tilted, every ray would pierce millions of instance AABBs.
    return {0, "scale: bundle of 2^24 capsules, obb (16,777,216 instances)",
            "r=0.00005 tilt 0; case 1's camera",
            {{"capsules", bundle_run(1 << 24, 0.00005, 0.0, {"obb"})}}, ""};
}

}  // namespace rtc
