// Embree 3's own hair BVHs, oriented against axis-aligned (issue 54 item 4):
// the CPU measurement the simulator's `obb-nodes` prediction is set beside.
//
// Which BVH Embree builds over curves is the device's `hair_accel` setting
// (kernels/common/scene.cpp, createHairAccel), and in Embree 3.13.5 every
// value it accepts is an oriented BVH: bvh4obb.virtualcurve4v/4i,
// bvh8obb.virtualcurve8v and bvh4obb.virtualcurve8i. Their builder
// (kernels/builders/bvh_builder_hair.h) makes a node oriented only where an
// oriented or strand split beats the aligned one by its SAH (traversal cost
// 1 aligned, 5 oriented). Embree 3 has no axis-aligned BVH over curves to
// select, so the aligned side here is Embree's aligned BVH over the same
// segments as user primitives (`object_accel`, binned SAH over each
// segment's AABB, the builder Embree uses for user geometry), whose callback
// runs the same capsule test rtcsim's `ref` runs (intersectors/capsule.h).
// So the two sides differ in two things, said wherever the ratio is printed:
// the nodes (aligned against partly oriented), and the leaf test (a scalar
// callback per segment against Embree's SIMD test of 4 or 8 segments).
//
// The segments are round linear curves (RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE),
// two vertices each with the capsule's radius and no neighbours: Embree
// renders a cone between a start and an end sphere, which for one radius is
// exactly the capsule, the primitive of the simulator's hair runs. (Flat
// curves face the ray and Bezier curves are another shape; links, a cone
// between two radii, would be round linear curves too.) A scene's mesh goes
// in as an Embree triangle mesh on both sides.
//
// What Embree exposes of each build: the device option `verbose=2` prints
// every BVH's statistics (node counts by kind, leaves, SAH, bytes), parsed
// here; the memory monitor callback gives the bytes Embree holds after the
// build. It does not expose traversal counts (node visits, primitive tests:
// its statistics counters need a build with EMBREE_STAT_COUNTERS, off by
// default, and no device property gives them), so the only
// per-ray count here is the aligned side's callbacks, counted by the callback.
#pragma once

#include "core/ray.h"
#include "intersectors/capsule.h"
#include "intersectors/triangle.h"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace rtc {

enum class HairBvh {
    Aligned,   // user primitives in Embree's aligned BVH (object_accel=bvh8.object)
    Oriented,  // round linear curves in Embree's hair BVH (hair_accel=bvh8obb.virtualcurve8v)
};
[[nodiscard]] const char* hair_bvh_name(HairBvh bvh);  // "aligned", "oriented"

// One BVH's statistics as Embree's `verbose=2` printed them (bvh_statistics.cpp).
struct EmbreeBvhStats {
    std::string primitive;  // Embree's primitive type: "object", "curve8v", "triangle4v", ...
    std::string builder;    // the builder's name, e.g. "BVH8OBBCurve8vBuilder_OBB_New"
    double sah = 0.0;
    double bytes = 0.0;     // nodes + leaves ("#bytes", Embree prints MB = 1e6 B)
    std::uint64_t aligned_nodes = 0, oriented_nodes = 0, leaves = 0;
};

// One ray's closest hit; prim is the capsule's index, or kMeshPrim for the mesh.
struct HairHit {
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    static constexpr std::uint32_t kMeshPrim = 0xFFFFFFFEu;
    float t = kInfinity;
    std::uint32_t prim = kNone;
    [[nodiscard]] bool hit() const { return prim != kNone; }
};

// An Embree device and scene holding `capsules` (and `triangles`, if any) in
// one of the two BVHs, built on `build_threads` threads. The spans must
// outlive the object. Throws std::runtime_error with Embree's error when the
// device or the build fails, or when bench was built without Embree.
class EmbreeHairScene {
public:
    EmbreeHairScene(std::span<const Capsule> capsules, std::span<const Triangle> triangles, HairBvh bvh,
                    unsigned build_threads);
    ~EmbreeHairScene();
    EmbreeHairScene(const EmbreeHairScene&) = delete;
    EmbreeHairScene& operator=(const EmbreeHairScene&) = delete;

    // The closest hit of every ray (rtcIntersect1 each) on `threads` threads
    // (core/parallel.h); hits.size() == rays.size(). Returns the capsule
    // tests the aligned side's callback ran (0 on the oriented side: Embree
    // does not count its own).
    std::uint64_t trace(std::span<const Ray> rays, std::span<HairHit> hits, unsigned threads) const;

    [[nodiscard]] HairBvh bvh() const;
    [[nodiscard]] double build_seconds() const;  // rtcCommitScene, wall time
    // What Embree held after the build (memory monitor: bytes allocated less
    // bytes freed since the device was made; BVHs, leaves, Embree's copies).
    [[nodiscard]] std::int64_t embree_bytes() const;
    // The statistics of every BVH the scene built (the mesh's too), and the
    // device's settings as Embree printed them.
    [[nodiscard]] const std::vector<EmbreeBvhStats>& bvh_stats() const;
    // The statistics of the BVH over the capsules.
    [[nodiscard]] const EmbreeBvhStats& hair_stats() const;
    [[nodiscard]] const std::string& device_config() const;  // the string given to rtcNewDevice

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Embree's version ("3.13.5"), or "" when bench was built without it.
[[nodiscard]] std::string embree_version();

// Parses the statistics Embree prints with `verbose=2` (exposed for tests).
[[nodiscard]] std::vector<EmbreeBvhStats> parse_embree_statistics(const std::string& printed);

}  // namespace rtc
