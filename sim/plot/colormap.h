// Colour maps for the heat maps: perceptually uniform sequential maps
// (viridis, inferno) for clocks per pixel, and a diverging blue-white-red map
// for ratios centred at 1. Each is a small table of control points sampled
// from the published map, linearly interpolated in sRGB; plenty for figures
// read against a colour bar.
#pragma once

#include "sim/plot/image.h"

namespace rtc {

enum class Colormap {
    Viridis,       // sequential, dark purple -> yellow
    Inferno,       // sequential, black -> pale yellow
    BlueWhiteRed,  // diverging (ColorBrewer RdBu, reversed): blue < centre (white) < red
};

// Neutral grey for pixels without data (NaN, inf, no rays): not on any map.
inline constexpr Rgb kNoDataGrey{128, 128, 128};

// Colour at t in [0, 1] (clamped). NaN gives kNoDataGrey.
[[nodiscard]] Rgb colormap_at(Colormap map, double t);

// "viridis", "inferno", "blue-white-red".
[[nodiscard]] const char* colormap_name(Colormap map);

}  // namespace rtc
