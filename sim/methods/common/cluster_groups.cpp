// The grouping of primitives into clusters (cluster_groups.h); the frames are
// in cluster_frame.cpp, the moments they share in cluster_moments.h.
#include "sim/methods/common/cluster_groups.h"
#include "sim/methods/common/cluster_moments.h"

#include "core/parallel.h"
#include "core/uninitialized.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace rtc {

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

namespace {

using namespace cluster_detail;

// A primitive with its index, as the grouping carries it: every group's
// members lie in order in one slice of a buffer, so each pass over a group
// reads memory in order (with indices into the scene instead, each pass over
// the 20 M fur's top groups was a random read per primitive).
template <class Prim>
struct Member {
    Prim prim;
    std::uint32_t id;
};

// A member's key in one candidate split, with its place in the group's slice.
struct Key {
    float key;
    std::uint32_t id;
    std::uint32_t at;
};
// The order of std::pair<float, std::uint32_t> (ties in the key to the
// smaller index), with which the grouping has always selected: the same
// comparisons make std::nth_element move the keys the same way.
bool key_less(const Key& a, const Key& b) { return a.key < b.key || (!(b.key < a.key) && a.id < b.id); }

// Groups smaller than this are never shared between threads.
constexpr std::size_t kParallelGroup = 65536;
constexpr std::size_t kChunk = 16384;

// The orientation grouping (cluster_groups.h): each group of more than k
// members is split into two by whichever of two candidate cuts costs less.
// The members of a group live in one of three buffers; each candidate writes
// its order into one of the other two, and the winner's buffer holds both
// halves for the next level, so nothing is copied back.
template <class Prim>
class OrientationGrouper {
public:
    OrientationGrouper(std::span<const Prim> prims, std::size_t k, unsigned threads)
        : k_(k), threads_(std::max(threads, 1u)) {
        const std::size_t n = prims.size();
        for (auto& b : buffer_) b.resize(n);
        for (auto& keys : keys_) keys.resize(n);
        for (std::size_t i = 0; i < n; ++i) buffer_[0][i] = {prims[i], static_cast<std::uint32_t>(i)};
    }

