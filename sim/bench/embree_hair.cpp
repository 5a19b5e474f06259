#include "sim/bench/embree_hair.h"

#include <sstream>
#include <stdexcept>

#if RTCSIM_EMBREE
#include "core/parallel.h"
#include "core/sinks.h"
#include "sim/bench/embree_scene.h"  // embree_ray_hit

#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <iostream>
#endif

namespace rtc {

const char* hair_bvh_name(HairBvh bvh) { return bvh == HairBvh::Aligned ? "aligned" : "oriented"; }

namespace {

// The number after `key` on `line` ("#nodes =    3258"), or 0.
double number_after(const std::string& line, const std::string& key) {
    const std::size_t at = line.find(key);
    if (at == std::string::npos) return 0.0;
    std::istringstream in(line.substr(at + key.size()));
    double x = 0.0;
    in >> x;
    return in ? x : 0.0;
}

}  // namespace

// The lines of kernels/bvh/bvh.cpp (postBuild) and bvh_statistics.cpp:
//   building BVH8<curve8v> using avx::BVH8HairBuilderSAH ...
//     total            : sah = ..., #bytes =    0.52 MB (100.00%), #nodes = ...
//     getAABBNodes     : ... #nodes =       9 (...)     <- aligned nodes
//     ungetAABBNodes   : ... #nodes =     576 (...)     <- oriented nodes
//     leaves           : ... #nodes =    2673 (...)     <- leaves
std::vector<EmbreeBvhStats> parse_embree_statistics(const std::string& printed) {
    std::vector<EmbreeBvhStats> out;
    std::istringstream in(printed);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("building BVH", 0) == 0) {
            EmbreeBvhStats s;
            const std::size_t lt = line.find('<'), gt = line.find('>'), using_at = line.find(" using ");
            if (lt != std::string::npos && gt != std::string::npos && gt > lt)
                s.primitive = line.substr(lt + 1, gt - lt - 1);
            if (using_at != std::string::npos) {
                s.builder = line.substr(using_at + 7);
                s.builder = s.builder.substr(0, s.builder.find(' '));
            }
            out.push_back(s);
            continue;
        }
        if (out.empty()) continue;
        EmbreeBvhStats& s = out.back();
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        std::string head = line.substr(0, colon);
        head.erase(0, head.find_first_not_of(' '));
        head.erase(head.find_last_not_of(' ') + 1);
        const auto nodes = static_cast<std::uint64_t>(number_after(line, "#nodes ="));
        if (head == "total" && line.find("sah =") != std::string::npos) {  // not the allocator's "total :"
            s.sah = number_after(line, "sah =");
            s.bytes = number_after(line, "#bytes =") * 1e6;
        } else if (head == "getAABBNodes") {
            s.aligned_nodes = nodes;
        } else if (head == "ungetAABBNodes") {
            s.oriented_nodes = nodes;
        } else if (head == "leaves") {
            s.leaves = nodes;
        }
    }
    return out;
}

#if RTCSIM_EMBREE

namespace {

// What a trace hands the aligned side's callback (Embree's way of passing
// per-ray data: a struct that starts with the context).
struct TraceContext {
    RTCIntersectContext context;
    const Ray* world_ray = nullptr;
    const Capsule* capsules = nullptr;
    std::uint64_t tests = 0;
};

void capsule_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* capsules = static_cast<const Capsule*>(args->geometryUserPtr);
    const Aabb b = bounds(capsules[args->primID]);
    RTCBounds& r = *args->bounds_o;
    r.lower_x = b.lo.x, r.lower_y = b.lo.y, r.lower_z = b.lo.z;
    r.upper_x = b.hi.x, r.upper_y = b.hi.y, r.upper_z = b.hi.z;
}

// rtcsim's capsule test on the ray within its current [tnear, tfar]; a nearer
// hit becomes the ray's closest.
void capsule_intersect(const RTCIntersectFunctionNArguments* args) {
    if (args->N != 1 || args->valid[0] == 0) return;  // rtcIntersect1 only: one ray
    auto* ctx = reinterpret_cast<TraceContext*>(args->context);
    ++ctx->tests;
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, 1);
    Ray world = *ctx->world_ray;
    world.tmin = RTCRayN_tnear(ray, 1, 0);
    world.tmax = RTCRayN_tfar(ray, 1, 0);
    NullSink sink;
    const std::optional<Hit> hit = intersect(ctx->capsules[args->primID], world, sink);
    if (!hit) return;
    RTCHitN* h = RTCRayHitN_HitN(args->rayhit, 1);
    RTCRayN_tfar(ray, 1, 0) = hit->t;
    RTCHitN_Ng_x(h, 1, 0) = hit->normal.x;
    RTCHitN_Ng_y(h, 1, 0) = hit->normal.y;
    RTCHitN_Ng_z(h, 1, 0) = hit->normal.z;
    RTCHitN_u(h, 1, 0) = hit->u;
    RTCHitN_v(h, 1, 0) = 0.0f;
    RTCHitN_primID(h, 1, 0) = args->primID;
    RTCHitN_geomID(h, 1, 0) = args->geomID;
    RTCHitN_instID(h, 1, 0, 0) = RTC_INVALID_GEOMETRY_ID;
}

