// Tests for sim/colormap and sim/heatmap: map ends, scales, colour bar,
// no-data grey, shared percentile scale, ratio maps centred at 1.
#include "sim/plot/colormap.h"
#include "sim/plot/heatmap.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace RTCSIM_TEST_FILE {  // one per file: tests/CMakeLists.txt compiles them in batches

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST_CASE("output colormap: ends, clamping, midpoint interpolation, NaN") {
    CHECK(rtc::colormap_at(rtc::Colormap::Viridis, 0.0) == rtc::Rgb{0x44, 0x01, 0x54});
    CHECK(rtc::colormap_at(rtc::Colormap::Viridis, 1.0) == rtc::Rgb{0xFD, 0xE7, 0x25});
    CHECK(rtc::colormap_at(rtc::Colormap::Viridis, -3.0) == rtc::colormap_at(rtc::Colormap::Viridis, 0.0));
    CHECK(rtc::colormap_at(rtc::Colormap::Viridis, 7.0) == rtc::colormap_at(rtc::Colormap::Viridis, 1.0));
    CHECK(rtc::colormap_at(rtc::Colormap::Inferno, 0.0) == rtc::Rgb{0x00, 0x00, 0x04});
    CHECK(rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 0.5) == rtc::Rgb{0xF7, 0xF7, 0xF7});
    CHECK(rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 0.0).b > rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 0.0).r);
    CHECK(rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 1.0).r > rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 1.0).b);
    // Halfway between the first two viridis control points (1/8 apart).
    const rtc::Rgb mid = rtc::colormap_at(rtc::Colormap::Viridis, 1.0 / 16.0);
    CHECK(mid.g == 23);  // (0x01 + 0x2D) / 2 = 23
    CHECK(rtc::colormap_at(rtc::Colormap::Inferno, std::nan("")) == rtc::kNoDataGrey);
    CHECK(std::string(rtc::colormap_name(rtc::Colormap::Inferno)) == "inferno");
}

TEST_CASE("output heatmap: scale positions, linear and log") {
    const rtc::HeatmapScale lin{10.0, 20.0, rtc::ScaleKind::Linear};
    CHECK(rtc::scale_position(lin, 15.0) == doctest::Approx(0.5));
    CHECK(rtc::scale_position(lin, 5.0) == 0.0);
    CHECK(rtc::scale_position(lin, 50.0) == 1.0);
    CHECK(std::isnan(rtc::scale_position(lin, INFINITY)));
    const rtc::HeatmapScale log{1.0, 100.0, rtc::ScaleKind::Log};
    CHECK(rtc::scale_position(log, 10.0) == doctest::Approx(0.5));
    CHECK(rtc::scale_position(log, 0.0) == 0.0);
}

TEST_CASE("output heatmap: common scale clips the top percentile across fields") {
    rtc::ScalarField a{10, 10, {}}, b{10, 10, {}};
    for (int i = 0; i < 100; ++i) {
        a.values.push_back(static_cast<float>(i));
        b.values.push_back(static_cast<float>(i + 100));
    }
    b.values[5] = 1e9f;  // one outlier
    b.values[6] = kNaN;  // ignored
    const rtc::HeatmapScale s = rtc::common_scale({&a, &b}, 99.0);
    CHECK(s.lo == 0.0);
    CHECK(s.hi >= 190.0);
    CHECK(s.hi < 1e9);
    const rtc::HeatmapScale all = rtc::common_scale({&a, &b}, 100.0);
    CHECK(all.hi == doctest::Approx(1e9));
    const rtc::HeatmapScale lg = rtc::common_scale({&a}, 99.0, rtc::ScaleKind::Log);
    CHECK(lg.lo > 0.0);  // zeros are skipped on a log scale
    CHECK(lg.lo < lg.hi);
    const rtc::ScalarField constant{2, 1, {5.0f, 5.0f}};
    const rtc::HeatmapScale c = rtc::common_scale({&constant});
    CHECK(c.lo < 5.0);
    CHECK(c.hi > 5.0);
    const rtc::ScalarField empty{1, 1, {kNaN}};
    CHECK(rtc::common_scale({&empty}).lo < rtc::common_scale({&empty}).hi);
}

