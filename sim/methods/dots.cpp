// dots: disjoint orthogonal triangle strips, how RTX hair was ray traced on
// the triangle path before LSS hardware, and NVIDIA's fallback where LSS is
// missing (RTX Character Rendering SDK, NVIDIA-RTX/RTXCR README; NVIDIA
// developer blog "Render Path-Traced Hair in Real Time with NVIDIA GeForce
// RTX 50 Series GPUs", 2025). Each straight segment becomes two quads that
// cross on its axis, in planes through the axis at right angles to each
// other, fixed in the segment's frame (not turned towards the camera), so any
// view sees at least one of them: 4 triangles, tested by the RT unit like
// mesh triangles, with no hand-over and no intersection program.
//
// As RTXCR's CurveTessellation::convertToDisjointOrthogonalTriangleStrips:
// the frame is the segment's direction plus a perpendicular chosen from its
// smallest component (perpStark), and each quad's half-width at an end is
// that end's radius times pi / (2 sqrt 2) = 1.11. Why that factor: seen from
// angle theta about the axis, the two quads span 2 w max(|cos|, |sin|),
// whose mean over theta is 2 w (2 sqrt 2 / pi); with w = r pi / (2 sqrt 2)
// the mean silhouette is the tube's 2 r. The quads reach 1.11 r from the axis
// in their own planes, so a ray can hit a quad just outside the tube, and a
// hit lies on a plane through the axis rather than on the surface: hits
// approximate ref's (MethodInfo::approximate; the run reports agreement).
//
// Straight kinds only (capsules, links, cylinders): a phantom curve is a
// cubic Bezier, and DOTS of a curve is a polyline approximation whose piece
// count is a choice of its own (not modelled; run the scene as capsules).
// Memory: the BLAS's triangle records plus the strips' own vertex and index
// buffers (4 vertices and 2 triangles per quad, indexed; RTXCR keeps 6
// unindexed vertices per quad with shading attributes, so this is a lower
// bound on what a renderer stores).
#include "core/parallel.h"
#include "sim/methods/common/method_adapter.h"
#include "sim/methods/common/two_level_method.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rtc {

namespace {

constexpr std::uint32_t kTrianglesPerSegment = 4;  // 2 quads x 2 triangles
constexpr std::uint32_t kVerticesPerSegment = 8;   // 2 quads x 4 corners
// The quads' half-width over the radius (see the top of the file).
constexpr double kHalfWidthPerRadius = std::numbers::pi / (2.0 * std::numbers::sqrt2);

// A straight segment with a radius at each end.
struct Segment {
    DVec3 p0, p1;
    double r0, r1;
};

Segment segment_of(const Cylinder& c) { return {c.p0, c.p1, c.radius, c.radius}; }
Segment segment_of(const Capsule& c) { return {c.p0, c.p1, c.radius, c.radius}; }
Segment segment_of(const Link& k) { return {k.p0, k.p1, k.r0, k.r1}; }

// A unit vector perpendicular to unit `u`: the cross product with the axis
// of u's smallest component (RTXCR's perpStark), so the frame depends only on
// the segment, never on the camera.
DVec3 perpendicular(const DVec3& u) {
    const DVec3 a = glm::abs(u);
    const bool x = a.x < a.y && a.x < a.z;
    const bool y = !x && a.y < a.z;
    return glm::normalize(glm::cross(u, DVec3(x ? 1.0 : 0.0, y ? 1.0 : 0.0, x || y ? 0.0 : 1.0)));
}

// The 4 triangles of one segment, written to out[0..3]: quad k spans the
// axis plane of frame vector k.
void crossed_quads(const Segment& s, Triangle* out) {
    const DVec3 axis = s.p1 - s.p0;
    const double length = glm::length(axis);
    // A zero-length segment has no axis: any frame gives quads of zero area,
    // which no ray hits (as the watertight test rejects degenerate triangles).
    const DVec3 u = length > 0.0 ? axis / length : DVec3(0.0, 0.0, 1.0);
    const DVec3 s_axis = perpendicular(u);
    const DVec3 frame[2] = {s_axis, glm::cross(u, s_axis)};
    for (int k = 0; k < 2; ++k) {
        const DVec3 w0 = frame[k] * (s.r0 * kHalfWidthPerRadius), w1 = frame[k] * (s.r1 * kHalfWidthPerRadius);
        const Vec3 a(s.p0 + w0), b(s.p0 - w0), c(s.p1 - w1), d(s.p1 + w1);
        out[2 * k] = {a, b, c};
        out[2 * k + 1] = {a, c, d};
    }
}

struct DotsStructures {
    TwoLevelStructures two_level;
    std::vector<Triangle> strips;  // kTrianglesPerSegment per primitive, in primitive order
};

template <class Prim>
DotsStructures build_dots(const std::vector<Prim>& prims, const Geometry& g, const MethodOptions& o) {
    DotsStructures s;
    s.strips.resize(prims.size() * kTrianglesPerSegment);
    parallel_for(prims.size(), o.triangle_blas.threads,
                 [&](std::size_t i, unsigned) { crossed_quads(segment_of(prims[i]), &s.strips[i * kTrianglesPerSegment]); });
    std::vector<Aabb> boxes(s.strips.size());
    parallel_for(s.strips.size(), o.triangle_blas.threads, [&](std::size_t i, unsigned) { boxes[i] = bounds(s.strips[i]); });
    std::vector<Bvh> blases;
    blases.push_back(build_bvh(boxes, o.triangle_blas));  // as any triangle BLAS: triangles may share leaves
    std::vector<BlasKind> kinds{BlasKind::StandInTriangles};
    std::vector<Instance> instances{make_instance(0, 0, Affine{})};
    add_mesh_blas(g, o, blases, kinds, instances);
    s.two_level = {build_two_level(std::move(blases), instances, o.tlas), std::move(kinds)};
    return s;
}

struct DotsMethod {
    using Structures = DotsStructures;

