// Embree 3's side of `bench --embree` (sim/bench/embree_bench.h): a bench
// case's capsules in an Embree scene laid out the way an rtcsim method lays
// them out, so that both trace the same rays through the same method and their
// rates can be compared (issue 39):
//   ref: one user geometry with a primitive per capsule (Embree's BVH over the
//        capsules' AABBs from the bounds callback), whose intersect callback
//        runs rtcsim's capsule test (intersectors/capsule.h);
//   obb: a scene of one user primitive whose box is the unit box [-1, 1]^3,
//        instanced once per capsule with the transform rtcsim's obb method
//        gives it (its OBB's world_from_unit); the callback, reached in the
//        instance's space, runs the capsule test of the instance's capsule on
//        the world ray, as rtcsim's obb program does.
// The capsule test is the same code on both sides, so the comparison measures
// everything around it: traversal, instancing, the frame's own work.
// Compiled only where CMake finds Embree (sim/bench/CMakeLists.txt).
#pragma once

#include "core/ray.h"
#include "intersectors/capsule.h"

#include <embree3/rtcore.h>

#include <cstdint>
#include <span>
#include <string>

namespace rtc {

// One ray's closest hit as Embree found it (prim: the capsule's index).
// `r` as Embree's ray and hit record for rtcIntersect1: no hit yet, every
// mask bit, time 0 (both Embree baselines trace rtcsim's rays this way).
[[nodiscard]] inline RTCRayHit embree_ray_hit(const Ray& r) {
    RTCRayHit rh;
    rh.ray.org_x = r.origin.x, rh.ray.org_y = r.origin.y, rh.ray.org_z = r.origin.z;
    rh.ray.tnear = r.tmin;
    rh.ray.dir_x = r.direction.x, rh.ray.dir_y = r.direction.y, rh.ray.dir_z = r.direction.z;
    rh.ray.time = 0.0f;
    rh.ray.tfar = r.tmax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}

struct EmbreeHit {
    float t = kInfinity;
    std::uint32_t prim = 0xFFFFFFFFu;
    [[nodiscard]] bool hit() const { return prim != 0xFFFFFFFFu; }
};

class EmbreeCapsules {
public:
    // `method` is "ref" or "obb"; the capsules must outlive this object (the
    // callbacks read them). Throws std::runtime_error with Embree's message
    // when the device or a build fails.
    EmbreeCapsules(std::span<const Capsule> capsules, const std::string& method);
    ~EmbreeCapsules();
    EmbreeCapsules(const EmbreeCapsules&) = delete;
    EmbreeCapsules& operator=(const EmbreeCapsules&) = delete;

    // The closest hit of every ray, one rtcIntersect1 each, on `threads`
    // threads (core/parallel.h); hits.size() == rays.size().
    void trace(std::span<const Ray> rays, std::span<EmbreeHit> hits, unsigned threads) const;

    [[nodiscard]] double build_seconds() const { return build_seconds_; }

private:
    std::span<const Capsule> capsules_;
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;  // what rays are traced against
    RTCScene unit_ = nullptr;   // obb: the instanced unit-box scene
    double build_seconds_ = 0.0;
};

}  // namespace rtc
