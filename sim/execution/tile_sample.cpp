#include "sim/execution/tile_sample.h"

#include "sim/workload/rng.h"

#include <cmath>

namespace rtc {

std::uint32_t sample_k(double fraction) {
    if (!(fraction > 0.0) || fraction >= 1.0) return 1;
    const double k = std::round(1.0 / fraction);
    return k >= 1e9 ? 1000000000u : static_cast<std::uint32_t>(std::max(1.0, k));
}

std::optional<TileSample> TileSample::make(int width, int height, int tile_w, int tile_h, const SamplingOptions& o) {
    const std::uint32_t k = sample_k(o.fraction);
    if (k <= 1 || width <= 0 || height <= 0 || tile_w <= 0 || tile_h <= 0) return std::nullopt;
    TileSample s;
    s.k_ = k;
    s.seed_ = o.seed;
    s.tile_w_ = tile_w;
    s.tile_h_ = tile_h;
    s.tiles_x_ = static_cast<std::uint32_t>((width + tile_w - 1) / tile_w);
    s.tiles_y_ = static_cast<std::uint32_t>((height + tile_h - 1) / tile_h);
    const std::size_t tiles = static_cast<std::size_t>(s.tiles_x_) * s.tiles_y_;
    const std::uint64_t stratum = 2ull * k;  // L
    // A stratum is a block of bw x bh = L tiles, as square in pixels as L's
    // divisors allow (bh the divisor nearest sqrt(L tile_w / tile_h)):
    // compact strata leave less spread inside them than strips of a row.
    std::uint64_t bh = 1;
    const double ideal = std::sqrt(static_cast<double>(stratum) * tile_w / tile_h);
    for (std::uint64_t d = 1; d <= stratum; ++d)
        if (stratum % d == 0 && std::abs(static_cast<double>(d) - ideal) < std::abs(static_cast<double>(bh) - ideal))
            bh = d;
    const std::uint64_t bw = stratum / bh;
    const std::uint64_t blocks_x = (s.tiles_x_ + bw - 1) / bw, blocks_y = (s.tiles_y_ + bh - 1) / bh;
    s.block_w_ = static_cast<std::uint32_t>(bw);
    s.block_h_ = static_cast<std::uint32_t>(bh);
    s.blocks_x_ = static_cast<std::uint32_t>(blocks_x);
    const std::size_t strata = static_cast<std::size_t>(blocks_x * blocks_y);
    s.traced_.assign(tiles, 0);
    s.slots_.reserve(strata * kPerStratum);
    const std::uint64_t key = mix64(o.seed ^ 0x5A4D504C45ull);  // "SAMPLE": apart from the path tracer's streams
    for (std::size_t h = 0; h < strata; ++h) {
        // Two distinct positions of L, uniformly: a in [0, L), b in [0, L - 1)
        // moved past a. The modulo's bias is below L / 2^64.
        const std::uint64_t r = hash_combine(hash_combine(key, static_cast<std::uint32_t>(h)),
                                             static_cast<std::uint32_t>(h >> 32));
        const std::uint64_t a = r % stratum;
        std::uint64_t b = mix64(r + 0x9E3779B97F4A7C15ull) % (stratum - 1);
        if (b >= a) ++b;
        for (const std::uint64_t pos : {std::min(a, b), std::max(a, b)}) {
            // Position pos of block h, row-major in the block; past the
            // frame's edge it is a padding tile.
            const std::uint64_t tx = (h % blocks_x) * bw + pos % bw, ty = (h / blocks_x) * bh + pos / bw;
            if (tx >= s.tiles_x_ || ty >= s.tiles_y_) {
                s.slots_.push_back(kEmpty);
                continue;
            }
            const std::uint64_t tile = ty * s.tiles_x_ + tx;
            s.slots_.push_back(static_cast<std::uint32_t>(tile));
            s.traced_[tile] = 1;
            ++s.traced_count_;
        }
    }
    return s;
}

namespace {

// k (k - 1) sum_h (y_h1 - y_h2)^2 and Satterthwaite's degrees of freedom,
// (sum_h d_h^2)^2 / sum_h d_h^4 (each stratum's variance has one).
SampledEstimate from_differences(double value, const std::vector<double>& e, std::uint32_t k, double scale) {
    SampledEstimate out;
    out.value = value;
    double sum2 = 0.0, sum4 = 0.0;
    for (std::size_t h = 0; h + 1 < e.size(); h += TileSample::kPerStratum) {
        const double d = e[h] - e[h + 1];
        sum2 += d * d;
        sum4 += d * d * d * d;
    }
    const double kk = static_cast<double>(k);
    out.std_error = std::sqrt(kk * (kk - 1.0) * sum2) / scale;
    out.dof = sum4 > 0.0 ? sum2 * sum2 / sum4 : static_cast<double>(e.size() / TileSample::kPerStratum);
    const double half = t_quantile_975(out.dof) * out.std_error;
    out.interval = {value - half, value + half};
    return out;
}

}  // namespace

SampledEstimate estimate_total(const std::vector<double>& y, std::uint32_t k) {
    double sum = 0.0;
    for (const double v : y) sum += v;
    return from_differences(static_cast<double>(k) * sum, y, k, 1.0);
}

SampledEstimate estimate_ratio(const std::vector<double>& num, const std::vector<double>& den, std::uint32_t k) {
    double sn = 0.0, sd = 0.0;
    for (const double v : num) sn += v;
    for (const double v : den) sd += v;
    if (!(sd > 0.0) || num.size() != den.size()) return {};
    const double r = sn / sd;
    std::vector<double> e(num.size());
    for (std::size_t i = 0; i < e.size(); ++i) e[i] = num[i] - r * den[i];
    return from_differences(r, e, k, static_cast<double>(k) * sd);
}

double t_quantile_975(double dof) {
    const double n = std::max(1.0, std::floor(dof));
    if (n == 1.0) return 12.706204736174704;  // tan(0.475 pi)
    if (n == 2.0) return 4.302652729749464;   // (2p - 1) / sqrt(2 p (1 - p)) at p = 0.975
    const double z = 1.959963984540054, z2 = z * z;
    const double z3 = z2 * z, z5 = z3 * z2, z7 = z5 * z2, z9 = z7 * z2;
    const double g1 = (z3 + z) / 4.0;
    const double g2 = (5.0 * z5 + 16.0 * z3 + 3.0 * z) / 96.0;
    const double g3 = (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / 384.0;
    const double g4 = (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z) / 92160.0;
    return z + g1 / n + g2 / (n * n) + g3 / (n * n * n) + g4 / (n * n * n * n);
}

}  // namespace rtc
