// Tests for sim/plot_svg: well-formed SVG (balanced tags), series names and
// escaped text present, deterministic bytes, log axes, fitted guide.
#include "core/input_error.h"
#include "sim/plot/plot_svg.h"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace {

// Every element opened is closed in order; returns false on any mismatch.
bool tags_balanced(const std::string& svg) {
    std::vector<std::string> stack;
    std::size_t pos = 0;
    while ((pos = svg.find('<', pos)) != std::string::npos) {
        const std::size_t end = svg.find('>', pos);
        if (end == std::string::npos) return false;
        const std::string tag = svg.substr(pos + 1, end - pos - 1);
        pos = end + 1;
        if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
        if (tag.back() == '/') continue;  // self-closing
        if (tag[0] == '/') {
            if (stack.empty() || stack.back() != tag.substr(1)) return false;
            stack.pop_back();
            continue;
        }
        stack.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
    return stack.empty();
}

std::size_t count(const std::string& s, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}

rtc::LinePlot sample_line_plot() {
    rtc::LinePlot p;
    p.axes.title = "Speedup <vs> tilt & N";
    p.axes.x_label = "tilt (deg)";
    p.axes.y_label = "speedup";
    p.series.push_back({"N = 1", {0, 30, 60, 90}, {1.0, 1.1, 1.3, 1.4}});
    p.series.push_back({"N = 64 \"wide\"", {0, 30, 60, 90}, {1.0, 2.0, 3.5, 4.0}});
    return p;
}

}  // namespace

TEST_CASE("output plot: xml_escape") {
    CHECK(rtc::xml_escape("a<b & \"c\" 'd' >") == "a&lt;b &amp; &quot;c&quot; &apos;d&apos; &gt;");
    CHECK(rtc::xml_escape(std::string("x\x01y")) == "xy");
}

TEST_CASE("output plot: line plot is balanced, names every series, escapes text, is deterministic") {
    const rtc::LinePlot p = sample_line_plot();
    const std::string svg = rtc::line_plot_svg(p);
    CHECK(svg.rfind("<?xml", 0) == 0);
    CHECK(tags_balanced(svg));
    CHECK(svg.find("N = 1") != std::string::npos);
    CHECK(svg.find("N = 64 &quot;wide&quot;") != std::string::npos);
    CHECK(svg.find("Speedup &lt;vs&gt; tilt &amp; N") != std::string::npos);
    CHECK(svg.find("<vs>") == std::string::npos);
    CHECK(count(svg, "<polyline") == 2);
    CHECK(count(svg, "<circle") == 8 + 2);  // data points plus legend markers
    CHECK(svg == rtc::line_plot_svg(p));
    CHECK(tags_balanced("<svg><g></svg></g>") == false);  // the checker itself can fail
}

TEST_CASE("output plot: NaN breaks a line, log y skips non-positive values") {
    rtc::LinePlot p;
    p.series.push_back({"s", {1, 2, 3, 4, 5}, {1.0, 2.0, std::nan(""), 4.0, 5.0}});
    CHECK(count(rtc::line_plot_svg(p), "<polyline") == 2);
    p.axes.log_y = true;
    p.series[0].y = {0.01, 0.1, 0.0, 10.0, 100.0};
    const std::string svg = rtc::line_plot_svg(p);
    CHECK(tags_balanced(svg));
    CHECK(count(svg, "<polyline") == 2);
    CHECK(svg.find(">0.01<") != std::string::npos);  // decade tick labels
    CHECK(svg.find(">100<") != std::string::npos);
    p.series[0].y.pop_back();
    CHECK_THROWS_AS((void)rtc::line_plot_svg(p), std::invalid_argument);
}

TEST_CASE("output plot: scatter with labels, identity and fitted guides") {
    rtc::ScatterPlot p;
    p.axes.title = "speedup vs SA ratio";
    for (int i = 1; i <= 5; ++i) p.points.push_back({double(i), 2.0 * i + 1.0, "p<" + std::to_string(i)});
    p.guide = rtc::ScatterGuide::LeastSquares;
    const std::string fit = rtc::scatter_plot_svg(p);
    CHECK(tags_balanced(fit));
    CHECK(fit.find("p&lt;3") != std::string::npos);
    CHECK(fit.find("R\xC2\xB2 = 1.000") != std::string::npos);  // exactly linear data
    p.guide = rtc::ScatterGuide::Identity;
    const std::string id = rtc::scatter_plot_svg(p);
    CHECK(tags_balanced(id));
    CHECK(id.find("y = x") != std::string::npos);
    CHECK(id.find("R\xC2\xB2") == std::string::npos);
    p.guide = rtc::ScatterGuide::None;
    CHECK(count(rtc::scatter_plot_svg(p), "<circle") == 5);
}

TEST_CASE("output plot: write_text_file failure names the path") {
    const std::string bad = "/nonexistent-rtcsim-dir/plot.svg";
    try {
        rtc::write_text_file(bad, "x");
        FAIL("expected InputError");
    } catch (const rtc::InputError& e) {
        CHECK(std::string(e.what()).find(bad) != std::string::npos);
    }
}

TEST_CASE("output plot: an interval is a shaded band, or error bars on categories") {
    rtc::LinePlot p;
    const double nan = std::nan("");
    p.series.push_back({"s", {1, 2, 3, 4}, {1.0, 2.0, 3.0, 4.0}, {0.9, 1.8, nan, 3.5}, {1.1, 2.3, nan, 4.4}});
    const std::string svg = rtc::line_plot_svg(p);
    CHECK(count(svg, "<polygon") == 1);  // points 1-2 (3 has none; 4 alone is no band)
    CHECK(svg.find("fill-opacity") != std::string::npos);
    p.lines = false;
    CHECK(count(rtc::line_plot_svg(p), "<polyline") == 3);  // an error bar per point with an interval
    p.series[0].y_low.pop_back();
    CHECK_THROWS_AS((void)rtc::line_plot_svg(p), std::invalid_argument);
}

}  // namespace RTCSIM_TEST_FILE
