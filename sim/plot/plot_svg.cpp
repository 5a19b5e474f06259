// SVG plot writer (see plot_svg.h). Both plot kinds share one frame: axes
// fitted to the data and widened to nice tick values, grid, tick labels,
// axis labels, title, and a legend (right of the plot area for line plots,
// inside its top-left corner for scatter plots, whose legend is the guide only).
#include "sim/plot/plot_svg.h"

#include "core/input_error.h"
#include "sim/util/table.h"
#include "sim/plot/ticks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace rtc {
namespace {

// Okabe-Ito colour-blind-safe palette, yellow last (weak on white).
constexpr std::array<const char*, 8> kPalette{"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                              "#E69F00", "#56B4E9", "#000000", "#F0E442"};
constexpr double kCharWidth = 7.0;  // rough width of a 12px sans-serif glyph

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

Axis make_axis(const std::vector<double>& values, bool log) {
    Axis a;
    a.log = log;
    double lo = INFINITY, hi = -INFINITY;
    for (double v : values)
        if (usable(v, log)) lo = std::min(lo, v), hi = std::max(hi, v);
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
        const std::vector<Tick> t = linear_ticks(lo, hi, 6);
        const double step = t.size() >= 2 ? t[1].value - t[0].value : (hi - lo);
        a.lo = std::floor(lo / step + 1e-9) * step;
        a.hi = std::ceil(hi / step - 1e-9) * step;
        a.ticks = linear_ticks(a.lo, a.hi, 6);
    }
    return a;
}

struct LegendEntry {
    std::string name;
    std::string color;
    bool dashed = false;
    bool marker = true;
};

// The frame shared by both plots; emits everything but the data.
struct Frame {
    PlotAxes axes;
    Axis x, y;
    double left = 70, top = 40, right = 0, bottom = 0;  // plot-area edges

    bool legend_inside = false;  // top-left inside the plot area, else right of it
    double legend_w = 0.0;
    int canvas_width = 0;  // axes.width, widened by an outside legend so long
                           // series names never squeeze the plot area

    Frame(const PlotAxes& ax, const std::vector<double>& xs, const std::vector<double>& ys,
          const std::vector<LegendEntry>& legend, bool inside)
        : axes(ax), x(make_axis(xs, ax.log_x)), y(make_axis(ys, ax.log_y)), legend_inside(inside) {
        for (const auto& e : legend) legend_w = std::max(legend_w, 34.0 + kCharWidth * static_cast<double>(e.name.size()));
        right = axes.width - 20.0;
        canvas_width = axes.width + (legend.empty() || legend_inside ? 0 : static_cast<int>(legend_w + 10.0));
        bottom = axes.height - 50.0;
        if (axes.title.empty()) top = 20;
    }
    double px(double v) const { return left + x.unit(v) * (right - left); }
    double py(double v) const { return bottom - y.unit(v) * (bottom - top); }