// The device's byte count, through the memory monitor callback.
bool count_bytes(void* user, ssize_t bytes, bool /*post*/) {
    static_cast<std::atomic<std::int64_t>*>(user)->fetch_add(bytes, std::memory_order_relaxed);
    return true;
}

void throw_on_error(RTCDevice device, const std::string& what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw std::runtime_error("Embree: " + what + " failed (error " + std::to_string(e) + ")");
}

// Embree prints its statistics on std::cout (the same object as ours: both
// use the shared libstdc++); while one of these lives they go to `text`.
class CaptureStdout {
public:
    explicit CaptureStdout(std::ostringstream& text) : old_(std::cout.rdbuf(text.rdbuf())) {}
    ~CaptureStdout() { std::cout.rdbuf(old_); }
    CaptureStdout(const CaptureStdout&) = delete;
    CaptureStdout& operator=(const CaptureStdout&) = delete;

private:
    std::streambuf* old_;
};

}  // namespace

struct EmbreeHairScene::Impl {
    std::span<const Capsule> capsules;
    HairBvh bvh = HairBvh::Aligned;
    std::string config;
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::atomic<std::int64_t> bytes{0};
    std::int64_t bytes_after_build = 0;
    double build_seconds = 0.0;
    std::vector<EmbreeBvhStats> stats;
    unsigned hair_geometry = RTC_INVALID_GEOMETRY_ID;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

EmbreeHairScene::EmbreeHairScene(std::span<const Capsule> capsules, std::span<const Triangle> triangles,
                                 HairBvh bvh, unsigned build_threads)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.capsules = capsules;
    m.bvh = bvh;
    // Both sides 8 wide (what Embree picks by default on AVX2), the
    // hair_accel value the oriented side's default would pick too, said
    // explicitly so that the statistics show which was built.
    m.config = "threads=" + std::to_string(build_threads) + ",verbose=2," +
               (bvh == HairBvh::Aligned ? "object_accel=bvh8.object" : "hair_accel=bvh8obb.virtualcurve8v");
    std::ostringstream printed;
    {
        const CaptureStdout capture(printed);
        m.device = rtcNewDevice(m.config.c_str());
        if (!m.device) throw std::runtime_error("Embree: rtcNewDevice(\"" + m.config + "\") failed");
        rtcSetDeviceMemoryMonitorFunction(m.device, count_bytes, &m.bytes);
        m.scene = rtcNewScene(m.device);
        const auto count = static_cast<unsigned>(capsules.size());
        RTCGeometry g = nullptr;
        if (bvh == HairBvh::Aligned) {
            g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(g, count);
            rtcSetGeometryUserData(g, const_cast<Capsule*>(capsules.data()));  // Embree's API is not const
            rtcSetGeometryBoundsFunction(g, capsule_bounds, nullptr);
            rtcSetGeometryIntersectFunction(g, capsule_intersect);
        } else {
            // Two vertices (x, y, z, radius) per segment, and no neighbours
            // (index i is 2 i, never the last one's end): a sphere at both
            // ends, the capsule.
            g = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), 2 * count));
            auto* index = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), count));
            throw_on_error(m.device, "the curve buffers");
            for (unsigned i = 0; i < count; ++i) {
                const Capsule& c = capsules[i];
                float* p = v + 8 * static_cast<std::size_t>(i);
                p[0] = c.p0.x, p[1] = c.p0.y, p[2] = c.p0.z, p[3] = c.radius;
                p[4] = c.p1.x, p[5] = c.p1.y, p[6] = c.p1.z, p[7] = c.radius;
                index[i] = 2 * i;
            }
        }
        rtcCommitGeometry(g);
        m.hair_geometry = rtcAttachGeometry(m.scene, g);
        rtcReleaseGeometry(g);
        if (!triangles.empty()) {
            RTCGeometry mesh = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
            const auto n = static_cast<unsigned>(triangles.size());
            auto* v = static_cast<float*>(
                rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
            auto* index = static_cast<unsigned*>(
                rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
            throw_on_error(m.device, "the mesh buffers");
            for (unsigned i = 0; i < n; ++i) {
                const Triangle& t = triangles[i];
                const Vec3 corners[3] = {t.v0, t.v1, t.v2};
                for (unsigned k = 0; k < 3; ++k) {
                    float* p = v + 3 * (3 * static_cast<std::size_t>(i) + k);
                    p[0] = corners[k].x, p[1] = corners[k].y, p[2] = corners[k].z;
                    index[3 * i + k] = 3 * i + k;
                }
            }
            rtcCommitGeometry(mesh);
            rtcAttachGeometry(m.scene, mesh);
            rtcReleaseGeometry(mesh);
        }
        const auto t0 = std::chrono::steady_clock::now();
        rtcCommitScene(m.scene);
        m.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::cout << std::flush;
    }
    throw_on_error(m.device, "the scene's build (" + m.config + ")");
    m.bytes_after_build = m.bytes.load();
    m.stats = parse_embree_statistics(printed.str());
    if (m.stats.empty()) throw std::runtime_error("Embree printed no BVH statistics under " + m.config);
}

