#include "sim/bench/embree_scene.h"

#include "core/affine.h"
#include "core/obb.h"
#include "core/parallel.h"
#include "core/sinks.h"

#include <chrono>
#include <stdexcept>

namespace rtc {

namespace {

// What a trace hands its callbacks. Embree gives an instanced primitive's
// callback the ray in the instance's space; the capsule test takes the world
// ray (rtcsim's obb program gets the world ray, as hardware's
// WorldRayOrigin/Direction), so each trace keeps a pointer to it here: a
// struct that starts with the context, Embree's way of passing per-ray data.
struct TraceContext {
    RTCIntersectContext context;
    const Ray* world_ray = nullptr;
    const Capsule* capsules = nullptr;
};

RTCBounds to_rtc(const Aabb& b) {
    RTCBounds r{};
    r.lower_x = b.lo.x, r.lower_y = b.lo.y, r.lower_z = b.lo.z;
    r.upper_x = b.hi.x, r.upper_y = b.hi.y, r.upper_z = b.hi.z;
    return r;
}

void capsule_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* capsules = static_cast<const Capsule*>(args->geometryUserPtr);
    *args->bounds_o = to_rtc(bounds(capsules[args->primID]));
}

void unit_box_bounds(const RTCBoundsFunctionArguments* args) { *args->bounds_o = to_rtc(kUnitBox); }

// The capsule test of capsule `index` on the trace's world ray, clipped to the
// ray's current [tnear, tfar] (t is the same in instance and world space: an
// instance transforms the direction without normalising it); a nearer hit
// becomes the ray's closest.
void hit_capsule(const RTCIntersectFunctionNArguments* args, std::uint32_t index) {
    if (args->N != 1 || args->valid[0] == 0) return;  // rtcIntersect1 only: one ray
    const auto* ctx = reinterpret_cast<const TraceContext*>(args->context);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, 1);
    Ray world = *ctx->world_ray;
    world.tmin = RTCRayN_tnear(ray, 1, 0);
    world.tmax = RTCRayN_tfar(ray, 1, 0);
    NullSink sink;
    const std::optional<Hit> hit = intersect(ctx->capsules[index], world, sink);
    if (!hit) return;
    RTCHitN* h = RTCRayHitN_HitN(args->rayhit, 1);
    RTCRayN_tfar(ray, 1, 0) = hit->t;
    RTCHitN_Ng_x(h, 1, 0) = hit->normal.x;  // world space (nothing here reads it)
    RTCHitN_Ng_y(h, 1, 0) = hit->normal.y;
    RTCHitN_Ng_z(h, 1, 0) = hit->normal.z;
    RTCHitN_u(h, 1, 0) = hit->u;
    RTCHitN_v(h, 1, 0) = 0.0f;
    RTCHitN_primID(h, 1, 0) = index;
    RTCHitN_geomID(h, 1, 0) = args->geomID;
    RTCHitN_instID(h, 1, 0, 0) = args->context->instID[0];
}

void ref_intersect(const RTCIntersectFunctionNArguments* args) { hit_capsule(args, args->primID); }
void obb_intersect(const RTCIntersectFunctionNArguments* args) { hit_capsule(args, args->context->instID[0]); }

void throw_on_error(RTCDevice device, const char* what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + what + " failed (error " + std::to_string(e) + ")");
}

// A user geometry of `count` primitives with these callbacks, attached to `scene`.
void attach_user_geometry(RTCDevice device, RTCScene scene, unsigned count, const void* data,
                          RTCBoundsFunction bounds_fn, RTCIntersectFunctionN intersect_fn) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, count);
    rtcSetGeometryUserData(g, const_cast<void*>(data));  // Embree's API is not const
    rtcSetGeometryBoundsFunction(g, bounds_fn, nullptr);
    rtcSetGeometryIntersectFunction(g, intersect_fn);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
}

}  // namespace

EmbreeCapsules::EmbreeCapsules(std::span<const Capsule> capsules, const std::string& method)
    : capsules_(capsules) {
    if (method != "ref" && method != "obb") throw std::runtime_error("Embree: no method " + method);
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
    const auto t0 = std::chrono::steady_clock::now();
    scene_ = rtcNewScene(device_);
    const auto count = static_cast<unsigned>(capsules.size());
    if (method == "ref") {
        attach_user_geometry(device_, scene_, count, capsules.data(), capsule_bounds, ref_intersect);
    } else {
        unit_ = rtcNewScene(device_);
        attach_user_geometry(device_, unit_, 1, nullptr, unit_box_bounds, obb_intersect);
        rtcCommitScene(unit_);
        for (unsigned i = 0; i < count; ++i) {
            // The affine map of rtcsim's obb instance, columns then translation.
            const Affine a = oriented_bounds(capsules[i]).world_from_unit;
            float xfm[12];
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) xfm[3 * c + r] = a.linear[c][r];
            for (int r = 0; r < 3; ++r) xfm[9 + r] = a.translation[r];
            RTCGeometry inst = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, unit_);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
            rtcCommitGeometry(inst);
            rtcAttachGeometryByID(scene_, inst, i);  // instID = the capsule's index
            rtcReleaseGeometry(inst);
        }
    }
    rtcCommitScene(scene_);
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    throw_on_error(device_, "the scene's build");
}

EmbreeCapsules::~EmbreeCapsules() {
    if (scene_) rtcReleaseScene(scene_);
    if (unit_) rtcReleaseScene(unit_);
    if (device_) rtcReleaseDevice(device_);
}

void EmbreeCapsules::trace(std::span<const Ray> rays, std::span<EmbreeHit> hits, unsigned threads) const {
    constexpr std::size_t kBlock = 256;  // rays per hand-out: small frames still spread over the threads
    parallel_for((rays.size() + kBlock - 1) / kBlock, threads, [&](std::size_t block, unsigned) {
        TraceContext ctx;
        rtcInitIntersectContext(&ctx.context);
        ctx.capsules = capsules_.data();
        const std::size_t end = std::min(rays.size(), (block + 1) * kBlock);
        for (std::size_t i = block * kBlock; i < end; ++i) {
            const Ray& r = rays[i];
            ctx.world_ray = &r;
            RTCRayHit rh = embree_ray_hit(r);
            rtcIntersect1(scene_, &ctx.context, &rh);
            hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? EmbreeHit{} : EmbreeHit{rh.ray.tfar, rh.hit.primID};
        }
    }, 1);
}

}  // namespace rtc
