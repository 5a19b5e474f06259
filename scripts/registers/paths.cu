// One program path per kernel, each straight-line or nearly so, for the
// dependent-chain analysis (ilp.py): which of a path's instructions wait on
// which. Every path is the project's own code (intersectors/*.h through
// devicify.py); a kernel only loads its inputs from global memory and stores
// what the path computes, so nothing is optimised away.
// Built by scripts/registers/measure; never part of the simulator's build.
#include <cstdint>

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"

namespace {

struct NullSink {
    static constexpr bool kCounts = false;
    __device__ void on(rtc::Event) {}
    __device__ void add(rtc::Event, std::uint32_t) {}
};

__device__ int tid() { return blockIdx.x * blockDim.x + threadIdx.x; }

// The programs' working precision (double, or float in the --float variant),
// so the harness adds no conversions of its own.
using Real = decltype(rtc::LocalRay::dd);

}  // namespace

extern "C" {

// Capsule, the common path: the frame and both cheap rejects (most calls end here).
__global__ void path_capsule_reject(const rtc::Capsule* prims, const rtc::Ray* rays, int* out) {
    const int i = tid();
    const rtc::Capsule cap = prims[i];
    const auto f = rtc::detail::capsule_frame_scalar(cap, rays[i]);
    out[i] = rtc::detail::capsule_reject_by(f, Real(cap.radius));
}

// Capsule, the solve after the rejects passed (capsule_hit's body).
__global__ void path_capsule_solve(const rtc::Capsule* prims, const rtc::Ray* rays, float* out) {
    const int i = tid();
    const rtc::Capsule cap = prims[i];
    const rtc::Ray ray = rays[i];
    const auto f = rtc::detail::capsule_frame_scalar(cap, ray);
    const auto h = rtc::detail::capsule_solve(ray, rtc::local_ray(f.d, f.oc, f.dd, f.od), f.a, f.ba, f.len2,
                                              Real(cap.radius));
    out[i] = h ? h->t : -1.0f;
}

// Cylinder and link: whole programs (one path each once the sphere reject passes).
__global__ void path_cylinder(const rtc::Cylinder* prims, const rtc::Ray* rays, float* out) {
    const int i = tid();
    NullSink s;
    const auto h = rtc::intersect(prims[i], rays[i], s);
    out[i] = h ? h->t : -1.0f;
}
__global__ void path_link(const rtc::Link* prims, const rtc::Ray* rays, float* out) {
    const int i = tid();
    NullSink s;
    const auto h = rtc::intersect(prims[i], rays[i], s);
    out[i] = h ? h->t : -1.0f;
}

// The paper's phantom program: the bounding-cylinder early out.
__global__ void path_reshetov_cylinder(const rtc::PhantomCurve* prims, const rtc::Ray* rays, int* out) {
    const int i = tid();
    const rtc::PhantomCurve pc = prims[i];
    out[i] = rtc::detail::reshetov_cylinder(pc, rays[i], Real(rtc::max_radius(pc)));
}

// Both phantom programs: the ray-centric frame (set-up).
__global__ void path_phantom_frame(const rtc::PhantomCurve* prims, const rtc::Ray* rays, Real* out) {
    const int i = tid();
    const auto c = rtc::detail::to_ray_frame(prims[i], rays[i]);
    Real s = c.dlen;
    for (int k = 0; k < 4; ++k) s += c.q[k].x + c.q[k].y + c.q[k].z + c.r[k];
    out[i] = s;
}

// The paper's phantom program: exactly one iteration of reshetov_search
// (max_iterations = 1), its curve already in the ray frame.
__global__ void path_reshetov_iteration(const rtc::detail::RccCurve* curves, const Real* t0, Real* out) {
    const int i = tid();
    std::uint32_t it = 0;
    const auto h = rtc::detail::reshetov_search(curves[i], t0[i], Real(0), 1, it);
    out[i] = h ? h->s : Real(-1);
}

// The bracketed program: exactly one iteration of phantom_search.
__global__ void path_phantom_iteration(const rtc::detail::RccCurve* curves, const Real* t0, Real* out) {
    const int i = tid();
    rtc::detail::PhantomCandidate best;
    const auto& c = curves[i];
    rtc::detail::phantom_search(c.q, c.r, t0[i], Real(0), Real(1), Real(0), 1, best);
    out[i] = best.s;
}

}  // extern "C"
