// How closely an approximate method's hits (MethodInfo::approximate: dots)
// follow the baseline's. Exact methods are tested to return the baseline's
// hits bit for bit; an approximate one is measured instead, on the same rays:
// a fixed sample of the rays the baseline traced (camera and path rays
// alike, since a method's own paths bounce off its own hits and part ways
// with the baseline's after the first hit), each traced again through the
// approximate method and compared with the baseline's recorded hit.
#pragma once

#include "sim/hardware/leaf_programs.h"
#include "sim/methods/method.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rtc {

// At most this many rays are compared: enough for a fraction to +-0.4 %
// (95 %, binomial), cheap next to the frame.
inline constexpr std::size_t kMaxAgreementRays = std::size_t{1} << 16;
// Two hits agree in distance when |t - t_base| |d| is at most this many
// radii of the curve primitive hit: one diameter, the strand's thickness.
// A ray crossing a strand meets the tube's surface and the dots quad on its
// axis half a diameter apart; a grazing ray, up to a chord further.
inline constexpr double kAgreementRadii = 2.0;

// The rays compared and the baseline's hits on them.
struct AgreementSample {
    std::vector<Ray> rays;
    std::vector<TraceHit> hits;
};

// Every k-th of the baseline's recorded rays and hits (k the smallest that
// keeps at most `max_rays`), so the sample does not depend on threads.
[[nodiscard]] AgreementSample agreement_sample(std::span<const Ray> rays, std::span<const TraceHit> hits,
                                               std::size_t max_rays = kMaxAgreementRays);

struct HitAgreement {
    std::string baseline;
    std::uint64_t rays = 0;
    std::uint64_t hit_miss = 0;  // both hit or both miss
    std::uint64_t both_hit = 0;
    std::uint64_t agree = 0;     // hit/miss agree and, when both hit, the distances within the tolerance
    double tolerance_radii = kAgreementRadii;

    // The fraction of rays that agree (hit/miss and distance); NaN without rays.
    [[nodiscard]] double fraction() const;
    [[nodiscard]] double hit_miss_fraction() const;
};

// Whether `hit` agrees with the baseline's `base` on `ray`: both miss, or
// both hit within kAgreementRadii radii of the larger curve primitive hit
// (a mesh hit has no radius: two mesh hits must be at the same distance).
[[nodiscard]] bool hits_agree(const TraceHit& base, const TraceHit& hit, const Ray& ray, const Geometry& g);

// Traces `sample`'s rays through `method` (closest hits) and compares them
// with the sample's hits.
[[nodiscard]] HitAgreement measure_hit_agreement(const BuiltMethod& method, const Geometry& g,
                                                 const TraceOptions& trace, const AgreementSample& sample,
                                                 std::string baseline, unsigned threads);

}  // namespace rtc
