// split: long primitives referenced from several smaller AABBs along their
// length (spatial splits), in one custom-primitive BLAS as ref. OptiX splits
// curve segments into separately bounded sub-segments when asked for fast
// traces (no factors published); pbrt-v4 cuts each cubic into 2^splitdepth =
// 8 pieces by default (src/pbrt/shapes.cpp). Here each primitive is halved
// recursively along its parameter, at most 3 times (8 pieces, pbrt-v4's
// default), while the two halves' AABB surface areas sum to less than kGain
// of their parent's: the expected number of boxes a ray reaches falls by at
// least 1 - kGain per cut (the AABB/OBB area ratio is the stop test
// rt-hardware.md section 9 suggests). Aligned primitives stay whole.
//
// What the hardware does: every reference is a leaf box; each one a ray
// reaches is a context switch and a call of the whole primitive's program
// (with the world ray), so the same primitive reached through two boxes is
// two calls, counted as such. Closest hits are identical to ref's: a piece's
// box contains that part of the primitive, the pieces cover it, and the
// program tests the whole primitive. Memory: one custom_prim per reference.
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

namespace rtc {

namespace {

constexpr int kMaxDepth = 3;
constexpr double kGain = 0.7;

double half_area(const Aabb& b) { return 0.5 * double(b.surface_area()); }

// A straight primitive's part between axis parameters a and b: spheres of
// linearly varying radius (capsule, link: each part is the hull of its end
// spheres) or flat discs across the axis (cylinder: the hull of two discs).
struct Straight {
    DVec3 p0, p1;
    double r0, r1;
    bool discs;
    [[nodiscard]] Aabb box(double a, double b) const {
        const DVec3 pa = p0 + a * (p1 - p0), pb = p0 + b * (p1 - p0);
        DVec3 ea(r0 + a * (r1 - r0)), eb(r0 + b * (r1 - r0));
        if (discs) {
            const DVec3 w = p1 - p0;
            const double l2 = glm::dot(w, w);
            // r0 sqrt(1 - w_i^2 / l2) as sqrt(w_j^2 + w_k^2) (no cancellation),
            // widened by 2^-40 for its roundings (as bounds(Cylinder)).
            const DVec3 a2 = w * w;
            if (l2 > 0.0)
                ea = eb = r0 * (glm::sqrt(DVec3(a2.y + a2.z, a2.z + a2.x, a2.x + a2.y) / l2) + 0x1p-40);
        }
        return outward_bounds(glm::min(pa - ea, pb - eb), glm::max(pa + ea, pb + eb));
    }
    void pieces(double a, double b, int depth, std::vector<Aabb>& out) const {
        const Aabb whole = box(a, b);
        const double m = 0.5 * (a + b);
        if (depth < kMaxDepth && half_area(box(a, m)) + half_area(box(m, b)) < kGain * half_area(whole)) {
            pieces(a, m, depth + 1, out);
            pieces(m, b, depth + 1, out);
        } else {
            out.push_back(whole);
        }
    }
};

Straight straight(const Cylinder& c) { return {DVec3(c.p0), DVec3(c.p1), c.radius, c.radius, true}; }
Straight straight(const Capsule& c) { return {DVec3(c.p0), DVec3(c.p1), c.radius, c.radius, false}; }
Straight straight(const Link& k) { return {DVec3(k.p0), DVec3(k.p1), k.r0, k.r1, false}; }

// A phantom curve's part: its control points and radii (de Casteljau, in double).
struct CurvePart {
    std::array<DVec3, 4> p;
    std::array<double, 4> r;
    [[nodiscard]] Aabb box() const {
        DVec3 lo(kInfinity), hi(-kInfinity);
        const double rad = std::max({r[0], r[1], r[2], r[3], 0.0});
        for (const DVec3& q : p) lo = glm::min(lo, q - rad), hi = glm::max(hi, q + rad);
        return outward_bounds(lo, hi);
    }
    [[nodiscard]] std::pair<CurvePart, CurvePart> halves() const {
        CurvePart l, h;
        const auto cut = [](const auto& c, auto& left, auto& right) {
            const auto m01 = 0.5 * (c[0] + c[1]), m12 = 0.5 * (c[1] + c[2]), m23 = 0.5 * (c[2] + c[3]);
            const auto a = 0.5 * (m01 + m12), b = 0.5 * (m12 + m23), mid = 0.5 * (a + b);
            left = {c[0], m01, a, mid};
            right = {mid, b, m23, c[3]};
        };
        cut(p, l.p, h.p);
        cut(r, l.r, h.r);
        return {l, h};
    }
    void pieces(int depth, std::vector<Aabb>& out) const {
        const auto [l, h] = halves();
        if (depth < kMaxDepth && half_area(l.box()) + half_area(h.box()) < kGain * half_area(box())) {
            l.pieces(depth + 1, out);
            h.pieces(depth + 1, out);
        } else {
            out.push_back(box());
        }
    }
};

template <class Prim>
void split_primitive(const Prim& prim, std::vector<Aabb>& out) {
    if constexpr (std::is_same_v<Prim, PhantomCurve>) {
        CurvePart c;
        for (int i = 0; i < 4; ++i) c.p[i] = DVec3(prim.cp[i]), c.r[i] = prim.radius[i];
        c.pieces(0, out);
    } else {
        straight(prim).pieces(0.0, 1.0, 0, out);
    }
    // The whole primitive's own box bounds every piece too: never worse than ref.
    if (out.size() == 1) out.front() = bounds(prim);
}

template <class Prim>
TwoLevelStructures build_split(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    std::vector<std::vector<Aabb>> per_prim(prims.size());
    parallel_for(prims.size(), o.custom_blas.threads, [&](std::size_t i, unsigned) {
        if (!is_finite(prims[i]))
            throw std::invalid_argument("split: primitive " + std::to_string(i) + " is not finite");
        split_primitive(prims[i], per_prim[i]);
    });
    std::vector<Aabb> boxes;
    std::vector<std::uint32_t> prim_of;
    for (std::size_t i = 0; i < prims.size(); ++i)
        for (const Aabb& b : per_prim[i]) boxes.push_back(b), prim_of.push_back(static_cast<std::uint32_t>(i));
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.custom_blas));
    // Leaves name the primitive, not the reference: the program is the primitive's.
    for (std::uint32_t& id : blases.front().prim_ids) id = prim_of[id];
    std::vector<BlasKind> kinds{BlasKind::Custom};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh_blas(g, o, blases, kinds, instances);
    return {build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)};
}

struct SplitLeaf {
    template <class Programs>
    static float custom_leaf(const PrimitiveQuery& q, Programs& programs) {
        return programs.custom(q.prim, q.world_ray, q.tmax);
    }
};

}  // namespace

MethodEntry split_method() {
    return {{"split",
             "ref with long primitives split into up to 8 AABB references along their length (pbrt-v4, OptiX)",
             {"custom_primitives"}},
            [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
            [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                return std::make_unique<BuiltMethodOf<TwoLevelMethod<SplitLeaf>>>(
                    std::visit([&](const auto& prims) { return build_split(prims, g, o); }, g.prims));
            }};
}

}  // namespace rtc