    static StructureCounts count(const Structures& s) {
        StructureCounts c = count_two_level(s.two_level);
        c.strip_triangles = s.strips.size();
        c.strip_vertices = s.strips.size() / kTrianglesPerSegment * kVerticesPerSegment;
        return c;
    }
    static std::size_t bytes(const Structures& s) {
        return s.two_level.accel.memory_bytes() + s.strips.size() * sizeof(Triangle);
    }

    template <TraversalMode Mode, class Programs>
    static TraceHit trace(const Structures& s, Programs& programs, const Ray& ray) {
        programs.begin();
        const BlasKind* kinds = s.two_level.blas_kind.data();
        const Triangle* strips = s.strips.data();
        trace_two_level<Mode>(s.two_level.accel, ray, programs.sink(), [&](const PrimitiveQuery& q) -> float {
            if (kinds[q.instance.blas] == BlasKind::Triangles) return programs.triangle(q.prim, q.object_ray, q.tmax);
            return programs.proxy_triangle(strips[q.prim], q.prim / kTrianglesPerSegment, q.object_ray, q.tmax);
        });
        return programs.template finish<Mode>(ray);
    }
};

std::string dots_not_applicable(const Geometry& g) {
    if (g.kind != PrimitiveKind::Phantom) return {};
    return "phantom curves are cubic Beziers; dots stands straight segments in for them "
           "(run the scene as capsules, links or cylinders)";
}

}  // namespace

MethodEntry dots_method() {
    MethodEntry e{{"dots",
                   "each segment as two crossed quads (4 triangles) in the RT unit's triangle path: no context "
                   "switch, hits approximate the curve",
                   {}},
                  [](const Geometry& g, const MethodOptions&) -> std::uint64_t { return 1 + (g.triangles.empty() ? 0 : 1); },
                  [](const Geometry& g, const MethodOptions& o) -> std::unique_ptr<BuiltMethod> {
                      if (const std::string why = dots_not_applicable(g); !why.empty())
                          throw std::invalid_argument("dots: " + why);
                      return std::visit(
                          [&](const auto& prims) -> std::unique_ptr<BuiltMethod> {
                              using Prim = typename std::decay_t<decltype(prims)>::value_type;
                              if constexpr (std::is_same_v<Prim, PhantomCurve>) {
                                  throw std::logic_error("dots: phantom curves were rejected above");
                              } else {
                                  return std::make_unique<BuiltMethodOf<DotsMethod>>(build_dots(prims, g, o));
                              }
                          },
                          g.prims);
                  },
                  dots_not_applicable,
                  // Beyond the per-primitive figure every method shares: per
                  // segment 4 triangles (36 B), their boxes (24 B) and about
                  // 40 B of build references and nodes each (estimated from
                  // the sizes, not measured).
                  [](double primitives, double, const MethodOptions&) {
                      return MethodFootprint{1.0, primitives * kTrianglesPerSegment * 100.0};
                  }};
    e.info.approximate = true;
    return e;
}

}  // namespace rtc
