// SVG plot writer (see plot_svg.h). Both plot kinds share one frame: axes
// fitted to the data and widened to nice tick values (or explicit x ticks),
// grid, tick labels, axis labels, title and subtitle, and a legend right of
// the plot area, in as many columns as its entries need.
#include "sim/plot/plot_svg.h"

#include "core/input_error.h"
#include "sim/util/json_file.h"
#include "sim/util/table.h"
#include "sim/plot/ticks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace rtc {
namespace {

// Okabe-Ito colour-blind-safe palette, yellow last (weak on white).
constexpr std::array<const char*, 8> kPalette{"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                              "#E69F00", "#56B4E9", "#000000", "#F0E442"};
constexpr double kCharWidth = 7.0;  // rough width of a 12px sans-serif glyph
constexpr std::size_t kMaxLegendChars = 44;
constexpr double kLegendRow = 18.0;

std::string num(double v) { return format_fixed(v, 2); }

bool usable(double v, bool log) { return std::isfinite(v) && (!log || v > 0.0); }

struct Axis {
    double lo = 0.0, hi = 1.0;
    bool log = false;
    std::vector<Tick> ticks;

    double unit(double v) const {  // data -> [0, 1]
        return log ? (std::log10(v) - std::log10(lo)) / (std::log10(hi) - std::log10(lo)) : (v - lo) / (hi - lo);
    }
};

Axis make_axis(const std::vector<double>& values, bool log, const std::vector<Tick>& explicit_ticks = {}) {
    Axis a;
    a.log = log;
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values)
        if (usable(v, log)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!explicit_ticks.empty()) {  // the ticks' range, padded so edge points stay whole
        for (const Tick& t : explicit_ticks)
            if (usable(t.value, log)) lo = std::min(lo, t.value), hi = std::max(hi, t.value), a.ticks.push_back(t);
        if (!(lo <= hi)) lo = log ? 1.0 : 0.0, hi = log ? 10.0 : 1.0;
        if (log) {
            const double pad = std::pow(10.0, std::max(0.05 * std::log10(hi / lo), 0.1));
            a.lo = lo / pad, a.hi = hi * pad;
        } else {
            const double pad = hi > lo ? 0.06 * (hi - lo) : 0.5;
            a.lo = lo - pad, a.hi = hi + pad;
        }
        return a;
    }
    if (!(lo <= hi)) lo = log ? 1.0 : 0.0, hi = log ? 10.0 : 1.0;
    if (lo == hi) {
        if (log) lo /= 2.0, hi *= 2.0;
        else lo -= std::max(1.0, std::abs(lo) * 0.1), hi += std::max(1.0, std::abs(hi) * 0.1);
    }
    if (log) {
        const double l0 = std::floor(std::log10(lo) + 1e-9), l1 = std::ceil(std::log10(hi) - 1e-9);
        a.lo = std::pow(10.0, l0);
        a.hi = std::pow(10.0, std::max(l1, l0 + 1.0));
        a.ticks = log_ticks(a.lo, a.hi);
    } else {
        // The data's range and 4 % either side, so no point sits on the frame
        // (not below 0 for positive data); nice ticks inside it.
        const double pad = 0.04 * (hi - lo);
        a.lo = lo > 0.0 ? std::max(0.0, lo - pad) : lo - pad;
        a.hi = hi + pad;
        a.ticks = linear_ticks(a.lo, a.hi, 7);
    }
    return a;
}

struct LegendEntry {
    std::string name;
    std::string color;
    bool dashed = false;
    bool marker = true;
    bool line = true;  // false: a text-only note (e.g. "no fit: R^2 = 0.23")
};

std::string shorten(const std::string& name) {
    if (name.size() <= kMaxLegendChars) return name;
    std::size_t cut = kMaxLegendChars - 3;
    while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;  // whole UTF-8 characters
    return name.substr(0, cut) + "...";
}

// The frame shared by both plots; emits everything but the data.
struct Frame {
    PlotAxes axes;
    Axis x, y;
    double left = 70, top = 40, right = 0, bottom = 0;  // plot-area edges
    double legend_w = 0.0;
    std::size_t legend_rows = 1, legend_cols = 0;
    bool rotate_x = false;  // x tick labels too long for their spacing: drawn at -35 degrees
    int canvas_width = 0, canvas_height = 0;  // axes' size, widened by the legend and rotated labels

