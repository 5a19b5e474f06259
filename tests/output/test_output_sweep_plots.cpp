// Sweep plots and plot layout: a paired sweep axis is one series on a log x
// axis with "count, radius" ticks, legends are key=value and outside the plot,
// colours stay distinct for many series, a weak fit is not drawn, and heat
// maps say where they clipped.
#include "sim/app/run_all.h"
#include "sim/plot/heatmap.h"
#include "sim/plot/plot_svg.h"
#include "sim/util/json_file.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <set>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

using namespace rtc;
namespace fs = std::filesystem;

namespace {

std::size_t occurrences(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The number in the attribute value that starts right after `key` (e.g.
// `width="`), searched from `from`; plain string search (std::regex trips
// GCC 12's -Wmaybe-uninitialized under the sanitizers).
double number_after(const std::string& text, const std::string& key, std::size_t from = 0) {
    const std::size_t at = text.find(key, from);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + key.size(), 32));
}

int svg_width(const std::string& svg) {
    const std::size_t open = svg.find("<svg ");
    REQUIRE(open != std::string::npos);
    return static_cast<int>(number_after(svg, "width=\"", open));
}

}  // namespace

TEST_CASE("output sweep plots: a paired axis is one series on a log axis labelled by its keys") {
    const fs::path out = fs::path(RTCSIM_BINARY_DIR) / "e2e" / "sweep_plots_paired";
    fs::remove_all(out);
    CliOptions cli;
    cli.config = "tests/configs/tiny.json";
    cli.out = out.string();
    cli.quiet = true;
    cli.threads = 2;
    cli.sets = {"sweep={\"scene\":[{\"count\":1,\"radius\":0.1},{\"count\":10,\"radius\":0.03},"
                "{\"count\":1000,\"radius\":0.003}]}",
                "output={\"images\":false,\"arrays\":false}", "workload.width=16", "workload.height=16"};
    REQUIRE(run_all(cli) == 0);
    const std::string svg = read_text_file((out / "speedup_vs_scene.svg").string());
    CHECK(occurrences(svg, "<polyline") == 1);  // one series, not one per point
    CHECK(svg.find(">count, radius (log scale)<") != std::string::npos);
    CHECK(svg.find(">1000, 0.003<") != std::string::npos);
    CHECK(svg.find("cost preset turing-per-ray-guess") != std::string::npos);
    CHECK(svg.find('{') == std::string::npos);  // no raw JSON anywhere
    CHECK(svg_width(svg) <= 1200);
    const std::string area = read_text_file((out / "speedup_vs_area_ratio.svg").string());
    CHECK(area.find("R\xC2\xB2 = ") != std::string::npos);  // R^2 printed, drawn or not
    CHECK(area.find(">1000, 0.003<") != std::string::npos);  // points carry their sweep values
}

TEST_CASE("output plot layout: distinct colours, legend outside in columns, weak fits not drawn") {
    std::set<std::string> colours;
    for (std::size_t i = 0; i < 20; ++i) colours.insert(series_color(i, 20));
    CHECK(colours.size() == 20);
    CHECK(series_color(0, 3) == series_color(0, 8));  // the qualitative palette while it lasts
    CHECK(spans_decades({1, 10, 100, 1000}));
    CHECK(!spans_decades({1, 10, 100}));
    CHECK(!spans_decades({0, 10, 1000}));

    LinePlot many;
    for (int i = 0; i < 40; ++i)
        many.series.push_back({"series number " + std::to_string(i), {0.0, 1.0}, {1.0, 2.0 + i}});
    const std::string svg = line_plot_svg(many);
    const int w = svg_width(svg);
    CHECK(w > many.axes.width);          // the legend is beside the plot area ...
    CHECK(w < many.axes.width + 700);    // ... in a few columns, not one endless one
    const std::string clip = "<clipPath id=\"plot-area\"><rect x=\"";
    const std::size_t clip_at = svg.find(clip);
    REQUIRE(clip_at != std::string::npos);
    const double plot_right = number_after(svg, clip, clip_at) + number_after(svg, " width=\"", clip_at);
    std::size_t labels = 0;
    for (std::size_t at = svg.find(">series number"); at != std::string::npos; at = svg.find(">series number", at + 1)) {
        const std::size_t text = svg.rfind("<text x=\"", at);
        REQUIRE(text != std::string::npos);
        CHECK(number_after(svg, "<text x=\"", text) > plot_right);
        ++labels;
    }
    CHECK(labels == 40);

    ScatterPlot scatter;
    scatter.guide = ScatterGuide::LeastSquares;
    scatter.points = {{1, 5, "a"}, {2, 1, "b"}, {3, 4, "c"}, {4, 2, "d"}};
    const std::string weak = scatter_plot_svg(scatter);
    CHECK(weak.find("no fit: R\xC2\xB2 = ") != std::string::npos);
    CHECK(weak.find("stroke=\"#D55E00\"") == std::string::npos);
    scatter.points = {{1, 1, "a"}, {2, 2.1, "b"}, {3, 2.9, "c"}, {4, 4.2, "d"}};
    const std::string strong = scatter_plot_svg(scatter);
    CHECK(strong.find("least-squares fit (R\xC2\xB2 = 0.9") != std::string::npos);
    CHECK(strong.find("stroke=\"#D55E00\"") != std::string::npos);
    for (const char* label : {">a<", ">b<", ">c<", ">d<"}) CHECK(strong.find(label) != std::string::npos);
}

TEST_CASE("output heatmap: a clipped scale is labelled at both ends and says where it clipped") {
    ScalarField f{10, 10, {}};
    for (int i = 0; i < 100; ++i) f.values.push_back(static_cast<float>(i));
    f.values[99] = 1e6f;
    const HeatmapScale s = common_scale({&f}, 95.0);
    CHECK(s.clipped_high());
    CHECK(!s.clipped_low());
    CHECK(s.data_max == doctest::Approx(1e6));
    HeatmapOptions o;
    o.bar_label = "cycles";
    const Heatmap small = render_heatmap(f, s, [] { HeatmapOptions x; x.text_scale = 1; return x; }());
    const Heatmap big = render_heatmap(f, s, o);
    CHECK(big.image.height > small.image.height);  // the clip note and 2x text take room
    CHECK(big.image.width > small.image.width);
    const HeatmapScale unclipped = common_scale({&f}, 100.0);
    CHECK(!unclipped.clipped_high());
}

}  // namespace RTCSIM_TEST_FILE
