#include "sim/methods/common/cluster_groups.h"

#include "core/parallel.h"
#include "intersectors/frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace rtc {

namespace {

using Sym3 = std::array<std::array<double, 3>, 3>;

struct Axes {
    DVec3 x, y, z;
};

// Eigenvectors of a symmetric 3x3 matrix (cyclic Jacobi rotations), ordered
// by eigenvalue, largest first; equal eigenvalues keep the axis order.
std::array<DVec3, 3> eigenvectors(Sym3 a) {
    double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
        if (!(off > 1e-30 * diag)) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                const double apq = a[p][q];
                if (apq == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                a[p][p] -= t * apq;
                a[q][q] += t * apq;
                a[p][q] = a[q][p] = 0.0;
                const int r = 3 - p - q;
                const double arp = a[r][p], arq = a[r][q];
                a[r][p] = a[p][r] = c * arp - s * arq;
                a[r][q] = a[q][r] = s * arp + c * arq;
                for (auto& row : v) {
                    const double vp = row[p], vq = row[q];
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    std::array<int, 3> order{0, 1, 2};
    std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return a[i][i] > a[j][j]; });
    std::array<DVec3, 3> out;
    for (int k = 0; k < 3; ++k) out[k] = DVec3(v[0][order[k]], v[1][order[k]], v[2][order[k]]);
    return out;
}

// Orientation tensor and point scatter of a set of primitives.
struct Moments {
    Sym3 orientation{};  // sum over primitives of length * d d^T (d: unit chord)
    Sym3 outer{};        // sum of (c - ref)(c - ref)^T over sphere centres c
    DVec3 sum{0.0}, ref{0.0};
    double points = 0.0;

    void add(const Spheres& s) {
        if (points == 0.0) ref = DVec3(s.center[0]);
        for (int i = 0; i < s.count; ++i) {
            const DVec3 c = DVec3(s.center[i]) - ref;
            sum += c;
            points += 1.0;
            for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q) outer[r][q] += c[r] * c[q];
        }
        const DVec3 d = DVec3(s.center[s.count - 1]) - DVec3(s.center[0]);
        const double len = glm::length(d);
        if (len > 0.0)
            for (int r = 0; r < 3; ++r)
                for (int q = 0; q < 3; ++q) orientation[r][q] += d[r] * d[q] / len;
    }
    [[nodiscard]] DVec3 mean() const { return points > 0.0 ? ref + sum / points : ref; }
    [[nodiscard]] Sym3 covariance() const {
        Sym3 c{};
        if (points == 0.0) return c;
        const DVec3 m = sum / points;
        for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) c[r][q] = outer[r][q] / points - m[r] * m[q];
        return c;
    }
};

// Right-handed orthonormal axes: x along `x`, y along the part of `hint`
// across x (any perpendicular when that vanishes).
Axes complete(DVec3 x, const DVec3& hint) {
    const double lx = glm::length(x);
    x = lx > 0.0 && std::isfinite(lx) ? x / lx : DVec3(1, 0, 0);
    DVec3 y = hint - glm::dot(hint, x) * x;
    if (!(glm::length(y) > 1e-6)) {
        const DVec3 a = std::abs(x.x) < 0.9 ? DVec3(1, 0, 0) : DVec3(0, 1, 0);
        y = a - glm::dot(a, x) * x;
    }
    y = glm::normalize(y);
    return {x, y, glm::cross(x, y)};
}

// The principal axis of the points across the unit axis x.
DVec3 across(const Moments& m, const DVec3& x) {
    const Sym3 c = m.covariance();
    Sym3 p{}, pc{}, pcp{};
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) p[r][q] = (r == q ? 1.0 : 0.0) - x[r] * x[q];
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
            for (int s = 0; s < 3; ++s) pc[r][q] += p[r][s] * c[s][q];
    for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
            for (int s = 0; s < 3; ++s) pcp[r][q] += pc[r][s] * p[s][q];
    return eigenvectors(pcp)[0];
}

Axes principal_axes(const Moments& m) {
    const DVec3 x = glm::normalize(eigenvectors(m.orientation)[0]);
    return complete(x, across(m, x));
}