    std::string open(const std::vector<LegendEntry>& legend) const {
        std::string s;
        s += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
        s += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + std::to_string(canvas_width) +
             "\" height=\"" + std::to_string(axes.height) + "\" viewBox=\"0 0 " + std::to_string(canvas_width) + " " +
             std::to_string(axes.height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
        s += "<defs><clipPath id=\"plot-area\"><rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" +
             num(right - left) + "\" height=\"" + num(bottom - top) + "\"/></clipPath></defs>\n";
        s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
        if (!axes.title.empty())
            s += "<text x=\"" + num((left + right) / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">" +
                 xml_escape(axes.title) + "</text>\n";
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
        for (const Tick& t : x.ticks)
            s += "<text x=\"" + num(px(t.value)) + "\" y=\"" + num(bottom + 16) + "\" text-anchor=\"middle\">" +
                 xml_escape(t.label) + "</text>\n";
        for (const Tick& t : y.ticks)
            s += "<text x=\"" + num(left - 6) + "\" y=\"" + num(py(t.value) + 4) + "\" text-anchor=\"end\">" +
                 xml_escape(t.label) + "</text>\n";
        if (!axes.x_label.empty())
            s += "<text x=\"" + num((left + right) / 2) + "\" y=\"" + num(bottom + 38) + "\" text-anchor=\"middle\">" +
                 xml_escape(axes.x_label) + "</text>\n";
        if (!axes.y_label.empty()) {
            const std::string cy = num((top + bottom) / 2);
            s += "<text x=\"18\" y=\"" + cy + "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " + cy + ")\">" +
                 xml_escape(axes.y_label) + "</text>\n";
        }
        s += "</g>\n";
        const double lx = legend_inside ? left + 8 : right + 12;
        if (legend_inside && !legend.empty())
            s += "<rect x=\"" + num(lx - 4) + "\" y=\"" + num(top + 4) + "\" width=\"" + num(legend_w) + "\" height=\"" +
                 num(18.0 * static_cast<double>(legend.size()) + 4) +
                 "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>\n";
        for (std::size_t i = 0; i < legend.size(); ++i) {
            const LegendEntry& e = legend[i];
            const double ly = top + 16 + 18.0 * static_cast<double>(i);
            s += "<line x1=\"" + num(lx) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx + 20) + "\" y2=\"" + num(ly) +
                 "\" stroke=\"" + e.color + "\" stroke-width=\"2\"" + (e.dashed ? " stroke-dasharray=\"5,3\"" : "") + "/>\n";
            if (e.marker)
                s += "<circle cx=\"" + num(lx + 10) + "\" cy=\"" + num(ly) + "\" r=\"3\" fill=\"" + e.color + "\"/>\n";
            s += "<text x=\"" + num(lx + 26) + "\" y=\"" + num(ly + 4) + "\">" + xml_escape(e.name) + "</text>\n";
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
        for (std::size_t k = 0; k < s.x.size(); ++k)
            if (usable(s.x[k], plot.axes.log_x) && usable(s.y[k], plot.axes.log_y))
                xs.push_back(s.x[k]), ys.push_back(s.y[k]);
        legend.push_back({s.name, kPalette[i % kPalette.size()], false, plot.markers});
    }
    const Frame f(plot.axes, xs, ys, legend, false);
    std::string svg = f.open(legend);
    svg += "<g clip-path=\"url(#plot-area)\">\n";
    for (std::size_t i = 0; i < plot.series.size(); ++i) {
        const PlotSeries& s = plot.series[i];
        const std::string color = kPalette[i % kPalette.size()];
        std::vector<std::pair<double, double>> run;
        std::string dots;
        auto flush = [&] {
            if (run.size() >= 2) svg += polyline(run, color, false);
            run.clear();
        };
        for (std::size_t k = 0; k < s.x.size(); ++k) {
            if (!usable(s.x[k], plot.axes.log_x) || !usable(s.y[k], plot.axes.log_y)) {
                flush();
                continue;
            }
            run.emplace_back(f.px(s.x[k]), f.py(s.y[k]));
            if (plot.markers)
                dots += "<circle cx=\"" + num(run.back().first) + "\" cy=\"" + num(run.back().second) +
                        "\" r=\"3\" fill=\"" + color + "\"/>\n";
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
    if (have_fit) legend.push_back({"least-squares fit (R\xC2\xB2 = " + format_fixed(r2, 3) + ")", "#D55E00", true, false});

    const Frame f(ax, xs, ys, legend, true);
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
    for (const ScatterPoint& p : plot.points) {
        if (!usable(p.x, ax.log_x) || !usable(p.y, ax.log_y)) continue;
        const double cx = f.px(p.x), cy = f.py(p.y);
        svg += "<circle cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"3.5\" fill=\"#0072B2\" fill-opacity=\"0.8\"/>\n";
        if (!p.label.empty())
            labels += "<text x=\"" + num(cx + 5) + "\" y=\"" + num(cy - 5) + "\" font-size=\"10\" fill=\"#333333\">" +
                      xml_escape(p.label) + "</text>\n";
    }
    return svg + "</g>\n" + labels + "</svg>\n";
}

void write_text_file(const std::string& path, const std::string& content) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot open for writing");
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) throw InputError(path + ": write failed");
}

}  // namespace rtc
