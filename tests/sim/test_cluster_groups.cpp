// The orientation grouping (sim/methods/common/cluster_groups.cpp) against
// its slow reference: the plain algorithm as first written (primitive
// indices, std::pair keys, every moment summed in full), which the fast one
// must reproduce member for member, at any thread count. The fast one carries
// the primitives in buffers, sums half the moments in lanes and splits big
// groups on several threads; none of that may change a single cluster.
#include "sim/methods_test_util.h"
#include "sim/methods/common/cluster_groups.h"
#include "sim/methods/common/cluster_moments.h"
#include "scenes/convert.h"
#include "scenes/generators/hair_gen.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
using namespace rtc::test;
using rtc::cluster_detail::Axes;
using rtc::cluster_detail::complete;
using rtc::cluster_detail::eigenvectors;
using rtc::cluster_detail::Sym3;

namespace {

struct RefMoments {
    Sym3 orientation{}, outer{};
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
    DVec3 mean() const { return points > 0.0 ? ref + sum / points : ref; }
    Sym3 covariance() const {
        Sym3 c{};
        if (points == 0.0) return c;
        const DVec3 m = sum / points;
        for (int r = 0; r < 3; ++r)
            for (int q = 0; q < 3; ++q) c[r][q] = outer[r][q] / points - m[r] * m[q];
        return c;
    }
};

Axes ref_principal_axes(const RefMoments& m) {
    const DVec3 x = glm::normalize(eigenvectors(m.orientation)[0]);
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
    return complete(x, eigenvectors(pcp)[0]);
}

template <class Prim>
RefMoments ref_moments(std::span<const Prim> prims, std::span<const std::uint32_t> ids) {
    RefMoments m;
    for (const std::uint32_t id : ids) m.add(spheres(prims[id]));
    return m;
}

template <class Prim>
double ref_group_cost(std::span<const Prim> prims, std::span<const std::uint32_t> ids) {
    const RefMoments m = ref_moments(prims, ids);
    const Axes a = ref_principal_axes(m);
    cluster_detail::DBox all;
    for (const std::uint32_t id : ids) all.extend(cluster_detail::box_in(prims[id], a, m.mean()));
    return static_cast<double>(ids.size()) * all.area();
}

template <class Prim>
std::size_t ref_split(std::span<const Prim> prims, std::span<std::uint32_t> ids, std::size_t k) {
    const std::size_t n = ids.size(), groups = (n + k - 1) / k;
    const RefMoments m = ref_moments(prims, std::span<const std::uint32_t>(ids));
    std::vector<std::pair<float, std::uint32_t>> keys(n);
    const auto partition = [&](std::size_t left, std::vector<std::uint32_t>& out) {
        std::nth_element(keys.begin(), keys.begin() + static_cast<std::ptrdiff_t>(left), keys.end());
        out.resize(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = keys[i].second;
        const std::span<const std::uint32_t> o(out);
        return ref_group_cost(prims, o.first(left)) + ref_group_cost(prims, o.subspan(left));
    };
    const DVec3 along = eigenvectors(m.covariance())[0];
    for (std::size_t i = 0; i < n; ++i)
        keys[i] = {static_cast<float>(glm::dot(cluster_detail::centroid(spheres(prims[ids[i]])) - m.ref, along)),
                   ids[i]};
    const std::size_t spatial_left = groups / 2 * k;
    std::vector<std::uint32_t> spatial, oriented;
    const double spatial_cost = partition(spatial_left, spatial);
    const DVec3 a0 = eigenvectors(m.orientation)[0];
    DVec3 a1 = a0;
    double least = 2.0;
    for (const std::uint32_t id : ids) {
        const DVec3 d = cluster_detail::unit_chord(spheres(prims[id]));
        const double along0 = std::abs(glm::dot(d, a0));
        if (glm::length(d) > 0.0 && along0 < least) least = along0, a1 = d;
    }
    std::size_t closer_to_a0 = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const DVec3 d = cluster_detail::unit_chord(spheres(prims[ids[i]]));
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

template <class Prim>
Clusters ref_group_orientation(std::span<const Prim> prims, std::size_t k) {
    const std::size_t n = prims.size();
    Clusters c;
    c.members.resize(n);
    std::iota(c.members.begin(), c.members.end(), 0u);
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, n}};
    while (!stack.empty()) {
        const auto [b, e] = stack.back();
        stack.pop_back();
        if (e - b <= k) {
            c.first.push_back(static_cast<std::uint32_t>(b));
            continue;
        }
        const std::size_t left = ref_split(prims, std::span(c.members).subspan(b, e - b), k);
        stack.emplace_back(b, b + left);
        stack.emplace_back(b + left, e);
    }
    std::sort(c.first.begin(), c.first.end());
    c.first.push_back(static_cast<std::uint32_t>(n));
    for (std::size_t g = 0; g + 1 < c.first.size(); ++g)
        std::sort(c.members.begin() + c.first[g], c.members.begin() + c.first[g + 1]);
    return c;
}

template <class Prim>
void check_same_groups(const std::vector<Prim>& prims, std::initializer_list<int> sizes) {
    const std::span<const Prim> p(prims);
    for (const int k : sizes) {
        CAPTURE(k);
        const Clusters want = ref_group_orientation(p, static_cast<std::size_t>(k));
        for (const unsigned threads : {1u, 2u, 3u}) {
            CAPTURE(threads);
            const Clusters got = group_orientation(p, k, threads);
            CHECK(got.first == want.first);
            CHECK(got.members == want.members);
        }
    }
}

}  // namespace

TEST_CASE("cluster groups: the orientation grouping is its reference's, for every kind and thread count") {
    for (const PrimitiveKind kind : kKinds) {
        CAPTURE(kind_name(kind));
        Rng rng(4100 + static_cast<int>(kind));
        std::visit([&](const auto& prims) { check_same_groups(prims, {2, 3, 7, 16, 64}); },
                   random_prims(rng, kind, 1500));
    }
}

TEST_CASE("cluster groups: the fur's grouping is its reference's, including groups split on two threads") {
    // The fur of configs/runs/cluster_fur20m.json at 150,000 segments: its
    // top groups are big enough (kParallelGroup) to be split in chunks.
    HairDesc d;
    d.strands = 37500;
    d.points_per_strand = 5;
    d.length = 0.15f;
    d.radius = 0.0008f;
    d.tip_radius = 0.0002f;
    d.seed = 3;
    const auto caps = std::get<std::vector<Capsule>>(to_primitives(make_hair(d).strands, PrimitiveKind::Capsule));
    REQUIRE(caps.size() == 150000);
    check_same_groups(caps, {256});
}

}  // namespace RTCSIM_TEST_FILE