struct DBox {
    DVec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
    void extend(const DBox& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    [[nodiscard]] double area() const {
        const DVec3 e = hi - lo;
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

template <class Prim>
DBox box_in(const Prim& prim, const Axes& a, const DVec3& origin) {
    const Spheres s = spheres(prim);
    DBox b;
    for (int i = 0; i < s.count; ++i) {
        const DVec3 v = DVec3(s.center[i]) - origin;
        const DVec3 q(glm::dot(v, a.x), glm::dot(v, a.y), glm::dot(v, a.z));
        b.lo = glm::min(b.lo, q - double(s.radius[i]));
        b.hi = glm::max(b.hi, q + double(s.radius[i]));
    }
    return b;
}

template <class Prim>
Moments moments(std::span<const Prim> prims, std::span<const std::uint32_t> ids) {
    Moments m;
    for (const std::uint32_t id : ids) m.add(spheres(prims[id]));
    return m;
}

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

// Primitives x area of the group's box in its own principal frame.
template <class Prim>
double group_cost(std::span<const Prim> prims, std::span<const std::uint32_t> ids) {
    const Moments m = moments(prims, ids);
    const Axes a = principal_axes(m);
    DBox all;
    for (const std::uint32_t id : ids) all.extend(box_in(prims[id], a, m.mean()));
    return static_cast<double>(ids.size()) * all.area();
}

DVec3 centroid(const Spheres& s) {
    DVec3 c(0.0);
    for (int i = 0; i < s.count; ++i) c += DVec3(s.center[i]);
    return c / double(s.count);
}

DVec3 unit_chord(const Spheres& s) {
    const DVec3 d = DVec3(s.center[s.count - 1]) - DVec3(s.center[0]);
    const double len = glm::length(d);
    return len > 0.0 ? d / len : DVec3(0.0);
}

// Splits `ids` (more than k primitives) in place at a multiple of k; returns
// the size of the first part.
template <class Prim>
std::size_t split(std::span<const Prim> prims, std::span<std::uint32_t> ids, std::size_t k) {
    const std::size_t n = ids.size(), groups = (n + k - 1) / k;
    const Moments m = moments(prims, std::span<const std::uint32_t>(ids));
    std::vector<std::pair<float, std::uint32_t>> keys(n);
    const auto partition = [&](std::size_t left, std::vector<std::uint32_t>& out) {
        std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(left), keys.end());
        out.resize(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = keys[i].second;
        const std::span<const std::uint32_t> o(out);
        return group_cost(prims, o.first(left)) + group_cost(prims, o.subspan(left));
    };
    // Spatial: object median (rounded to whole clusters) along the points' principal axis.
    const DVec3 along = eigenvectors(m.covariance())[0];
    for (std::size_t i = 0; i < n; ++i)
        keys[i] = {static_cast<float>(glm::dot(centroid(spheres(prims[ids[i]])) - m.ref, along)), ids[i]};
    const std::size_t spatial_left = groups / 2 * k;
    std::vector<std::uint32_t> spatial, oriented;
    const double spatial_cost = partition(spatial_left, spatial);
    // Orientation (Embree's strand split): the dominant direction a0 against
    // the direction least aligned with it, a1; each primitive to the closer.
    const DVec3 a0 = eigenvectors(m.orientation)[0];
    DVec3 a1 = a0;
    double least = 2.0;
    for (const std::uint32_t id : ids) {
        const DVec3 d = unit_chord(spheres(prims[id]));
        const double along0 = std::abs(glm::dot(d, a0));
        if (glm::length(d) > 0.0 && along0 < least) least = along0, a1 = d;
    }
    std::size_t closer_to_a0 = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const DVec3 d = unit_chord(spheres(prims[ids[i]]));
        const float key = static_cast<float>(std::abs(glm::dot(d, a1)) - std::abs(glm::dot(d, a0)));
        keys[i] = {key, ids[i]};
        closer_to_a0 += key < 0.0f;
    }
    const std::size_t oriented_left = std::clamp((closer_to_a0 + k / 2) / k * k, k, (groups - 1) * k);
    const double oriented_cost = partition(oriented_left, oriented);
    const bool orient = oriented_cost < spatial_cost;
    std::copy((orient ? oriented : spatial).begin(), (orient ? oriented : spatial).end(), ids.begin());
    return orient ? oriented_left : spatial_left;
}

}  // namespace

namespace {

// Calls run(first, count) for every strand run of at most k primitives.
template <class Run>
void for_each_run(std::size_t primitives, std::span<const std::uint32_t> strand_first, std::size_t k, Run&& run) {
    const std::size_t strands = strand_first.empty() ? 1 : strand_first.size();
    for (std::size_t s = 0; s < strands; ++s) {
        const std::size_t b = strand_first.empty() ? 0 : strand_first[s];
        const std::size_t e = s + 1 < strands ? strand_first[s + 1] : primitives;
        for (std::size_t r = b; r < e; r += k) run(r, std::min(k, e - r));
    }
}

}  // namespace

std::uint64_t strand_cluster_count(std::size_t primitives, std::span<const std::uint32_t> strand_first, int size) {
    std::uint64_t n = 0;
    for_each_run(primitives, strand_first, static_cast<std::size_t>(std::max(size, 1)),
                 [&](std::size_t, std::size_t) { ++n; });
    return n;
}

Clusters group_strand(std::size_t primitives, std::span<const std::uint32_t> strand_first, int size) {
    Clusters c;
    c.members.resize(primitives);
    std::iota(c.members.begin(), c.members.end(), 0u);
    for_each_run(primitives, strand_first, static_cast<std::size_t>(std::max(size, 1)),
                 [&](std::size_t first, std::size_t) { c.first.push_back(static_cast<std::uint32_t>(first)); });
    c.first.push_back(static_cast<std::uint32_t>(primitives));
    return c;
}

template <class Prim>
Clusters group_orientation(std::span<const Prim> prims, int size, unsigned threads) {
    const std::size_t n = prims.size(), k = static_cast<std::size_t>(std::max(size, 1));
    if (k == 1 || n <= k) return group_strand(n, {}, size);
    Clusters c;
    c.members.resize(n);
    std::iota(c.members.begin(), c.members.end(), 0u);
    // Level by level: the groups of one level are split in parallel, each in
    // its own slice of `members`, so the result does not depend on threads.
    std::vector<std::pair<std::size_t, std::size_t>> level{{0, n}};
    std::vector<std::uint32_t> starts;
    while (!level.empty()) {
        std::vector<std::size_t> left(level.size(), 0);
        parallel_for(level.size(), threads, [&](std::size_t i, unsigned) {
            const auto [b, e] = level[i];
            if (e - b > k) left[i] = split(prims, std::span(c.members).subspan(b, e - b), k);
        }, 1);
        std::vector<std::pair<std::size_t, std::size_t>> next;
        for (std::size_t i = 0; i < level.size(); ++i) {
            const auto [b, e] = level[i];
            if (left[i] == 0) {
                starts.push_back(static_cast<std::uint32_t>(b));
            } else {
                next.emplace_back(b, b + left[i]);
                next.emplace_back(b + left[i], e);
            }
        }
        level = std::move(next);
    }
    std::sort(starts.begin(), starts.end());
    c.first = std::move(starts);
    c.first.push_back(static_cast<std::uint32_t>(n));
    for (std::size_t g = 0; g + 1 < c.first.size(); ++g)
        std::sort(c.members.begin() + c.first[g], c.members.begin() + c.first[g + 1]);
    return c;
}

template <class Prim>
FramedCluster frame_cluster(std::span<const Prim> prims, std::span<const std::uint32_t> members,
                            ClusterFrame choice) {
    const Moments m = moments(prims, members);
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

#define RTCSIM_CLUSTER_KIND(P)                                                                  \
    template Clusters group_orientation<P>(std::span<const P>, int, unsigned);                  \
    template FramedCluster frame_cluster<P>(std::span<const P>, std::span<const std::uint32_t>, \
                                            ClusterFrame);
RTCSIM_CLUSTER_KIND(Cylinder)
RTCSIM_CLUSTER_KIND(Capsule)
RTCSIM_CLUSTER_KIND(Link)
RTCSIM_CLUSTER_KIND(PhantomCurve)
#undef RTCSIM_CLUSTER_KIND

}  // namespace rtc