    Clusters run() {
        const std::size_t n = buffer_[0].size();
        Clusters c;
        c.members.resize(n);
        Moments root;
        for (std::size_t i = 0; i < n; ++i) root.add(spheres(buffer_[0][i].prim));
        // Level by level: the groups of one level are split in parallel, each
        // in its own slice of the buffers, so the result does not depend on
        // threads; a level of fewer groups than threads shares them out
        // inside each group.
        std::vector<Group> level{{0, n, 0, root}};
        std::vector<std::uint32_t> starts;
        while (!level.empty()) {
            std::vector<Halves> halves(level.size());
            const unsigned inner = std::max(1u, threads_ / static_cast<unsigned>(level.size()));
            parallel_for(level.size(), threads_, [&](std::size_t i, unsigned) {
                if (level[i].end - level[i].begin > k_) halves[i] = split(level[i], inner);
            }, 1);
            std::vector<Group> next;
            for (std::size_t i = 0; i < level.size(); ++i) {
                const Group& g = level[i];
                if (halves[i].left == 0) {
                    starts.push_back(static_cast<std::uint32_t>(g.begin));
                    for (std::size_t j = g.begin; j < g.end; ++j) c.members[j] = buffer_[g.buffer][j].id;
                } else {
                    const std::size_t mid = g.begin + halves[i].left;
                    next.push_back({g.begin, mid, halves[i].buffer, halves[i].moments[0]});
                    next.push_back({mid, g.end, halves[i].buffer, halves[i].moments[1]});
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

private:
    struct Group {
        std::size_t begin, end;
        int buffer;
        Moments moments;  // of the members in their order in the buffer
    };
    struct Halves {
        std::size_t left = 0;  // members in the first half; 0: not split
        int buffer = 0;        // holding both halves in order
        std::array<Moments, 2> moments;
    };

    // Splits a group of more than k members at a multiple of k: either
    // spatially (object median, rounded to whole clusters, along the points'
    // principal axis) or by orientation (Embree's strand split: the dominant
    // direction a0 against the direction least aligned with it, a1; each
    // primitive to the closer), whichever gives the smaller sum over both
    // halves of (members x area of the half's box in its own principal frame).
    Halves split(const Group& g, unsigned threads) {
        const std::size_t n = g.end - g.begin, groups = (n + k_ - 1) / k_;
        const Member<Prim>* src = buffer_[g.buffer].data() + g.begin;
        Key* spatial = keys_[0].data() + g.begin;
        Key* oriented = keys_[1].data() + g.begin;
        const Moments& m = g.moments;
        const D4 ref = lanes(m.ref);
        const DVec3 along = eigenvectors(m.covariance())[0];
        const DVec3 a0 = eigenvectors(m.orientation())[0];
        // The spatial keys, and in each chunk the first chord least aligned with a0.
        const std::size_t chunks = threads > 1 && n >= kParallelGroup ? n / kChunk : 1;
        const auto chunk = [&](std::size_t c) {
            return std::pair{c * n / chunks, (c + 1) * n / chunks};
        };
        std::vector<std::pair<double, DVec3>> least(chunks, {2.0, a0});
        parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
            const auto [b, e] = chunk(c);
            auto& [low, a1] = least[c];
            for (std::size_t i = b; i < e; ++i) {
                const Spheres s = spheres(src[i].prim);
                spatial[i] = {static_cast<float>(dot(centroid_lanes(s) - ref, along)), src[i].id,
                              static_cast<std::uint32_t>(i)};
                // unit_chord(s) and its glm::length(d) > 0.0, which is len > 0.
                double len = 0.0;
                const D4 d = unit_chord_lanes(s, len);
                const double along0 = std::abs(dot(d, a0));
                if (len > 0.0 && along0 < low) low = along0, a1 = dvec3(d);
            }
        }, 1);
        std::pair<double, DVec3> first_least = least[0];
        for (std::size_t c = 1; c < chunks; ++c)
            if (least[c].first < first_least.first) first_least = least[c];
        const DVec3 a1 = first_least.second;
        std::vector<std::size_t> closer(chunks, 0);
        parallel_for(chunks, threads, [&](std::size_t c, unsigned) {
            const auto [b, e] = chunk(c);
            for (std::size_t i = b; i < e; ++i) {
                double len = 0.0;
                const D4 d = unit_chord_lanes(spheres(src[i].prim), len);
                const float key = static_cast<float>(std::abs(dot(d, a1)) - std::abs(dot(d, a0)));
                oriented[i] = {key, src[i].id, static_cast<std::uint32_t>(i)};
                closer[c] += key < 0.0f;
            }
        }, 1);
        const std::size_t closer_to_a0 = std::accumulate(closer.begin(), closer.end(), std::size_t{0});
        const std::size_t lefts[2] = {groups / 2 * k_,
                                      std::clamp((closer_to_a0 + k_ / 2) / k_ * k_, k_, (groups - 1) * k_)};
        // Both candidates, side by side when the threads are there.
        std::array<Halves, 2> candidate;
        std::array<double, 2> cost{};
        parallel_for(2, threads, [&](std::size_t which, unsigned) {
            Halves& h = candidate[which];
            h.left = lefts[which];
            h.buffer = (g.buffer + 1 + static_cast<int>(which)) % 3;
            cost[which] = select(which == 0 ? spatial : oriented, n, h, src, buffer_[h.buffer].data() + g.begin);
        }, 1);
        return cost[1] < cost[0] ? candidate[1] : candidate[0];
    }

    // Selects h.left members by key into `out` (in nth_element's order),
    // sums each half's moments in that order and returns the candidate's
    // cost: members x area of each half's box in its principal frame.
    static double select(Key* keys, std::size_t n, Halves& h, const Member<Prim>* src, Member<Prim>* out) {
        std::nth_element(keys, keys + h.left, keys + n, key_less);
        for (std::size_t i = 0; i < n; ++i) out[i] = src[keys[i].at];
        double cost = 0.0;
        for (int half = 0; half < 2; ++half) {
            const std::size_t b = half == 0 ? 0 : h.left, e = half == 0 ? h.left : n;
            Moments& m = h.moments[half];
            for (std::size_t i = b; i < e; ++i) m.add(spheres(out[i].prim));
            const AxesLanes a(principal_axes(m));
            const D4 origin = lanes(m.mean());
            DBoxLanes all;
            for (std::size_t i = b; i < e; ++i) all.extend_in(out[i].prim, a, origin);
            cost += static_cast<double>(e - b) * all.box().area();
        }
        return cost;
    }

    std::size_t k_;
    unsigned threads_;
    std::array<UninitializedVector<Member<Prim>>, 3> buffer_;
    std::array<UninitializedVector<Key>, 2> keys_;  // the spatial and the oriented candidates'
};

}  // namespace

template <class Prim>
Clusters group_orientation(std::span<const Prim> prims, int size, unsigned threads) {
    const std::size_t n = prims.size(), k = static_cast<std::size_t>(std::max(size, 1));
    if (k == 1 || n <= k) return group_strand(n, {}, size);
    return OrientationGrouper<Prim>(prims, k, threads).run();
}

#define RTCSIM_CLUSTER_KIND(P) template Clusters group_orientation<P>(std::span<const P>, int, unsigned);
RTCSIM_CLUSTER_KIND(Cylinder)
RTCSIM_CLUSTER_KIND(Capsule)
RTCSIM_CLUSTER_KIND(Link)
RTCSIM_CLUSTER_KIND(PhantomCurve)
#undef RTCSIM_CLUSTER_KIND

}  // namespace rtc