    Frame(const PlotAxes& ax, const std::vector<double>& xs, const std::vector<double>& ys,
          const std::vector<LegendEntry>& legend)
        : axes(ax), x(make_axis(xs, ax.log_x, ax.x_ticks)), y(make_axis(ys, ax.log_y)) {
        for (const auto& e : legend)
            legend_w = std::max(legend_w, (e.line || e.marker ? 34.0 : 4.0) + kCharWidth * static_cast<double>(shorten(e.name).size()));
        if (!axes.title.empty()) top = axes.subtitle.empty() ? 40 : 56;
        else top = axes.subtitle.empty() ? 20 : 36;
        right = axes.width - 20.0;
        bottom = axes.height - 50.0;
        double label_w = 0.0;
        for (const Tick& t : x.ticks) label_w = std::max(label_w, kCharWidth * static_cast<double>(t.label.size()));
        const double spacing = (right - left) / static_cast<double>(std::max<std::size_t>(x.ticks.size(), 1));
        rotate_x = label_w > spacing - 6.0;
        const double extra = rotate_x ? std::max(0.0, 0.57 * label_w - 10.0) : 0.0;  // sin 35 deg
        canvas_height = axes.height + static_cast<int>(extra);
        bottom = canvas_height - 50.0 - extra;
        legend_rows = std::max<std::size_t>(1, static_cast<std::size_t>((bottom - top - 8.0) / kLegendRow));
        legend_cols = legend.empty() ? 0 : (legend.size() + legend_rows - 1) / legend_rows;
        canvas_width = axes.width + static_cast<int>(static_cast<double>(legend_cols) * (legend_w + 12.0));
    }
    double px(double v) const { return left + x.unit(v) * (right - left); }
    double py(double v) const { return bottom - y.unit(v) * (bottom - top); }

    std::string open(const std::vector<LegendEntry>& legend) const {
        std::string s;
        s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
        s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + std::to_string(canvas_width) +
             "\" height=\"" + std::to_string(canvas_height) + "\" viewBox=\"0 0 " + std::to_string(canvas_width) + " " +
             std::to_string(canvas_height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
        s += "<defs><clipPath id=\"plot-area\"><rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" +
             num(right - left) + "\" height=\"" + num(bottom - top) + "\"/></clipPath></defs>\n";
        s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
        if (!axes.title.empty())
            s += "<text x=\"" + num((left + right) / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">" +
                 xml_escape(axes.title) + "</text>\n";
        if (!axes.subtitle.empty())
            s += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(top - 10) +
                 "\" text-anchor=\"middle\" fill=\"#555555\">" + xml_escape(axes.subtitle) + "</text>\n";
        s += "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
        for (const Tick& t : x.ticks)
            s += "<line x1=\"" + num(px(t.value)) + "\" y1=\"" + num(top) + "\" x2=\"" + num(px(t.value)) + "\" y2=\"" +
                 num(bottom) + "\"/>\n";
        for (const Tick& t : y.ticks)
            s += "<line x1=\"" + num(left) + "\" y1=\"" + num(py(t.value)) + "\" x2=\"" + num(right) + "\" y2=\"" +
                 num(py(t.value)) + "\"/>\n";
        s += "</g>\n<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(right - left) +
             "\" height=\"" + num(bottom - top) + "\" fill=\"none\" stroke=\"#333333\"/>\n";
        s += "<g fill=\"#222222\">\n";
        for (const Tick& t : x.ticks) {
            const std::string tx = num(px(t.value)), ty = num(bottom + 16);
            if (rotate_x)
                s += "<text x=\"" + tx + "\" y=\"" + ty + "\" text-anchor=\"end\" transform=\"rotate(-35 " + tx + " " +
                     ty + ")\">" + xml_escape(t.label) + "</text>\n";
            else
                s += "<text x=\"" + tx + "\" y=\"" + ty + "\" text-anchor=\"middle\">" + xml_escape(t.label) + "</text>\n";
        }
        for (const Tick& t : y.ticks)
            s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(py(t.value) + 4) + "\" text-anchor=\"end\">" +
                 xml_escape(t.label) + "</text>\n";
        if (!axes.x_label.empty())
            s += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(canvas_height - 12.0) + "\" text-anchor=\"middle\">" +
                 xml_escape(axes.x_label) + "</text>\n";
        if (!axes.y_label.empty()) {
            const std::string cy = num((top + bottom) / 2);
            s += "<text x=\"18\" y=\"" + cy + "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " + cy + ")\">" +
                 xml_escape(axes.y_label) + "</text>\n";
        }
        s += "</g>\n";
        for (std::size_t i = 0; i < legend.size(); ++i) {
            const LegendEntry& e = legend[i];
            const double lx = right + 14 + static_cast<double>(i / legend_rows) * (legend_w + 12.0);
            const double ly = top + 10 + kLegendRow * static_cast<double>(i % legend_rows);
            if (e.line)
                s += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 20) + "\" y2=\"" + num(ly) +
                     "\" stroke=\"" + e.color + "\" stroke-width=\"2\"" + (e.dashed ? " stroke-dasharray=\"5,3\"" : "") + "/>\n";
            if (e.marker)
                s += "<circle cx=\"" + num(lx + 10) + "\" cy=\"" + num(ly) + "\" r=\"3\" fill=\"" + e.color + "\"/>\n";
            s += "<text x=\"" + num(lx + (e.line || e.marker ? 26 : 0)) + "\" y=\"" + num(ly + 4) + "\">" + xml_escape(shorten(e.name)) +
                 "</text>\n";
        }
        return s;
    }
};

std::string polyline(const std::vector<std::pair<double, double>>& pts, const std::string& color, bool dashed) {
    std::string s = "<polyline fill=\"none\" stroke=\"" + color + "\" stroke-width=\"2\"";
    if (dashed) s += " stroke-dasharray=\"5,3\"";
    s += " points=\"";
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (i) s += ' ';
        s += num(pts[i].first);
        s += ',';
        s += num(pts[i].second);
    }
    return s + "\"/>\n";
}

}  // namespace

