#include "sim/run/hit_agreement.h"

#include "core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rtc {

AgreementSample agreement_sample(std::span<const Ray> rays, std::span<const TraceHit> hits, std::size_t max_rays) {
    AgreementSample s;
    const std::size_t n = std::min(rays.size(), hits.size());
    if (n == 0 || max_rays == 0) return s;
    const std::size_t stride = (n + max_rays - 1) / max_rays;
    for (std::size_t i = 0; i < n; i += stride) {
        s.rays.push_back(rays[i]);
        s.hits.push_back(hits[i]);
    }
    return s;
}

double HitAgreement::fraction() const {
    return rays ? static_cast<double>(agree) / static_cast<double>(rays) : std::numeric_limits<double>::quiet_NaN();
}

double HitAgreement::hit_miss_fraction() const {
    return rays ? static_cast<double>(hit_miss) / static_cast<double>(rays) : std::numeric_limits<double>::quiet_NaN();
}

bool hits_agree(const TraceHit& base, const TraceHit& hit, const Ray& ray, const Geometry& g) {
    if (base.hit() != hit.hit()) return false;
    if (!base.hit()) return true;
    const auto radius = [&](const TraceHit& h) {
        return h.geom == GeometryId::Curves ? static_cast<double>(primitive_radius(g, h.prim)) : 0.0;
    };
    const double gap = std::abs(static_cast<double>(hit.t) - static_cast<double>(base.t)) *
                       glm::length(DVec3(ray.direction));
    return gap <= kAgreementRadii * std::max(radius(base), radius(hit));
}

HitAgreement measure_hit_agreement(const BuiltMethod& method, const Geometry& g, const TraceOptions& trace,
                                   const AgreementSample& sample, std::string baseline, unsigned threads) {
    HitAgreement a;
    a.baseline = std::move(baseline);
    const std::size_t n = sample.rays.size();
    std::vector<TraceHit> hits(n);
    parallel_for(n, threads, [&](std::size_t i, unsigned) {
        CountingSink sink;  // the counts are the frame's business, not the comparison's
        hits[i] = method.trace(g, sample.rays[i], trace, sink);
    });
    a.rays = n;
    for (std::size_t i = 0; i < n; ++i) {
        const TraceHit& base = sample.hits[i];
        a.hit_miss += base.hit() == hits[i].hit();
        a.both_hit += base.hit() && hits[i].hit();
        a.agree += hits_agree(base, hits[i], sample.rays[i], g);
    }
    return a;
}

}  // namespace rtc
