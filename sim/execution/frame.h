// Running a workload through a method's compiled ray path: per ray, or in
// warps under the SIMT execution model (FrameOptions::warp). What a run
// takes and gives is in frame_result.h; the runners in per_ray_frame.h and
// warp_frame.h.
#pragma once

#include "sim/execution/frame_result.h"
#include "sim/execution/per_ray_frame.h"
#include "sim/execution/warp_frame.h"

namespace rtc {

// Traces the workload per ray, or in warps when fo.warp is set.
template <class Tracer>
FrameResult run_frame(const RayWorkload& frame, const FrameOptions& fo, const Tracer& tracer) {
    return fo.warp ? run_frame_warp(frame, fo, tracer) : run_frame_per_ray(frame, fo, tracer);
}

}  // namespace rtc