std::string series_color(std::size_t i, std::size_t n) {
    if (n <= kPalette.size()) return kPalette[i % kPalette.size()];
    // Evenly spaced hues (HSL s = 0.75), neighbours told apart by lightness too
    // (0.32 and 0.55 alternating).
    const double h = 360.0 * static_cast<double>(i) / static_cast<double>(n), l = i % 2 ? 0.55 : 0.32;
    const double c = (1.0 - std::abs(2.0 * l - 1.0)) * 0.75, hp = h / 60.0;
    const double xx = c * (1.0 - std::abs(std::fmod(hp, 2.0) - 1.0)), m = l - c / 2.0;
    double r = 0, g = 0, b = 0;
    if (hp < 1) r = c, g = xx;
    else if (hp < 2) r = xx, g = c;
    else if (hp < 3) g = c, b = xx;
    else if (hp < 4) g = xx, b = c;
    else if (hp < 5) r = xx, b = c;
    else r = c, b = xx;
    const auto byte = [](double v) { return std::clamp(static_cast<int>(std::lround(v * 255.0)), 0, 255); };
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02X%02X%02X", byte(r + m), byte(g + m), byte(b + m));
    return buf;
}

bool spans_decades(const std::vector<double>& values, double decades) {
    double lo = INFINITY, hi = 0.0;
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        if (v <= 0.0) return false;
        lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return hi > 0.0 && hi / lo > std::pow(10.0, decades);
}

std::string xml_escape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&apos;"; break;
            default:
                if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
        }
    }
    return out;
}

