// Procedural hair and fur, so that every experiment runs without data files:
// strands grown along the surface normal from roots spread uniformly (by
// area) over a sphere or a triangle mesh, or from a small disk as one lock
// (all strands along one axis, curling in phase: a ringlet), in one of three
// styles:
//   straight: along the normal, leaning a little at random;
//   wavy:     plus a planar sine wave across the growth direction;
//   curly:    plus a helix around the growth direction (tight curls when the
//             helix radius is small and the turns many; give each turn
//             enough points, ~8 or more, or the polyline aliases the helix).
// With `basis` Bezier the points are a cubic Bezier control polygon of the
// same centreline (scene.h: CurveBasis): points 0, 3, 6, ... lie on it and
// the two between are placed from its tangents (Hermite to Bezier,
// c1 = p0 + T0 h/3, c2 = p3 - T3 h/3 over the curve's parameter span h), so
// consecutive curves join with a continuous tangent; points past the last
// full curve (points - 1 not a multiple of 3) lie on the centreline.
// Fast enough for millions of segments (no allocation per strand), and a pure
// function of the description (seeded SplitMix64).
#pragma once

#include "scenes/scene.h"

#include <cstdint>

namespace rtc {

enum class HairStyle : std::uint8_t { Straight, Wavy, Curly };
enum class HairEmitter : std::uint8_t { Sphere, Mesh, Lock };

struct HairDesc {
    HairEmitter emitter = HairEmitter::Sphere;
    Vec3 sphere_center{0.0f};           // sphere emitter
    float sphere_radius = 1.0f;
    Vec3 lock_center{0.0f};             // lock emitter: centre of the root disk
    float lock_radius = 0.01f;          // lock emitter: root disk radius (> 0)
    Vec3 lock_axis{0.0f, -1.0f, 0.0f};  // lock emitter: growth direction (hanging down)
    HairStyle style = HairStyle::Straight;
    std::uint32_t strands = 10000;      // >= 1
    std::uint32_t points_per_strand = 8;  // >= 2; segments = strands * (points - 1)
    float length = 0.3f;                // root-to-tip distance along the growth axis
    float radius = 0.002f;              // at the root
    float tip_radius = -1.0f;           // at the tip, linear taper; < 0: same as radius
    float lean = 0.2f;                  // random lean of the growth axis off the normal
    float wave_amplitude = 0.08f;       // wavy: amplitude, as a fraction of length
    float waves = 2.0f;                 // wavy: full periods along the strand
    float curl_radius = 0.06f;          // curly: helix radius, as a fraction of length
    float curl_turns = 4.0f;            // curly: helix turns along the strand
    std::uint64_t seed = 1;
    bool with_mesh = false;             // add the emitter (sphere mesh, or the mesh) as triangles
    CurveBasis basis = CurveBasis::BSpline;  // what the points are (see above)
};

// Sphere or lock emitter; throws std::invalid_argument on a description out
// of range. A lock's strands share the curl (or wave) phase and the frame it
// is measured in, so with lean 0 every strand is a translate of the first.
[[nodiscard]] Scene make_hair(const HairDesc& desc);
// Mesh emitter: roots on `emitter`'s triangles (area-weighted), growing along
// each triangle's normal (counter-clockwise winding faces out).
[[nodiscard]] Scene make_hair_on_mesh(const HairDesc& desc, const TriangleMesh& emitter);

}  // namespace rtc
