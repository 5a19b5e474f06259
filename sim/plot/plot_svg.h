// SVG plots for the reports: line plots with several named series ("speedup
// vs tilt, one line per N") and scatter plots with optional point labels and
// a y = x or least-squares guide ("speedup vs AABB/OBB surface-area ratio").
// Hand-written SVG 1.1, no dependencies; text is XML-escaped and numbers are
// printed locale-independently, so the same input gives the same bytes.
#pragma once

#include <string>
#include <vector>

namespace rtc {

struct PlotSeries {
    std::string name;
    std::vector<double> x;  // same length as y; NaN points break the line
    std::vector<double> y;
};

struct PlotAxes {
    std::string title;
    std::string x_label;
    std::string y_label;
    bool log_x = false;  // non-positive values are skipped on a log axis
    bool log_y = false;
    int width = 640;  // SVG user units (px)
    int height = 420;
};

struct LinePlot {
    PlotAxes axes;
    std::vector<PlotSeries> series;
    bool markers = true;  // a dot at every data point
};

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
