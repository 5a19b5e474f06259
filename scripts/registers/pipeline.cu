// A compact path tracer's ray generation and Disney-like BRDF shading (this
// project's own code, written for this measurement; sized after the Disney
// BRDF of ChameleonRT, the renderer Wald et al. 2020 used), compiled for
// sm_75 to measure what an OptiX pipeline's non-intersection programs cost in
// registers.
//
// OptiX 7 links a pipeline's programs into one kernel whose register count
// covers every program in it; the intersection program runs as a call inside
// traversal, so the pipeline's count is at least the largest of its
// programs'. Two kernels per intersection program bracket that:
//   pt_<kind>_split: shading with the trace reading its hit record from
//     memory (what the RT core hands back); the pipeline figure is then
//     max(pt_shade, is_<kind>) (programs.cu);
//   pt_<kind>_fused: the trace's candidate loop, calling the intersection
//     program, inlined into the bounce loop: everything the shading keeps
//     across the trace stays live around the program (an upper bracket).
// Built by scripts/registers/measure; never part of the simulator's build.
#include <cstdint>

#include "intersectors/capsule.h"
#include "intersectors/cylinder.h"
#include "intersectors/link.h"
#include "intersectors/phantom.h"

namespace pt {

struct NullSink {
    static constexpr bool kCounts = false;
    __device__ void on(rtc::Event) {}
    __device__ void add(rtc::Event, std::uint32_t) {}
};

struct V3 {
    float x, y, z;
};
__device__ inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
__device__ inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
__device__ inline V3 operator*(V3 a, V3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
__device__ inline V3 operator*(float s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
__device__ inline float dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
__device__ inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
__device__ inline V3 normalize(V3 a) { return rsqrtf(dot(a, a)) * a; }
__device__ inline V3 lerp(V3 a, V3 b, float t) { return (1.0f - t) * a + t * b; }
__device__ inline float lerpf(float a, float b, float t) { return (1.0f - t) * a + t * b; }
__device__ inline float luminance(V3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }
__device__ inline float sqr(float x) { return x * x; }

constexpr float kPi = 3.14159265358979f;

// PCG32 (O'Neill 2014), one state per path.
struct Rng {
    std::uint64_t state;
    __device__ float next() {
        const std::uint64_t old = state;
        state = old * 6364136223846793005ull + 1442695040888963407ull;
        const std::uint32_t xs = std::uint32_t(((old >> 18u) ^ old) >> 27u);
        const std::uint32_t rot = std::uint32_t(old >> 59u);
        const std::uint32_t r = (xs >> rot) | (xs << ((32u - rot) & 31u));
        return float(r >> 8) * 0x1p-24f;
    }
};

struct Material {
    V3 base_color;
    float metallic, specular, roughness, specular_tint, anisotropy;
    float sheen, sheen_tint, clearcoat, clearcoat_gloss, ior, specular_transmission;
};

struct Frame {
    V3 t, b, n;
};
__device__ inline Frame frame_of(V3 n) {  // Duff et al. 2017
    const float s = copysignf(1.0f, n.z);
    const float a = -1.0f / (s + n.z), b = n.x * n.y * a;
    return {{1.0f + s * n.x * n.x * a, s * b, -s * n.x}, {b, s + n.y * n.y * a, -n.y}, n};
}
__device__ inline V3 to_local(const Frame& f, V3 v) { return {dot(v, f.t), dot(v, f.b), dot(v, f.n)}; }
__device__ inline V3 to_world(const Frame& f, V3 v) { return v.x * f.t + v.y * f.b + v.z * f.n; }

// Disney 2012 / 2015 BRDF pieces (Burley), isotropic-or-anisotropic GGX.
__device__ inline float schlick(float c) { const float m = fminf(fmaxf(1.0f - c, 0.0f), 1.0f); return (m * m) * (m * m) * m; }
__device__ inline float gtr1(float nh, float a) {
    if (a >= 1.0f) return 1.0f / kPi;
    const float a2 = a * a, t = 1.0f + (a2 - 1.0f) * nh * nh;
    return (a2 - 1.0f) / (kPi * logf(a2) * t);
}
__device__ inline float gtr2_aniso(V3 h, float ax, float ay) {
    return 1.0f / (kPi * ax * ay * sqr(sqr(h.x / ax) + sqr(h.y / ay) + h.z * h.z));
}
__device__ inline float smith_g_aniso(V3 v, float ax, float ay) {
    const float tan2 = (sqr(v.x * ax) + sqr(v.y * ay)) / fmaxf(v.z * v.z, 1e-12f);
    return 2.0f / (1.0f + sqrtf(1.0f + tan2));
}
__device__ inline float smith_g_ggx(float nv, float a) {
    const float a2 = a * a, b = nv * nv;
    return 1.0f / (nv + sqrtf(a2 + b - a2 * b));
}
__device__ inline void aniso_alpha(const Material& m, float& ax, float& ay) {
    const float aspect = sqrtf(1.0f - 0.9f * m.anisotropy);
    ax = fmaxf(0.001f, sqr(m.roughness) / aspect);
    ay = fmaxf(0.001f, sqr(m.roughness) * aspect);
}

__device__ V3 disney_eval(const Material& m, V3 wo, V3 wi) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return {0.0f, 0.0f, 0.0f};
    V3 h = normalize(wo + wi);
    const float lum = luminance(m.base_color);
    const V3 tint = lum > 0.0f ? (1.0f / lum) * m.base_color : V3{1.0f, 1.0f, 1.0f};
    const V3 one{1.0f, 1.0f, 1.0f};
    const V3 spec0 = lerp(m.specular * 0.08f * lerp(one, tint, m.specular_tint), m.base_color, m.metallic);
    const V3 sheen_c = lerp(one, tint, m.sheen_tint);
    // diffuse (Burley) with the retro-reflection term and Hanrahan-Krueger-like subsurface flattening
    const float fl = schlick(wi.z), fv = schlick(wo.z), ld = dot(wi, h);
    const float fd90 = 0.5f + 2.0f * ld * ld * m.roughness;
    const float fd = lerpf(1.0f, fd90, fl) * lerpf(1.0f, fd90, fv);
    const float fss90 = ld * ld * m.roughness, fss = lerpf(1.0f, fss90, fl) * lerpf(1.0f, fss90, fv);
    const float ss = 1.25f * (fss * (1.0f / (wi.z + wo.z) - 0.5f) + 0.5f);
    const float diffuse = (1.0f / kPi) * lerpf(fd, ss, 0.3f) * (1.0f - m.metallic) * (1.0f - m.specular_transmission);
    // specular
    float ax, ay;
    aniso_alpha(m, ax, ay);
    const float ds = gtr2_aniso(h, ax, ay), fh = schlick(ld);
    const V3 fs = lerp(spec0, one, fh);
    const float gs = smith_g_aniso(wi, ax, ay) * smith_g_aniso(wo, ax, ay);
    // sheen, clearcoat
    const V3 sheen = (fh * m.sheen * (1.0f - m.metallic)) * sheen_c;
    const float dr = gtr1(h.z, lerpf(0.1f, 0.001f, m.clearcoat_gloss));
    const float fr = lerpf(0.04f, 1.0f, fh);
    const float gr = smith_g_ggx(wi.z, 0.25f) * smith_g_ggx(wo.z, 0.25f);
    const float cc = 0.25f * m.clearcoat * gr * fr * dr;
    const V3 spec = (ds * gs / (4.0f * wi.z * wo.z)) * fs;
    return diffuse * m.base_color + sheen + spec + V3{cc, cc, cc};
}

__device__ float disney_pdf(const Material& m, V3 wo, V3 wi) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const V3 h = normalize(wo + wi);
    float ax, ay;
    aniso_alpha(m, ax, ay);
    const float diffuse_w = (1.0f - m.metallic) * 0.5f, cc_w = 0.25f * m.clearcoat;
    const float spec_w = 1.0f - diffuse_w - cc_w;
    const float pd = wi.z / kPi;
    const float ps = gtr2_aniso(h, ax, ay) * h.z / (4.0f * fabsf(dot(wo, h)));
    const float pc = gtr1(h.z, lerpf(0.1f, 0.001f, m.clearcoat_gloss)) * h.z / (4.0f * fabsf(dot(wo, h)));
    return diffuse_w * pd + spec_w * ps + cc_w * pc;
}

__device__ V3 disney_sample(const Material& m, V3 wo, Rng& rng, V3& f, float& pdf) {
    const float diffuse_w = (1.0f - m.metallic) * 0.5f, cc_w = 0.25f * m.clearcoat;
    const float u = rng.next(), u1 = rng.next(), u2 = rng.next();
    V3 wi;
    if (u < diffuse_w) {  // cosine hemisphere
        const float r = sqrtf(u1), phi = 2.0f * kPi * u2;
        float s, c;
        sincosf(phi, &s, &c);
        wi = {r * c, r * s, sqrtf(fmaxf(0.0f, 1.0f - u1))};
    } else {
        V3 h;
        if (u < diffuse_w + cc_w) {  // GTR1 half vector
            const float a = lerpf(0.1f, 0.001f, m.clearcoat_gloss), a2 = a * a;
            const float cos_t = sqrtf(fmaxf(0.0f, (1.0f - powf(a2, 1.0f - u1)) / (1.0f - a2)));
            const float sin_t = sqrtf(fmaxf(0.0f, 1.0f - cos_t * cos_t));
            float s, c;
            sincosf(2.0f * kPi * u2, &s, &c);
            h = {sin_t * c, sin_t * s, cos_t};
        } else {  // anisotropic GGX half vector
            float ax, ay;
            aniso_alpha(m, ax, ay);
            float s, c;
            sincosf(2.0f * kPi * u2, &s, &c);
            V3 d{ax * sqrtf(u1) * c, ay * sqrtf(u1) * s, sqrtf(fmaxf(0.0f, 1.0f - u1))};
            h = normalize(d);
        }
        if (h.z < 0.0f) h = -1.0f * h;
        wi = 2.0f * dot(wo, h) * h - wo;
    }
    f = disney_eval(m, wo, wi);
    pdf = disney_pdf(m, wo, wi);
    return wi;
}

struct Hit {  // what the trace hands back: the closest hit or none
    float t;
    V3 n;
    float u;
    int prim;
};

struct Params {
    V3 eye, du, dv, dir00;
    int width, height, samples, max_depth;
    V3 light_p, light_u, light_v, light_e;
    const Material* materials;
    const int* material_of;
    float4* image;
};

// The trace, as the RT core would answer it: the hit record from memory.
__device__ Hit trace_record(const Hit* records, unsigned slot) { return records[slot]; }

// The trace with the intersection program inlined: the candidates the RT core
// would hand back, one program call each, nearest hit kept.
template <class Prim, class Call>
__device__ Hit trace_fused(const Prim* prims, const int* cand, int n_cand, V3 o, V3 d, float tmax, Call call) {
    Hit best{-1.0f, {0, 0, 0}, 0.0f, -1};
    rtc::Ray ray;
    ray.origin = rtc::Vec3(o.x, o.y, o.z);
    ray.direction = rtc::Vec3(d.x, d.y, d.z);
    ray.tmin = 1e-4f;
    ray.tmax = tmax;
    for (int k = 0; k < n_cand; ++k) {
        const int p = cand[k];
        NullSink sink;
        const auto h = call(prims[p], ray, sink);
        if (h) {
            ray.tmax = h->t;
            best = {h->t, {h->normal.x, h->normal.y, h->normal.z}, h->u, p};
        }
    }
    return best;
}

// Ray generation + per-bounce shading with next-event estimation and MIS;
// `trace(o, d, tmax, slot)` answers a ray.
template <class Trace>
__device__ void render(const Params& P, Trace trace) {
    const int px = blockIdx.x * blockDim.x + threadIdx.x, py = blockIdx.y;
    if (px >= P.width) return;
    Rng rng{(std::uint64_t(py) * P.width + px) * 0x9E3779B97F4A7C15ull + 1};
    V3 sum{0, 0, 0};
    unsigned slot = (py * P.width + px) * 64u;
    for (int s = 0; s < P.samples; ++s) {
        const float fx = (px + rng.next()) / P.width, fy = (py + rng.next()) / P.height;
        V3 o = P.eye, d = normalize(P.dir00 + fx * P.du + fy * P.dv);
        V3 throughput{1, 1, 1}, radiance{0, 0, 0};
        float prev_pdf = 1.0f;
        for (int depth = 0; depth < P.max_depth; ++depth) {
            const Hit hit = trace(o, d, 1e30f, slot++);
            if (hit.prim < 0) {  // miss: a constant sky
                radiance = radiance + 0.5f * throughput;
                break;
            }
            const Material m = P.materials[P.material_of[hit.prim]];
            const V3 p = o + hit.t * d;
            V3 n = normalize(hit.n);
            if (dot(n, d) > 0.0f) n = -1.0f * n;
            const Frame fr = frame_of(n);
            const V3 wo = to_local(fr, -1.0f * d);
            // next-event estimation on a quad light, MIS with the BRDF's pdf
            const float lu = rng.next(), lv = rng.next();
            const V3 lp = P.light_p + lu * P.light_u + lv * P.light_v;
            V3 ld = lp - p;
            const float dist2 = dot(ld, ld), dist = sqrtf(dist2);
            ld = (1.0f / dist) * ld;
            const V3 ln = normalize(cross(P.light_u, P.light_v));
            const float area = sqrtf(dot(cross(P.light_u, P.light_v), cross(P.light_u, P.light_v)));
            const float cos_l = fabsf(dot(ld, ln));
            const V3 wi_l = to_local(fr, ld);
            if (wi_l.z > 0.0f && cos_l > 0.0f) {
                const Hit shadow = trace(p, ld, dist * (1.0f - 1e-4f), slot++);
                if (shadow.prim < 0) {
                    const float light_pdf = dist2 / (cos_l * area);
                    const float bsdf_pdf = disney_pdf(m, wo, wi_l);
                    const float w = sqr(light_pdf) / (sqr(light_pdf) + sqr(bsdf_pdf));
                    const V3 f = disney_eval(m, wo, wi_l);
                    radiance = radiance + (wi_l.z * w / light_pdf) * (throughput * f * P.light_e);
                }
            }
            V3 f;
            float pdf;
            const V3 wi = disney_sample(m, wo, rng, f, pdf);
            if (!(pdf > 0.0f) || wi.z <= 0.0f) break;
            throughput = throughput * ((wi.z / pdf) * f);
            prev_pdf = pdf;
            // Russian roulette after three bounces
            if (depth > 2) {
                const float q = fmaxf(0.05f, 1.0f - fmaxf(throughput.x, fmaxf(throughput.y, throughput.z)));
                if (rng.next() < q) break;
                throughput = (1.0f / (1.0f - q)) * throughput;
            }
            o = p;
            d = to_world(fr, wi);
        }
        sum = sum + radiance + V3{0.0f * prev_pdf, 0.0f, 0.0f};
    }
    const float inv = 1.0f / P.samples;
    P.image[py * P.width + px] = make_float4(sum.x * inv, sum.y * inv, sum.z * inv, 1.0f);
}

}  // namespace pt

