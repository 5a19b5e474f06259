// The oriented-node BVH builder (Woop et al. 2014, after Embree's
// bvh_builder_hair.h); see core/obb_build.h for what it chooses and why.
#include "core/obb_build.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace rtc {

ObbFrame frame_from_axis(const DVec3& axis, const DVec3& origin) {
    ObbFrame f;
    f.origin = origin;
    const double len = glm::length(axis);
    if (!(len > 0.0) || !std::isfinite(len)) return f;
    const DVec3 n = axis / len;
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    const DVec3 x(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const DVec3 y(b, sign + n.y * n.y * a, -n.y);
    // glm is column-major: the rows of rot are the columns of its transpose.
    f.rot = glm::transpose(glm::dmat3(x, y, n));
    return f;
}

void LocalBounds::add(const ObbFrame& f, const BoundProxy& p) {
    const double r = std::max(static_cast<double>(p.radius), 0.0);
    for (const Vec3& q : p.points) {
        const DVec3 l = f.local(DVec3(q));
        lo = glm::min(lo, l - r);
        hi = glm::max(hi, l + r);
    }
}

double LocalBounds::half_area() const {
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return 0.0;
    const DVec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

Aabb LocalBounds::padded() const {
    Aabb b;
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return b;
    constexpr double kUlps = 16.0 * std::numeric_limits<float>::epsilon();
    for (int i = 0; i < 3; ++i) {
        const double m = std::max({std::abs(lo[i]), std::abs(hi[i]), hi[i] - lo[i]});
        const double pad = m * kUlps + std::numeric_limits<float>::min();
        float l = static_cast<float>(lo[i] - pad), h = static_cast<float>(hi[i] + pad);
        if (static_cast<double>(l) > lo[i] - pad) l = float_step_down(l);
        if (static_cast<double>(h) < hi[i] + pad) h = float_step_up(h);
        b.lo[i] = l;
        b.hi[i] = h;
    }
    return b;
}

std::size_t ObbFrames::rotated_entries() const {
    return static_cast<std::size_t>(
        std::count_if(frame_of.begin(), frame_of.end(), [](std::uint32_t f) { return f != kWorldFrame; }));
}

namespace {

double half_area(const Aabb& b) {
    if (b.empty()) return 0.0;
    const DVec3 e(b.extent());
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Best binned object split (Wald 2007) of items given by their boxes; the
// split sends bins [0, bin] left. cost = sum over sides of half area x count.
struct ObjectSplit {
    double cost = std::numeric_limits<double>::infinity();
    int axis = -1, bin = 0;
    double cmin = 0.0, scale = 0.0;
    [[nodiscard]] bool left(const Aabb& b) const {
        const double c = 0.5 * (double(b.lo[axis]) + double(b.hi[axis]));
        return std::min(int((c - cmin) * scale), 1 << 20) <= bin;
    }
};

ObjectSplit binned_sah(const std::vector<Aabb>& boxes, int bins) {
    constexpr int kMaxBins = 64;
    bins = std::clamp(bins, 2, kMaxBins);
    DVec3 cmin(std::numeric_limits<double>::infinity()), cmax(-std::numeric_limits<double>::infinity());
    for (const Aabb& b : boxes) {
        const DVec3 c = 0.5 * (DVec3(b.lo) + DVec3(b.hi));
        cmin = glm::min(cmin, c);
        cmax = glm::max(cmax, c);
    }
    ObjectSplit best;
    for (int axis = 0; axis < 3; ++axis) {
        const double extent = cmax[axis] - cmin[axis];
        if (!(extent > 0.0)) continue;
        const double scale = bins * (1.0 - 1e-9) / extent;
        Aabb bin_box[kMaxBins];
        std::uint32_t bin_n[kMaxBins] = {};
        ObjectSplit s;
        s.axis = axis, s.cmin = cmin[axis], s.scale = scale;
        for (const Aabb& b : boxes) {
            const double c = 0.5 * (double(b.lo[axis]) + double(b.hi[axis]));
            const int k = std::clamp(int((c - s.cmin) * scale), 0, bins - 1);
            bin_box[k].extend(b);
            ++bin_n[k];
        }
        double right_cost[kMaxBins];
        Aabb acc;
        std::uint32_t n = 0;
        for (int k = bins - 1; k > 0; --k) {
            acc.extend(bin_box[k]);
            n += bin_n[k];
            right_cost[k] = n ? half_area(acc) * n : -1.0;
        }
        acc = {};
        n = 0;
        for (int k = 0; k + 1 < bins; ++k) {
            acc.extend(bin_box[k]);
            n += bin_n[k];
            if (n == 0 || right_cost[k + 1] < 0.0) continue;
            const double cost = half_area(acc) * n + right_cost[k + 1];
            if (cost < best.cost) {
                best = s;
                best.bin = k;
                best.cost = cost;
            }
        }
    }
    return best;
}

class Builder {
public:
    Builder(std::span<const Aabb> boxes, std::span<const BoundProxy> proxies, const ObbBuildOptions& o)
        : boxes_(boxes), proxies_(proxies), o_(o), ids_(boxes.size()) {
        std::iota(ids_.begin(), ids_.end(), 0u);
    }

    ObbBvh run() {
        out_.bvh.width = o_.width;
        out_.frames.style = ObbStyle::PerChild;
        const Range all = make_range(0, static_cast<std::uint32_t>(ids_.size()));
        out_.bvh.root.box = all.world;
        out_.bvh.root.first = 0;
        out_.bvh.root.count = BvhEntry::kInnerBit;
        if (!ids_.empty()) {
            const Built b = build_node(all, 0);
            out_.bvh.root.first = b.first;
            out_.bvh.root.count = BvhEntry::kInnerBit | b.count;
        }
        out_.bvh.prim_ids.assign(ids_.begin(), ids_.end());
        return std::move(out_);
    }

private:
    struct Range {
        std::uint32_t begin = 0, end = 0;
        Aabb world;
        [[nodiscard]] std::uint32_t size() const { return end - begin; }
    };
    enum class Kind { Aligned, Oriented, Strand, Median };
    struct Split {
        Kind kind = Kind::Median;
        double cost = std::numeric_limits<double>::infinity();
        ObjectSplit object;
        ObbFrame frame;
        DVec3 axis0{0.0}, axis1{0.0};
    };

    Range make_range(std::uint32_t b, std::uint32_t e) const {
        Range r{b, e, {}};
        for (std::uint32_t i = b; i < e; ++i) r.world.extend(boxes_[ids_[i]]);
        return r;
    }

    DVec3 unit_axis(std::uint32_t id) const {
        const DVec3 a(proxies_[id].axis());
        const double l = glm::length(a);
        return l > 0.0 && std::isfinite(l) ? a / l : DVec3(0.0);
    }

    // Embree's computeAlignedSpace: the direction of the first primitive with one.
    ObbFrame aligned_space(const Range& r) const {
        DVec3 axis(0.0);
        for (std::uint32_t i = r.begin; i < r.end && axis == DVec3(0.0); ++i) axis = unit_axis(ids_[i]);
        return frame_from_axis(axis, DVec3(r.world.center()));
    }

    // A child's frame: the mean direction of its primitives (each turned to
    // agree with the first, weighted by length), steadier than Embree's first
    // primitive's direction for a mixed group.
    ObbFrame mean_space(const Range& r) const {
        DVec3 sum(0.0);
        for (std::uint32_t i = r.begin; i < r.end; ++i) {
            const DVec3 a(proxies_[ids_[i]].axis());
            sum += glm::dot(a, sum) < 0.0 ? -a : a;
        }
        return frame_from_axis(sum, DVec3(r.world.center()));
    }

    Aabb local_box(const ObbFrame& f, std::uint32_t id) const {
        LocalBounds b;
        b.add(f, proxies_[id]);
        return {Vec3(b.lo), Vec3(b.hi)};
    }

    Split find_split(const Range& r, int depth) const {
        Split best;
        if (depth > 48) return best;  // a degenerate input: bound the depth (traversal stack)
        const double area = half_area(r.world);
        const double leaf = o_.intersection * r.size() * area;
        std::vector<Aabb> local(r.size());
        for (std::uint32_t i = r.begin; i < r.end; ++i) local[i - r.begin] = boxes_[ids_[i]];
        if (const ObjectSplit s = binned_sah(local, o_.bins); s.axis >= 0) {
            best.kind = Kind::Aligned;
            best.object = s;
            best.cost = o_.traversal_aligned * area + o_.intersection * s.cost;
        }
        if (!(best.cost > o_.try_oriented * leaf)) return best;
        // (b) object split in the frame of the first primitive's direction.
        const ObbFrame f = aligned_space(r);
        for (std::uint32_t i = r.begin; i < r.end; ++i) local[i - r.begin] = local_box(f, ids_[i]);
        if (const ObjectSplit s = binned_sah(local, o_.bins); s.axis >= 0) {
            const double cost = o_.traversal_oriented * area + o_.intersection * s.cost;
            if (cost < best.cost) best = {Kind::Oriented, cost, s, f, {}, {}};
        }
        // (c) strand split: the first direction and the one least aligned with it.
        const DVec3 a0 = glm::transpose(f.rot)[2];
        DVec3 a1(0.0);
        double least = 1.0;
        for (std::uint32_t i = r.begin; i < r.end; ++i) {
            const DVec3 a = unit_axis(ids_[i]);
            if (a == DVec3(0.0)) continue;
            const double d = std::abs(glm::dot(a, a0));
            if (d < least) least = d, a1 = a;
        }
        if (least < 0.985) {  // the two clusters differ by more than ~10 degrees
            const ObbFrame f0 = frame_from_axis(a0, f.origin), f1 = frame_from_axis(a1, f.origin);
            LocalBounds b0, b1;
            std::uint32_t n0 = 0, n1 = 0;
            for (std::uint32_t i = r.begin; i < r.end; ++i) {
                const DVec3 a = unit_axis(ids_[i]);
                if (std::abs(glm::dot(a, a0)) >= std::abs(glm::dot(a, a1))) b0.add(f0, proxies_[ids_[i]]), ++n0;
                else b1.add(f1, proxies_[ids_[i]]), ++n1;
            }
            const double cost = o_.traversal_oriented * area +
                                o_.intersection * (b0.half_area() * n0 + b1.half_area() * n1);
            if (n0 && n1 && cost < best.cost) best = {Kind::Strand, cost, {}, {}, a0, a1};
        }
        return best;
    }

    std::uint32_t partition(const Range& r, const Split& s) {
        const auto first = ids_.begin() + r.begin, last = ids_.begin() + r.end;
        std::vector<std::uint32_t>::iterator mid = first + r.size() / 2;
        if (s.kind == Kind::Aligned)
            mid = std::stable_partition(first, last, [&](std::uint32_t id) { return s.object.left(boxes_[id]); });
        else if (s.kind == Kind::Oriented)
            mid = std::stable_partition(first, last, [&](std::uint32_t id) { return s.object.left(local_box(s.frame, id)); });
        else if (s.kind == Kind::Strand)
            mid = std::stable_partition(first, last, [&](std::uint32_t id) {
                const DVec3 a = unit_axis(id);
                return std::abs(glm::dot(a, s.axis0)) >= std::abs(glm::dot(a, s.axis1));
            });
        if (mid == first || mid == last) mid = first + r.size() / 2;  // never an empty side
        return static_cast<std::uint32_t>(mid - ids_.begin());
    }

    struct Built {
        std::uint32_t first, count;
        double enter_cost;  // SAH cost of entering this node (its visit + its child tests)
    };

    // Fills one node (a run of entries) over `r`. The children are split as
    // Embree splits them; the node is then oriented or not by the SAH of its
    // own terms (rt-hardware: Embree decides by the split kind, which leaves
    // the leaf boxes aligned whenever an aligned split of two primitives is
    // cheap, losing the OBB leaf boxes that save hand-overs on RT hardware):
    //   aligned:  n t_aligned  A(node) + sum_c A_aabb(c) enter(c)
    //   oriented: n t_oriented A(node) + sum_c A_obb(c)  enter(c)
    // with enter(leaf) = t_intersection and enter(inner c) its visit + tests.
    Built build_node(const Range& r, int depth) {
        std::vector<Range> children{r};
        while (static_cast<int>(children.size()) < o_.width) {
            int pick = -1;
            double largest = -1.0;
            for (std::size_t c = 0; c < children.size(); ++c)
                if (children[c].size() > 1 && half_area(children[c].world) > largest)
                    largest = half_area(children[c].world), pick = static_cast<int>(c);
            if (pick < 0) break;
            const Range parent = children[static_cast<std::size_t>(pick)];
            const std::uint32_t mid = partition(parent, find_split(parent, depth));
            children[static_cast<std::size_t>(pick)] = make_range(parent.begin, mid);
            children.push_back(make_range(mid, parent.end));
        }
        const auto n = static_cast<std::uint32_t>(children.size());
        const auto first = static_cast<std::uint32_t>(out_.bvh.entries.size());
        out_.bvh.entries.resize(first + n);
        out_.frames.frame_of.resize(first + n, kWorldFrame);
        std::vector<BvhEntry> entry(n);
        std::vector<double> enter(n);
        std::vector<ObbFrame> frame(n);
        std::vector<Aabb> local(n);
        double aligned = n * o_.traversal_aligned * half_area(r.world);
        double oriented = n * o_.traversal_oriented * half_area(r.world);
        for (std::uint32_t c = 0; c < n; ++c) {
            const Range& ch = children[c];
            if (ch.size() == 1) {
                entry[c] = {ch.world, ch.begin, 1};
                enter[c] = o_.intersection;
            } else {
                const Built b = build_node(ch, depth + 1);
                entry[c] = {ch.world, b.first, BvhEntry::kInnerBit | b.count};
                enter[c] = b.enter_cost;
            }
            frame[c] = mean_space(ch);
            LocalBounds lb;
            for (std::uint32_t i = ch.begin; i < ch.end; ++i) lb.add(frame[c], proxies_[ids_[i]]);
            local[c] = lb.padded();
            aligned += half_area(ch.world) * enter[c];
            oriented += half_area(local[c]) * enter[c];
        }
        const bool orient = oriented < aligned;
        for (std::uint32_t c = 0; c < n; ++c) {
            if (orient) {
                entry[c].box = local[c];
                out_.frames.frame_of[first + c] = static_cast<std::uint32_t>(out_.frames.frames.size());
                out_.frames.frames.push_back(frame[c]);
            }
            out_.bvh.entries[first + c] = entry[c];
        }
        const double visit = o_.node + n * (orient ? o_.traversal_oriented : o_.traversal_aligned);
        return {first, n, visit};
    }

    std::span<const Aabb> boxes_;
    std::span<const BoundProxy> proxies_;
    ObbBuildOptions o_;
    std::vector<std::uint32_t> ids_;
    ObbBvh out_;
};

}  // namespace

ObbBvh build_obb_bvh(std::span<const Aabb> boxes, std::span<const BoundProxy> proxies,
                     const ObbBuildOptions& options) {
    if (boxes.size() != proxies.size())
        throw std::invalid_argument("build_obb_bvh: one proxy per box expected");
    if (options.width != 2 && options.width != 4 && options.width != 8)
        throw std::invalid_argument("build_obb_bvh: width must be 2, 4 or 8");
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (!boxes[i].finite())
            throw std::invalid_argument("build_obb_bvh: primitive " + std::to_string(i) +
                                        " has a box that is not finite");
    return Builder(boxes, proxies, options).run();
}

}  // namespace rtc
