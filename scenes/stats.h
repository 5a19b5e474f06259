// Summary figures of a scene, for reports and for sanity checks of loaders:
// counts, bounds and the shape of the segments (length over radius is what
// makes AABBs loose, hence what the masquerade trick feeds on).
#pragma once

#include "core/aabb.h"
#include "scenes/scene.h"

#include <cstddef>

namespace rtc {

// The AABB/OBB surface-area figures need the primitives' bounding programs
// for a chosen kind, so they live beside the methods: sim/area_stats.h.
struct SceneStats {
    std::size_t strands = 0;
    std::size_t segments = 0;
    std::size_t points = 0;
    std::size_t triangles = 0;
    CurveBasis curve_basis = CurveBasis::BSpline;  // how the points make phantom curves (scene.h)
    std::size_t curves = 0;               // phantom curves before pre-subdivision (BSpline: = segments)
    Aabb bounds;                          // points grown by their radii, plus mesh vertices
    double mean_segment_length = 0.0;
    double mean_radius = 0.0;             // per segment: mean of its two point radii
    double mean_length_over_radius = 0.0; // per segment, over segments with radius > 0 (0 if none)
    // Segments too thin for float at their position: both radii below
    // kThinUlps float ulps (2^-23 x) of their largest coordinate magnitude.
    // Their boxes are at least about an ulp of the position wider than the
    // primitive (a float box can do no better), so their AABB/OBB figures and
    // counts move with the scene's position (issue 38, item 4).
    std::size_t thin_segments = 0;
};

inline constexpr double kThinUlps = 4.0;

// True when a primitive of radius `radius` at coordinates of magnitude up to
// `magnitude` is thinner than kThinUlps float ulps there.
[[nodiscard]] inline bool too_thin_for_float(double radius, double magnitude) {
    return radius < kThinUlps * 0x1p-23 * magnitude;
}

[[nodiscard]] SceneStats compute_stats(const Scene& scene);

}  // namespace rtc