extern "C" {

// Shading alone: the trace is the RT core's answer read from memory (also the
// whole SM-side pipeline of a triangle-only scene: triangles need no program).
__global__ void pt_shade(pt::Params P, const pt::Hit* records) {
    pt::render(P, [&](pt::V3, pt::V3, float, unsigned slot) { return pt::trace_record(records, slot); });
}

#define RTCSIM_FUSED(NAME, PRIM, CALL)                                                                   \
    __global__ void NAME(pt::Params P, const PRIM* prims, const int* cand, int n_cand) {                 \
        pt::render(P, [&](pt::V3 o, pt::V3 d, float tmax, unsigned) {                                    \
            return pt::trace_fused(prims, cand, n_cand, o, d, tmax, CALL);                               \
        });                                                                                              \
    }

RTCSIM_FUSED(pt_cylinder_fused, rtc::Cylinder,
             [](const rtc::Cylinder& c, const rtc::Ray& r, pt::NullSink& s) { return rtc::intersect(c, r, s); })
RTCSIM_FUSED(pt_capsule_fused, rtc::Capsule,
             [](const rtc::Capsule& c, const rtc::Ray& r, pt::NullSink& s) { return rtc::intersect(c, r, s); })
RTCSIM_FUSED(pt_link_fused, rtc::Link,
             [](const rtc::Link& c, const rtc::Ray& r, pt::NullSink& s) { return rtc::intersect(c, r, s); })
RTCSIM_FUSED(pt_phantom_paper_fused, rtc::PhantomCurve, [](const rtc::PhantomCurve& c, const rtc::Ray& r, pt::NullSink& s) {
    rtc::PhantomOptions opt;
    opt.program = rtc::PhantomProgram::Paper;
    return rtc::intersect(c, r, s, opt);
})
RTCSIM_FUSED(pt_phantom_bracketed_fused, rtc::PhantomCurve,
             [](const rtc::PhantomCurve& c, const rtc::Ray& r, pt::NullSink& s) {
                 return rtc::intersect(c, r, s, rtc::PhantomOptions{});
             })

}  // extern "C"
