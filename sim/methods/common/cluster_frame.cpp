// A cluster's BLAS frame and its members' boxes in it (cluster_groups.h).
#include "sim/methods/common/cluster_groups.h"
#include "sim/methods/common/cluster_moments.h"

#include "intersectors/frame.h"

#include <algorithm>
#include <cmath>

namespace rtc {

namespace {

using namespace cluster_detail;

// What a ray pays for a cluster in frame `a`, in context switches: the
// members' boxes (each one a ray pierces is a context switch and a program)
// plus a fifth of the world AABB of the cluster's box (each one a ray
// pierces is an instance transform and a BLAS root visit, about a fifth of a
// context switch and its program under configs/hw/turing-calibrated.json:
// 64 + 2 + 4 against 224 + 150 cycles). Surface areas stand for the odds.
inline constexpr double kEnterWeight = 0.2;

double world_area(const DBox& b, const Axes& a) {
    const DVec3 h = 0.5 * (b.hi - b.lo);
    const DVec3 w = glm::abs(a.x) * h.x + glm::abs(a.y) * h.y + glm::abs(a.z) * h.z;
    return 8.0 * (w.x * w.y + w.y * w.z + w.z * w.x);
}

template <class Prim>
double frame_cost(std::span<const Prim> prims, std::span<const std::uint32_t> ids, const Axes& a,
                  const DVec3& origin) {
    DBox all;
    double sum = 0.0;
    for (const std::uint32_t id : ids) {
        const DBox b = box_in(prims[id], a, origin);
        sum += b.area();
        all.extend(b);
    }
    return sum + kEnterWeight * world_area(all, a);
}

}  // namespace

template <class Prim>
FramedCluster frame_cluster(std::span<const Prim> prims, std::span<const std::uint32_t> members,
                            ClusterFrame choice) {
    Moments m;
    for (const std::uint32_t id : members) m.add(spheres(prims[id]));
    const DVec3 origin = m.mean();
    Axes best = principal_axes(m);
    if (choice == ClusterFrame::Best && !members.empty()) {
        const auto points = eigenvectors(m.covariance());
        const Spheres first = spheres(prims[members.front()]), last = spheres(prims[members.back()]);
        const DVec3 chord = DVec3(last.center[last.count - 1]) - DVec3(first.center[0]);
        const Axes candidates[] = {complete(points[0], points[1]),
                                   {DVec3(1, 0, 0), DVec3(0, 1, 0), DVec3(0, 0, 1)},
                                   complete(chord, across(m, glm::length(chord) > 0.0 ? glm::normalize(chord)
                                                                                      : DVec3(1, 0, 0)))};
        double best_cost = frame_cost(prims, members, best, origin);
        for (const Axes& a : candidates) {
            const double cost = frame_cost(prims, members, a, origin);
            if (cost < best_cost) best_cost = cost, best = a;
        }
    }
    // Box the members in the frame the instance stores (rounded to float).
    const Vec3 fx(best.x), fy(best.y), fz(best.z), fo(origin);
    const Axes stored{DVec3(fx), DVec3(fy), DVec3(fz)};
    FramedCluster out{Affine::from_columns(fx, fy, fz, fo), {}};
    out.boxes.reserve(members.size());
    for (const std::uint32_t id : members) {
        const DBox b = box_in(prims[id], stored, DVec3(fo));
        // The hardware's error bound (frame.h, kObbSlack): the member's
        // points lie within sqrt(3) * scale of the frame's origin.
        const double scale = std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z),
                                       std::abs(b.hi.x), std::abs(b.hi.y), std::abs(b.hi.z)});
        const DVec3 pad = 0.5 * (b.hi - b.lo) * double(kObbPad) + DVec3(kObbSlack * std::sqrt(3.0) * scale);
        out.boxes.push_back(outward_bounds(b.lo - pad, b.hi + pad));
    }
    return out;
}

#define RTCSIM_CLUSTER_KIND(P)                                                                     \
    template FramedCluster frame_cluster<P>(std::span<const P>, std::span<const std::uint32_t>, \
                                            ClusterFrame);
RTCSIM_CLUSTER_KIND(Cylinder)
RTCSIM_CLUSTER_KIND(Capsule)
RTCSIM_CLUSTER_KIND(Link)
RTCSIM_CLUSTER_KIND(PhantomCurve)
#undef RTCSIM_CLUSTER_KIND

}  // namespace rtc
