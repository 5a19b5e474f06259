// The project's own intersection programs (intersectors/*.h, annotated for
// CUDA by devicify.py, otherwise unchanged) compiled for the GPU the paper
// used, one kernel per program, each called the way OptiX calls an
// intersection program: one (ray, candidate primitive) pair per thread, the
// primitive read from global memory, the hit written back. ptxas then
// reports what the program costs in registers on sm_75.
//
// Built by scripts/registers/measure; never part of the simulator's build.
#include <cstdint>

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"
#include "intersectors/triangle.h"

namespace {

// A sink that records nothing (Sink::kCounts false: count_ops compiles away).
struct NullSink {
    static constexpr bool kCounts = false;
    __device__ void on(rtc::Event) {}
    __device__ void add(rtc::Event, std::uint32_t) {}
};

struct HitOut {
    float t;
    float nx, ny, nz;
    float u;
    int prim;
};

template <class Prim, class Call>
__device__ void program(const Prim* prims, const rtc::Ray* rays, const int* candidate, HitOut* out, Call call) {
    const int i = blockIdx.x * blockDim.x + threadIdx.x;
    const rtc::Ray ray = rays[i];
    const int p = candidate[i];
    NullSink sink;
    const auto hit = call(prims[p], ray, sink);
    if (hit) out[i] = {hit->t, hit->normal.x, hit->normal.y, hit->normal.z, hit->u, p};
}

}  // namespace

extern "C" {

__global__ void is_cylinder(const rtc::Cylinder* prims, const rtc::Ray* rays, const int* cand, HitOut* out) {
    program(prims, rays, cand, out,
            [](const rtc::Cylinder& c, const rtc::Ray& r, NullSink& s) { return rtc::intersect(c, r, s); });
}

__global__ void is_capsule(const rtc::Capsule* prims, const rtc::Ray* rays, const int* cand, HitOut* out) {
    program(prims, rays, cand, out,
            [](const rtc::Capsule& c, const rtc::Ray& r, NullSink& s) { return rtc::intersect(c, r, s); });
}

__global__ void is_link(const rtc::Link* prims, const rtc::Ray* rays, const int* cand, HitOut* out) {
    program(prims, rays, cand, out,
            [](const rtc::Link& c, const rtc::Ray& r, NullSink& s) { return rtc::intersect(c, r, s); });
}

// The paper's program: Reshetov & Luebke with the bounding-cylinder early out.
__global__ void is_phantom_paper(const rtc::PhantomCurve* prims, const rtc::Ray* rays, const int* cand,
                                 HitOut* out) {
    program(prims, rays, cand, out, [](const rtc::PhantomCurve& c, const rtc::Ray& r, NullSink& s) {
        rtc::PhantomOptions opt;
        opt.program = rtc::PhantomProgram::Paper;
        return rtc::intersect(c, r, s, opt);
    });
}

// The project's bracketed program (phantom.h).
__global__ void is_phantom_bracketed(const rtc::PhantomCurve* prims, const rtc::Ray* rays, const int* cand,
                                     HitOut* out) {
    program(prims, rays, cand, out, [](const rtc::PhantomCurve& c, const rtc::Ray& r, NullSink& s) {
        return rtc::intersect(c, r, s, rtc::PhantomOptions{});
    });
}

// Triangles are tested by the RT core; this is the project's software copy of
// that test (Woop et al. 2013), for scale only.
__global__ void is_triangle(const rtc::Triangle* prims, const rtc::Ray* rays, const int* cand, HitOut* out) {
    program(prims, rays, cand, out,
            [](const rtc::Triangle& c, const rtc::Ray& r, NullSink& s) { return rtc::intersect(c, r, s); });
}

}  // extern "C"
