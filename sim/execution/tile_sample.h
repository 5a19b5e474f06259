// Sampled simulation (docs/sampling.md): which warp tiles of a camera frame
// are traced, and the estimators that scale the traced tiles' sums to the
// whole frame with a confidence interval.
//
// Design: the frame's tiles (tile_width x tile_height pixels, every sample
// and bounce of their paths) are cut into strata, blocks of L = 2k tiles
// (k = round(1 / fraction)) as square in pixels as L's divisors allow (4 x 8
// tiles, 32 x 32 pixels, at k = 16), from the top left; blocks over the
// frame's edge are padded with empty tiles (no pixels, no cost). Two tiles of each
// stratum are drawn without replacement, from a counter-based hash of (seed,
// stratum): every tile is traced with probability exactly 2 / L = 1 / k, so
// every total is estimated by k x the traced tiles' sum (Horvitz-Thompson),
// and the tiles do not depend on the method, the thread count or the band of
// a sharded run. Compact blocks leave less spread inside a stratum than
// strips of a tile row did (about half the interval's width on the dense
// bundles). Two per stratum is the finest stratification that still
// estimates its own variance (Cochran, Sampling Techniques, 3rd ed., ch. 5;
// the ratio estimator: ch. 6); SMARTS (Wunderlich et al., ISCA 2003)
// samples the units of a simulation in the same spirit.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace rtc {

struct SamplingOptions {
    double fraction = 1.0;   // (0, 1]; 1: every tile (no sampling)
    std::uint64_t seed = 1;  // the same seed traces the same tiles
};

class TileSample {
public:
    static constexpr std::uint32_t kEmpty = UINT32_MAX;  // a padding tile (no pixels)
    static constexpr std::size_t kPerStratum = 2;

    // The sample of a width x height frame in tiles of tile_w x tile_h
    // pixels; nullopt when the fraction rounds to every tile (k = 1).
    [[nodiscard]] static std::optional<TileSample> make(int width, int height, int tile_w, int tile_h,
                                                        const SamplingOptions& o);

    // 1 / the traced fraction: every estimate is k x the traced sum.
    [[nodiscard]] std::uint32_t k() const { return k_; }
    [[nodiscard]] double fraction() const { return 1.0 / k_; }
    [[nodiscard]] std::uint64_t seed() const { return seed_; }
    [[nodiscard]] int tile_width() const { return tile_w_; }
    [[nodiscard]] int tile_height() const { return tile_h_; }
    [[nodiscard]] std::uint32_t tiles_x() const { return tiles_x_; }
    [[nodiscard]] std::uint32_t tiles_y() const { return tiles_y_; }
    [[nodiscard]] std::size_t tiles() const { return traced_.size(); }
    [[nodiscard]] std::size_t strata() const { return slots_.size() / kPerStratum; }
    // A stratum's block of tiles, block_width() x block_height() = 2k, and
    // the blocks per row: stratum h is block (h % blocks_x, h / blocks_x).
    [[nodiscard]] std::uint32_t block_width() const { return block_w_; }
    [[nodiscard]] std::uint32_t block_height() const { return block_h_; }
    [[nodiscard]] std::uint32_t blocks_x() const { return blocks_x_; }
    // The tiles traced (padding tiles drawn are counted in slots, not here).
    [[nodiscard]] std::size_t traced_tiles() const { return traced_count_; }
    // Whether tile (tx, ty) is traced.
    [[nodiscard]] bool traced(std::uint32_t tx, std::uint32_t ty) const {
        return traced_[static_cast<std::size_t>(ty) * tiles_x_ + tx] != 0;
    }
    // Whether pixel (px, py) lies in a traced tile.
    [[nodiscard]] bool traced_pixel(std::uint32_t px, std::uint32_t py) const {
        return traced(px / static_cast<std::uint32_t>(tile_w_), py / static_cast<std::uint32_t>(tile_h_));
    }
    // The drawn tiles, kPerStratum per stratum in stratum order: a row-major
    // tile index, or kEmpty for a padding tile (its value is 0).
    [[nodiscard]] const std::vector<std::uint32_t>& slots() const { return slots_; }

    // Per slot, the sum of `pixel_value(pixel)` over the tile's pixels
    // (0 for padding): the per-tile values the estimators below take.
    template <class F>
    [[nodiscard]] std::vector<double> tile_values(int width, int height, F&& pixel_value) const {
        std::vector<double> v(slots_.size(), 0.0);
        for (std::size_t s = 0; s < slots_.size(); ++s) {
            if (slots_[s] == kEmpty) continue;
            const std::uint32_t tx = slots_[s] % tiles_x_, ty = slots_[s] / tiles_x_;
            const auto x0 = static_cast<int>(tx) * tile_w_, y0 = static_cast<int>(ty) * tile_h_;
            double sum = 0.0;
            for (int y = y0; y < std::min(y0 + tile_h_, height); ++y)
                for (int x = x0; x < std::min(x0 + tile_w_, width); ++x)
                    sum += pixel_value(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                       static_cast<std::size_t>(x));
            v[s] = sum;
        }
        return v;
    }

private:
    std::uint32_t k_ = 1;
    std::uint64_t seed_ = 1;
    int tile_w_ = 8, tile_h_ = 4;
    std::uint32_t tiles_x_ = 0, tiles_y_ = 0;
    std::uint32_t block_w_ = 0, block_h_ = 0, blocks_x_ = 0;  // a stratum's block of tiles; blocks per row
    std::vector<std::uint8_t> traced_;  // per tile, row-major
    std::vector<std::uint32_t> slots_;
    std::size_t traced_count_ = 0;
};

// k = round(1 / fraction), at least 1: the fraction a sample actually traces is 1 / k.
[[nodiscard]] std::uint32_t sample_k(double fraction);

// An estimate from a stratified sample of two per stratum (values per slot,
// as TileSample::slots orders them) and its 95 % confidence interval.
struct SampledEstimate {
    double value = 0.0;
    double std_error = 0.0;
    double dof = 0.0;  // Satterthwaite's effective degrees of freedom
    std::array<double, 2> interval{};
};

// The frame total: k x sum(y), variance k (k - 1) sum_h (y_h1 - y_h2)^2.
[[nodiscard]] SampledEstimate estimate_total(const std::vector<double>& y, std::uint32_t k);
// The ratio sum(num) / sum(den) of two totals over the same tiles (a
// speedup: baseline cycles over a method's), with the linearized variance
// of the ratio estimator: that of the total of num - R den, over (k sum(den))^2.
[[nodiscard]] SampledEstimate estimate_ratio(const std::vector<double>& num, const std::vector<double>& den,
                                             std::uint32_t k);

// The 0.975 quantile of Student's t with `dof` degrees of freedom (rounded
// down, at least 1): exact for 1 and 2, the Cornish-Fisher expansion above
// (Abramowitz & Stegun 26.7.5), within 0.3 % from 3 on.
[[nodiscard]] double t_quantile_975(double dof);

}  // namespace rtc
