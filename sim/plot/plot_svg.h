// SVG plots for the reports: line plots with several named series ("speedup
// vs tilt, one line per N") and scatter plots with optional point labels and
// a y = x or least-squares guide ("speedup vs AABB/OBB surface-area ratio").
// Legends sit outside the plot area (right of it, in columns when long).
// Hand-written SVG 1.1, no dependencies; text is XML-escaped and numbers are
// printed locale-independently, so the same input gives the same bytes.
#pragma once

#include "sim/plot/ticks.h"

#include <string>
#include <vector>

namespace rtc {

struct PlotSeries {
    std::string name;
    std::vector<double> x;  // same length as y; NaN points break the line
    std::vector<double> y;
    // Optional interval around y (both empty, or as long as y; NaN: none at
    // that point): a shaded band when points are joined, else error bars.
    // (Default-initialized: the series written {name, x, y} stay valid.)
    std::vector<double> y_low = {}, y_high = {};
};

struct PlotAxes {
    std::string title;
    std::string subtitle;  // one smaller line under the title (e.g. the cost preset)
    std::string x_label;
    std::string y_label;
    bool log_x = false;  // non-positive values are skipped on a log axis
    bool log_y = false;
    std::vector<Tick> x_ticks;  // explicit x ticks (e.g. "1000, 0.002" at x = 1000); empty: automatic
    int width = 640;  // SVG user units (px) of the frame; an outside legend widens the canvas
    int height = 420;
};

struct LinePlot {
    PlotAxes axes;
    std::vector<PlotSeries> series;
    bool markers = true;  // a dot at every data point
    bool lines = true;    // join a series' points (off for categorical x)
    std::vector<std::vector<std::string>> point_labels;  // optional, per series and point: beside its marker
};

// Colour of series i of n: the Okabe-Ito palette (colour-blind safe) up to
// 8 series, evenly spaced hues beyond, so no two series share a colour.
[[nodiscard]] std::string series_color(std::size_t i, std::size_t n);

// True when positive values span more than `decades` decades (log axis).
[[nodiscard]] bool spans_decades(const std::vector<double>& values, double decades = 2.0);

struct ScatterPoint {
    double x = 0.0;
    double y = 0.0;
    std::string label;  // drawn next to the point when non-empty
};

enum class ScatterGuide {
    None,
    Identity,      // y = x across the visible range
    LeastSquares,  // fitted y = a + b x, in log space on log axes (a power law)
};

struct ScatterPlot {
    PlotAxes axes;
    std::vector<ScatterPoint> points;
    ScatterGuide guide = ScatterGuide::None;
    // LeastSquares: the fit is drawn only when R^2 >= min_r2; R^2 is printed either way.
    double min_r2 = 0.8;
};

// Throws std::invalid_argument when a series' x and y differ in length.
[[nodiscard]] std::string line_plot_svg(const LinePlot& plot);
[[nodiscard]] std::string scatter_plot_svg(const ScatterPlot& plot);

// &, <, >, " and ' as entities; other control characters dropped (not
// allowed in XML 1.0).
[[nodiscard]] std::string xml_escape(const std::string& text);

// Writes `content` to `path`; throws rtc::InputError naming the path on failure.
void write_text_file(const std::string& path, const std::string& content);

}  // namespace rtc