std::string line_plot_svg(const LinePlot& plot) {
    std::vector<double> xs, ys;
    std::vector<LegendEntry> legend;
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
        const PlotSeries& s = plot.series[i];
        if (s.x.size() != s.y.size())
            throw std::invalid_argument("line_plot_svg: series '" + s.name + "' has x and y of different lengths");
        const bool band = !s.y_low.empty();
        if (band && (s.y_low.size() != s.y.size() || s.y_high.size() != s.y.size()))
            throw std::invalid_argument("line_plot_svg: series '" + s.name + "' has an interval of another length");
        for (std::size_t k = 0; k < s.x.size(); ++k)
            if (usable(s.x[k], plot.axes.log_x) && usable(s.y[k], plot.axes.log_y)) {
                xs.push_back(s.x[k]), ys.push_back(s.y[k]);
                for (double v : {band ? s.y_low[k] : NAN, band ? s.y_high[k] : NAN})
                    if (usable(v, plot.axes.log_y)) xs.push_back(s.x[k]), ys.push_back(v);
            }
        legend.push_back({s.name, series_color(i, plot.series.size()), false, plot.markers, plot.lines});
    }
    const Frame f(plot.axes, xs, ys, legend);
    std::string svg = f.open(legend);
    svg += "<g clip-path=\"url(#plot-area)\">\n";
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
        const PlotSeries& s = plot.series[i];
        const std::string color = series_color(i, plot.series.size());
        std::vector<std::pair<double, double>> run, upper, lower;
        const auto flush_band = [&] {  // upper edge left to right, lower edge back
            upper.insert(upper.end(), lower.rbegin(), lower.rend());
            std::string pts;
            for (const auto& [x, y] : upper) pts.append(pts.empty() ? "" : " ").append(num(x)).append(",").append(num(y));
            if (upper.size() >= 4) svg += "<polygon fill=\"" + color + "\" fill-opacity=\"0.18\" stroke=\"none\" points=\"" + pts + "\"/>\n";
            upper.clear(), lower.clear();
        };
        for (std::size_t k = 0; k < s.y_low.size(); ++k) {
            if (!usable(s.x[k], plot.axes.log_x) || !usable(s.y_low[k], plot.axes.log_y) ||
                !usable(s.y_high[k], plot.axes.log_y)) {
                flush_band();
                continue;
            }
            upper.emplace_back(f.px(s.x[k]), f.py(s.y_high[k]));
            lower.emplace_back(f.px(s.x[k]), f.py(s.y_low[k]));
            if (!plot.lines) {  // categories: an error bar per point
                svg += polyline({upper.back(), lower.back()}, color, false);
                upper.clear(), lower.clear();
            }
        }
        flush_band();
        std::string dots;
        auto flush = [&] {
            if (plot.lines && run.size() >= 2) svg += polyline(run, color, false);
            run.clear();
        };
        for (std::size_t k = 0; k < s.x.size(); ++k) {
            if (!usable(s.x[k], plot.axes.log_x) || !usable(s.y[k], plot.axes.log_y)) {
                flush();
                continue;
            }
            run.emplace_back(f.px(s.x[k]), f.py(s.y[k]));
            if (i < plot.point_labels.size() && k < plot.point_labels[i].size() && !plot.point_labels[i][k].empty())
                dots += "<text x=\"" + num(run.back().first + 6) + "\" y=\"" + num(run.back().second - 6) +
                        "\" font-size=\"10\" fill=\"" + color + "\">" + xml_escape(plot.point_labels[i][k]) + "</text>\n";
            if (plot.markers || !plot.lines)
                dots += "<circle cx=\"" + num(run.back().first) + "\" cy=\"" + num(run.back().second) + "\" r=\"" +
                        (plot.lines ? "3" : "4") + "\" fill=\"" + color + "\"/>\n";
        }
        flush();
        svg += dots;
    }
    return svg + "</g>\n</svg>\n";
}