TEST_CASE("output heatmap: pixel colours match the map ends, NaN is grey, the colour bar exists") {
    const rtc::ScalarField f{3, 2, {0.0f, 100.0f, kNaN, 50.0f, 1e6f, -5.0f}};
    rtc::HeatmapOptions opt;
    opt.title = "Clocks per pixel";
    opt.bar_label = "clocks";
    opt.caption = "test";
    opt.pixel_scale = 4;
    const rtc::Heatmap h = rtc::render_heatmap(f, {0.0, 100.0}, opt);
    const rtc::Rgb low = rtc::colormap_at(rtc::Colormap::Viridis, 0.0);
    const rtc::Rgb high = rtc::colormap_at(rtc::Colormap::Viridis, 1.0);
    CHECK(h.map.width == 12);
    CHECK(h.map.height == 8);
    auto at = [&](int fx, int fy) { return h.image.get(h.map.x + fx * 4 + 2, h.map.y + fy * 4 + 2); };
    CHECK(at(0, 0) == low);
    CHECK(at(1, 0) == high);
    CHECK(at(2, 0) == rtc::kNoDataGrey);
    CHECK(at(0, 1) == rtc::colormap_at(rtc::Colormap::Viridis, 0.5));
    CHECK(at(1, 1) == high);  // clamped above hi
    CHECK(at(2, 1) == low);   // clamped below lo
    // Colour bar: top row is the high end, bottom row the low end, to the right of the map.
    const rtc::PixelRect& bar = h.colorbar;
    CHECK(bar.x > h.map.x + h.map.width);
    CHECK(bar.height >= h.map.height);
    CHECK(h.image.get(bar.x + bar.width / 2, bar.y) == high);
    CHECK(h.image.get(bar.x + bar.width / 2, bar.y + bar.height - 1) == low);
    // Ink above the map (the title) and tick labels right of the bar.
    int title_ink = 0, label_ink = 0;
    for (int y = 0; y < h.map.y; ++y)
        for (int x = 0; x < h.image.width; ++x) title_ink += h.image.get(x, y) != rtc::Rgb{255, 255, 255};
    for (int y = bar.y; y < bar.y + bar.height; ++y)
        for (int x = bar.x + bar.width + 8; x < h.image.width; ++x)
            label_ink += h.image.get(x, y) != rtc::Rgb{255, 255, 255};
    CHECK(title_ink > 20);
    CHECK(label_ink > 20);
    CHECK_THROWS_AS((void)rtc::render_heatmap(rtc::ScalarField{2, 2, {1.0f}}, {0.0, 1.0}), std::invalid_argument);
}

TEST_CASE("output heatmap: ratio map is white at 1, red above, blue below, grey without data") {
    const rtc::ScalarField ref{4, 1, {8.0f, 1.0f, 2.0f, 0.0f}};
    const rtc::ScalarField obb{4, 1, {1.0f, 8.0f, 2.0f, 0.0f}};
    const rtc::ScalarField r = rtc::ratio_field(ref, obb);
    CHECK(r.values[0] == 8.0f);
    CHECK(std::isnan(r.values[3]));
    rtc::RatioMapOptions opt;
    opt.pixel_scale = 3;
    const rtc::Heatmap h = rtc::render_ratio_map(ref, obb, opt);
    auto at = [&](int fx) { return h.image.get(h.map.x + fx * 3 + 1, h.map.y + 1); };
    CHECK(at(0) == rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 1.0));
    CHECK(at(1) == rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 0.0));
    CHECK(at(2) == rtc::colormap_at(rtc::Colormap::BlueWhiteRed, 0.5));
    CHECK(at(3) == rtc::kNoDataGrey);
    const std::vector<rtc::Tick> ticks = rtc::ratio_ticks(8.0);
    REQUIRE(ticks.size() == 7);
    CHECK(ticks[0].label == "1/8x");
    CHECK(ticks[0].value == 0.125);
    CHECK(ticks[3].label == "1x");
    CHECK(ticks[6].label == "8x");
    CHECK(rtc::ratio_ticks(1000.0).size() <= 9);
    CHECK_THROWS_AS((void)rtc::ratio_field(ref, rtc::ScalarField{2, 2, {1, 1, 1, 1}}), std::invalid_argument);
}

}  // namespace RTCSIM_TEST_FILE