EmbreeHairScene::~EmbreeHairScene() = default;

std::uint64_t EmbreeHairScene::trace(std::span<const Ray> rays, std::span<HairHit> hits, unsigned threads) const {
    const Impl& m = *impl_;
    constexpr std::size_t kBlock = 256;  // rays per hand-out
    std::atomic<std::uint64_t> tests{0};
    parallel_for((rays.size() + kBlock - 1) / kBlock, threads, [&](std::size_t block, unsigned) {
        TraceContext ctx;
        rtcInitIntersectContext(&ctx.context);
        ctx.capsules = m.capsules.data();
        const std::size_t end = std::min(rays.size(), (block + 1) * kBlock);
        for (std::size_t i = block * kBlock; i < end; ++i) {
            const Ray& r = rays[i];
            ctx.world_ray = &r;
            RTCRayHit rh = embree_ray_hit(r);
            rtcIntersect1(m.scene, &ctx.context, &rh);
            HairHit h;
            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
                h.t = rh.ray.tfar;
                h.prim = rh.hit.geomID == m.hair_geometry ? rh.hit.primID : HairHit::kMeshPrim;
            }
            hits[i] = h;
        }
        tests.fetch_add(ctx.tests, std::memory_order_relaxed);
    }, 1);
    return tests.load();
}

std::string embree_version() { return RTC_VERSION_STRING; }

HairBvh EmbreeHairScene::bvh() const { return impl_->bvh; }
double EmbreeHairScene::build_seconds() const { return impl_->build_seconds; }
std::int64_t EmbreeHairScene::embree_bytes() const { return impl_->bytes_after_build; }
const std::vector<EmbreeBvhStats>& EmbreeHairScene::bvh_stats() const { return impl_->stats; }
const std::string& EmbreeHairScene::device_config() const { return impl_->config; }

const EmbreeBvhStats& EmbreeHairScene::hair_stats() const {
    // The mesh's BVH is over triangles; the other one is the hair's.
    for (const EmbreeBvhStats& s : impl_->stats)
        if (s.primitive.rfind("triangle", 0) != 0) return s;
    throw std::runtime_error("Embree: no hair BVH among the statistics under " + impl_->config);
}

#else

struct EmbreeHairScene::Impl {};

std::string embree_version() { return ""; }

EmbreeHairScene::EmbreeHairScene(std::span<const Capsule>, std::span<const Triangle>, HairBvh, unsigned) {
    throw std::runtime_error("bench was built without Embree 3 (apt-get install libembree-dev, then configure again)");
}
EmbreeHairScene::~EmbreeHairScene() = default;
std::uint64_t EmbreeHairScene::trace(std::span<const Ray>, std::span<HairHit>, unsigned) const { return 0; }
HairBvh EmbreeHairScene::bvh() const { return HairBvh::Aligned; }
double EmbreeHairScene::build_seconds() const { return 0.0; }
std::int64_t EmbreeHairScene::embree_bytes() const { return 0; }
const std::vector<EmbreeBvhStats>& EmbreeHairScene::bvh_stats() const {
    static const std::vector<EmbreeBvhStats> none;
    return none;
}
const EmbreeBvhStats& EmbreeHairScene::hair_stats() const { throw std::runtime_error("built without Embree"); }
const std::string& EmbreeHairScene::device_config() const {
    static const std::string none;
    return none;
}

#endif

}  // namespace rtc
