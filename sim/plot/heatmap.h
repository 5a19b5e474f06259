// Heat maps of per-pixel scalar fields (clocks per pixel, box tests per ray):
// the paper's figure 1/4 pictures. A field is drawn through a colour map on a
// caller-given scale, so several methods can share one common scale
// (common_scale), with a colour bar, tick labels, a title and a caption.
// Ratio maps (reference / masquerade) use the diverging map on a log scale
// centred at 1. Pixels without data (NaN, inf: no rays) are neutral grey.
#pragma once

#include "sim/plot/colormap.h"
#include "sim/plot/image.h"
#include "sim/plot/ticks.h"

#include <limits>
#include <string>
#include <vector>

namespace rtc {

// width x height floats, row-major, row 0 = top (the camera's image order).
struct ScalarField {
    int width = 0;
    int height = 0;
    std::vector<float> values;

    [[nodiscard]] float at(int x, int y) const {
        return values[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
    }
};

enum class ScaleKind { Linear, Log };

struct HeatmapScale {
    double lo = 0.0;
    double hi = 1.0;
    ScaleKind kind = ScaleKind::Linear;
    // What common_scale saw (NaN: unknown). Values beyond [lo, hi] are drawn
    // in the end colours; render_heatmap then labels the bar's end ">= hi"
    // and says in a note at which percentile and value it clipped.
    double data_min = std::numeric_limits<double>::quiet_NaN();
    double data_max = std::numeric_limits<double>::quiet_NaN();
    double percentile = 100.0;
    [[nodiscard]] bool clipped_high() const { return data_max > hi; }
    [[nodiscard]] bool clipped_low() const { return data_min < lo; }
};

// Position of `value` on the scale, clamped to [0, 1]; NaN for no data
// (non-finite value). On a log scale values <= 0 clamp to 0.
[[nodiscard]] double scale_position(const HeatmapScale& scale, double value);

// One scale for several fields: hi is the `percentile` (0..100) of all
// finite values, clipping rare outliers; lo is the minimum (linear) or the
// (100 - percentile) percentile of the positive values (log). Degenerate or
// empty input still gives a usable range (lo < hi). Records the data's
// minimum, maximum and the percentile, so the map can say it clipped.
[[nodiscard]] HeatmapScale common_scale(const std::vector<const ScalarField*>& fields,
                                        double percentile = 99.5, ScaleKind kind = ScaleKind::Linear);

struct HeatmapOptions {
    std::string title;      // drawn at 2x above the map; may be empty
    std::string bar_label;  // above the colour bar, e.g. "clocks / pixel"
    std::string caption;    // below the map; '\n' starts a new line
    Colormap colormap = Colormap::Viridis;
    int pixel_scale = 0;      // integer magnification; 0 = automatic (>= ~320 px)
    std::vector<Tick> ticks;  // empty = automatic for the scale
    int text_scale = 2;       // magnification of all text (the font is ~7 px at 1)
};

struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
};

struct Heatmap {
    Image image;
    PixelRect map;       // where the field was drawn (pixel_scale x field size)
    PixelRect colorbar;  // the colour bar's inside, top = scale.hi
};

// Throws std::invalid_argument when values.size() != width * height.
[[nodiscard]] Heatmap render_heatmap(const ScalarField& field, const HeatmapScale& scale,
                                     const HeatmapOptions& options = {});

// Per-pixel numerator / denominator; NaN where either is non-finite, or the
// ratio is undefined (0/0, x/0). Throws std::invalid_argument on size mismatch.
[[nodiscard]] ScalarField ratio_field(const ScalarField& numerator, const ScalarField& denominator);

struct RatioMapOptions {
    std::string title;
    std::string ratio_label = "ref/obb";  // shown over the colour bar
    std::string caption;
    double max_ratio = 8.0;  // scale spans [1/max_ratio, max_ratio], log, centred at 1
    int pixel_scale = 0;
    int text_scale = 2;
};

// Powers of two in [1/max_ratio, max_ratio], labelled "1/4x", "1x", "4x".
[[nodiscard]] std::vector<Tick> ratio_ticks(double max_ratio);

// numerator/denominator with the diverging map: 1 is white, > 1 red, < 1 blue;
// ticks at powers of two labelled "1/4x", "1x", "4x".
[[nodiscard]] Heatmap render_ratio_map(const ScalarField& numerator, const ScalarField& denominator,
                                       const RatioMapOptions& options = {});

}  // namespace rtc