std::string scatter_plot_svg(const ScatterPlot& plot) {
    const PlotAxes& ax = plot.axes;
    std::vector<double> xs, ys;
    for (const ScatterPoint& p : plot.points)
        if (usable(p.x, ax.log_x) && usable(p.y, ax.log_y)) xs.push_back(p.x), ys.push_back(p.y);

    // Guide line in the axes' own (possibly log) coordinates: y' = a + b x'.
    auto fwd_x = [&](double v) { return ax.log_x ? std::log10(v) : v; };
    auto fwd_y = [&](double v) { return ax.log_y ? std::log10(v) : v; };
    auto inv_y = [&](double v) { return ax.log_y ? std::pow(10.0, v) : v; };
    bool have_fit = false;
    double a = 0.0, b = 1.0, r2 = 0.0;
    if (plot.guide == ScatterGuide::LeastSquares && xs.size() >= 2) {
        double mx = 0, my = 0;
        for (std::size_t i = 0; i < xs.size(); ++i) mx += fwd_x(xs[i]), my += fwd_y(ys[i]);
        mx /= static_cast<double>(xs.size()), my /= static_cast<double>(xs.size());
        double sxx = 0, sxy = 0, syy = 0;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const double dx = fwd_x(xs[i]) - mx, dy = fwd_y(ys[i]) - my;
            sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
        }
        if (sxx > 0.0) {
            have_fit = true;
            b = sxy / sxx;
            a = my - b * mx;
            r2 = syy > 0.0 ? sxy * sxy / (sxx * syy) : 1.0;
        }
    }
    std::vector<LegendEntry> legend;
    if (plot.guide == ScatterGuide::Identity) legend.push_back({"y = x", "#777777", true, false});
    if (have_fit && r2 < plot.min_r2) {  // a line through unrelated points would suggest a relation
        have_fit = false;
        legend.push_back({"no fit: R\xC2\xB2 = " + format_fixed(r2, 2) + " < " + format_fixed(plot.min_r2, 2), "", false,
                          false, false});
    } else if (have_fit) {
        legend.push_back({"least-squares fit (R\xC2\xB2 = " + format_fixed(r2, 3) + ")", "#D55E00", true, false});
    }

    const Frame f(ax, xs, ys, legend);
    std::string svg = f.open(legend);
    svg += "<g clip-path=\"url(#plot-area)\">\n";
    if (plot.guide == ScatterGuide::Identity) {
        const double lo = std::max(f.x.lo, f.y.lo), hi = std::min(f.x.hi, f.y.hi);
        if (lo < hi) svg += polyline({{f.px(lo), f.py(lo)}, {f.px(hi), f.py(hi)}}, "#777777", true);
    }
    if (have_fit) {
        std::vector<std::pair<double, double>> pts;
        for (int i = 0; i <= 32; ++i) {  // sampled: straight on these axes, but cheap and exact enough
            const double t = i / 32.0;
            const double xv = ax.log_x ? f.x.lo * std::pow(f.x.hi / f.x.lo, t) : f.x.lo + t * (f.x.hi - f.x.lo);
            const double yv = inv_y(a + b * fwd_x(xv));
            if (usable(yv, ax.log_y)) pts.emplace_back(f.px(xv), f.py(yv));
        }
        if (pts.size() >= 2) svg += polyline(pts, "#D55E00", true);
    }
    std::string labels;  // outside the clip, so labels of edge points stay whole
    struct Box { double x0, y0, x1, y1; };
    std::vector<Box> taken;  // placed labels and the points themselves
    for (const ScatterPoint& p : plot.points)
        if (usable(p.x, ax.log_x) && usable(p.y, ax.log_y))
            taken.push_back({f.px(p.x) - 4, f.py(p.y) - 4, f.px(p.x) + 4, f.py(p.y) + 4});
    const auto overlaps = [&](const Box& b) {  // with another label or point, or outside the plot area
        if (b.x0 < f.left || b.x1 > f.right || b.y0 < f.top || b.y1 > f.bottom) return true;
        return std::any_of(taken.begin(), taken.end(),
                           [&](const Box& o) { return b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1; });
    };
    for (const ScatterPoint& p : plot.points) {
        if (!usable(p.x, ax.log_x) || !usable(p.y, ax.log_y)) continue;
        const double cx = f.px(p.x), cy = f.py(p.y);
        svg += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"3.5\" fill=\"#0072B2\" fill-opacity=\"0.8\"/>\n";
        if (p.label.empty()) continue;
        // First free spot of: right, left, above, below, further right/left; else right anyway.
        const double w = 6.0 * static_cast<double>(p.label.size()), h = 11.0;
        const std::array<std::pair<double, double>, 8> spots{{{cx + 6, cy - 2}, {cx - 6 - w, cy - 2}, {cx - w / 2, cy - 8},
                                                              {cx - w / 2, cy + 6 + h}, {cx + 6, cy - 10}, {cx + 6, cy + 8},
                                                              {cx - 6 - w, cy - 10}, {cx - 6 - w, cy + 8}}};
        const auto free = std::find_if(spots.begin(), spots.end(), [&](const auto& s) {
            return !overlaps({s.first, s.second - h + 2, s.first + w, s.second + 2});
        });
        if (free == spots.end()) continue;  // crowded: no label rather than an unreadable pile
        const std::pair<double, double> at = *free;
        taken.push_back({at.first, at.second - h + 2, at.first + w, at.second + 2});
        labels += "<text x=\"" + num(at.first) + "\" y=\"" + num(at.second + 3) + "\" font-size=\"10\" fill=\"#333333\">" +
                  xml_escape(p.label) + "</text>\n";
    }
    return svg + "</g>\n" + labels + "</svg>\n";
}

void write_text_file(const std::string& path, const std::string& content) {
    write_file_atomically(path, content);
}

}  // namespace rtc
