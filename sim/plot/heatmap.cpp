// Heat-map rendering and shared scales (see heatmap.h). Layout, top to
// bottom: title, bar label, [map | colour bar + ticks], no-data key, caption.
#include "sim/plot/heatmap.h"

#include "sim/util/table.h"
#include "sim/plot/text_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rtc {
namespace {

constexpr Rgb kBackground{255, 255, 255};
constexpr Rgb kInk{20, 20, 20};
constexpr Rgb kFrame{90, 90, 90};
constexpr int kMargin = 12;
constexpr int kBarGap = 16;
constexpr int kBarWidth = 18;
constexpr int kTickLength = 4;
constexpr int kMinBarHeight = 160;

void check_size(const ScalarField& f, const char* who) {
    if (f.width < 0 || f.height < 0 ||
        f.values.size() != static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height))
        throw std::invalid_argument(std::string(who) + ": field values do not match width * height");
}

// Value of the sorted sample at percentile p (0..100), nearest rank.
double percentile_of(std::vector<double>& v, double p) {
    const double q = std::clamp(p, 0.0, 100.0) / 100.0;
    const auto k = static_cast<std::size_t>(std::llround(q * static_cast<double>(v.size() - 1)));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

int auto_pixel_scale(const ScalarField& f) {
    const int longest = std::max({f.width, f.height, 1});
    return std::clamp(320 / longest, 1, 8);
}

std::string number(double v) { return format_sig(v, 3); }

std::vector<Tick> auto_ticks(const HeatmapScale& s) {
    return s.kind == ScaleKind::Log ? log_ticks(s.lo, s.hi) : linear_ticks(s.lo, s.hi, 6);
}

}  // namespace

double scale_position(const HeatmapScale& s, double v) {
    if (!std::isfinite(v)) return std::numeric_limits<double>::quiet_NaN();
    double t = 0.0;
    if (s.kind == ScaleKind::Log) {
        if (v <= 0.0 || s.lo <= 0.0 || s.hi <= s.lo) return 0.0;
        t = (std::log(v) - std::log(s.lo)) / (std::log(s.hi) - std::log(s.lo));
    } else {
        if (s.hi <= s.lo) return v >= s.hi ? 1.0 : 0.0;
        t = (v - s.lo) / (s.hi - s.lo);
    }
    return std::clamp(t, 0.0, 1.0);
}

HeatmapScale common_scale(const std::vector<const ScalarField*>& fields, double percentile, ScaleKind kind) {
    std::vector<double> values;
    for (const ScalarField* f : fields) {
        if (!f) continue;
        for (float v : f->values)
            if (std::isfinite(v) && (kind == ScaleKind::Linear || v > 0.0f)) values.push_back(v);
    }
    HeatmapScale s{0.0, 1.0, kind};
    if (kind == ScaleKind::Log) s = {1.0, 10.0, kind};
    if (values.empty()) return s;
    const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
    s.data_min = *mn;
    s.data_max = *mx;
    s.percentile = percentile;
    s.hi = percentile_of(values, percentile);
    s.lo = kind == ScaleKind::Log ? percentile_of(values, 100.0 - percentile)
                                  : *std::min_element(values.begin(), values.end());
    if (!(s.lo < s.hi)) {  // constant field: widen around the value
        if (kind == ScaleKind::Log) {
            s.lo = s.hi / 2.0;
            s.hi = s.hi * 2.0;
        } else {
            s.lo = s.hi - std::max(1.0, std::abs(s.hi) * 0.5);
            s.hi = s.hi + std::max(1.0, std::abs(s.hi) * 0.5);
            if (s.lo < 0.0 && s.hi - std::abs(s.hi) * 0.5 >= 0.0) s.lo = 0.0;
        }
    }
    return s;
}

Heatmap render_heatmap(const ScalarField& field, const HeatmapScale& scale, const HeatmapOptions& opt) {
    check_size(field, "render_heatmap");
    const int ts = std::max(opt.text_scale, 1);
    const int ps = opt.pixel_scale > 0 ? opt.pixel_scale : auto_pixel_scale(field);
    const int map_w = field.width * ps, map_h = field.height * ps;
    const int bar_h = std::max(map_h, kMinBarHeight);
    std::vector<Tick> ticks = opt.ticks.empty() ? auto_ticks(scale) : opt.ticks;
    bool any_missing = false;
    for (float v : field.values) any_missing = any_missing || !std::isfinite(v);
    // Both ends of the bar are labelled (">=" / "<=" where values were
    // clipped); inner ticks too close to an end give way.
    const bool hi_clip = scale.clipped_high(), lo_clip = scale.clipped_low();
    if (opt.ticks.empty()) {
        const double min_gap = 1.2 * text_height("0", ts) / std::max(bar_h, 1);
        std::erase_if(ticks, [&](const Tick& t) {
            const double pos = scale_position(scale, t.value);
            return std::isnan(pos) || pos < min_gap || pos > 1.0 - min_gap;
        });
        ticks.insert(ticks.begin(), {scale.lo, (lo_clip ? "<= " : "") + number(scale.lo)});
        ticks.push_back({scale.hi, (hi_clip ? ">= " : "") + number(scale.hi)});
    }
    std::string caption = opt.caption;
    if (hi_clip || lo_clip) {
        std::string note = "colours clipped";
        if (hi_clip)
            note += " above " + number(scale.hi) + (scale.percentile < 100.0 ? " (" + number(scale.percentile) + "th percentile)" : "") +
                    ", max " + number(scale.data_max);
        if (lo_clip) note += std::string(hi_clip ? ";" : "") + " below " + number(scale.lo) + ", min " + number(scale.data_min);
        caption += (caption.empty() ? "" : "\n") + note;
    }

    int label_w = 0;
    for (const Tick& t : ticks) label_w = std::max(label_w, text_width(t.label, ts));
    const int title_h = opt.title.empty() ? 0 : text_height(opt.title, ts) + 4 * ts;
    const int bar_label_h = opt.bar_label.empty() ? 0 : text_height(opt.bar_label, ts) + 2 * ts;
    const int line_h = text_height("0", ts);
    const int top = kMargin + title_h + bar_label_h + line_h / 2;  // room for the top tick label
    const int body_h = std::max(map_h, bar_h) + line_h / 2 + (any_missing ? 14 * ts : 0);
    const int caption_h = caption.empty() ? 0 : text_height(caption, ts) + 6 * ts;

    const int bar_x = kMargin + map_w + kBarGap;
    const int ticks_right = bar_x + kBarWidth + 2 + kTickLength + 3 + label_w;
    int width = std::max(ticks_right, bar_x + text_width(opt.bar_label, ts)) + kMargin;
    width = std::max({width, text_width(opt.title, ts) + 2 * kMargin, text_width(caption, ts) + 2 * kMargin});
    const int height = top + body_h + caption_h + kMargin;

    Heatmap out{Image(width, height, kBackground), {kMargin, top, map_w, map_h}, {bar_x + 1, top + 1, kBarWidth, bar_h}};
    Image& img = out.image;
    if (!opt.title.empty()) draw_text(img, kMargin, kMargin, opt.title, {kInk, ts, TextAlign::Left});
    if (!opt.bar_label.empty()) draw_text(img, bar_x, kMargin + title_h, opt.bar_label, {kInk, ts, TextAlign::Left});

    for (int y = 0; y < field.height; ++y)
        for (int x = 0; x < field.width; ++x) {
            const Rgb c = colormap_at(opt.colormap, scale_position(scale, field.at(x, y)));
            img.fill_rect(kMargin + x * ps, top + y * ps, ps, ps, c);
        }

    // Colour bar: inside rows top (t = 1) to bottom (t = 0), framed.
    const PixelRect& bar = out.colorbar;
    for (int j = 0; j < bar.height; ++j) {
        const double t = bar.height > 1 ? 1.0 - static_cast<double>(j) / (bar.height - 1) : 1.0;
        img.fill_rect(bar.x, bar.y + j, bar.width, 1, colormap_at(opt.colormap, t));
    }
    img.stroke_rect(bar.x - 1, bar.y - 1, bar.width + 2, bar.height + 2, kFrame);
    for (const Tick& t : ticks) {
        const double pos = scale_position(scale, t.value);
        if (std::isnan(pos)) continue;
        const int y = bar.y + static_cast<int>(std::lround((1.0 - pos) * (bar.height - 1)));
        const int x0 = bar.x + bar.width + 1;
        img.fill_rect(x0, y, kTickLength, 1, kInk);
        draw_text(img, x0 + kTickLength + 3, y - 4 * ts, t.label, {kInk, ts, TextAlign::Left});
    }
    if (any_missing) {
        const int y = top + std::max(map_h, bar_h) + line_h / 2 + 2 * ts;
        img.fill_rect(bar.x, y, 6 * ts, 6 * ts, kNoDataGrey);
        draw_text(img, bar.x + 8 * ts, y, "no data", {kInk, ts, TextAlign::Left});
    }
    if (!caption.empty()) draw_text(img, kMargin, top + body_h + 6 * ts, caption, {kInk, ts, TextAlign::Left});
    return out;
}

ScalarField ratio_field(const ScalarField& a, const ScalarField& b) {
    check_size(a, "ratio_field");
    check_size(b, "ratio_field");
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("ratio_field: fields differ in size");
    ScalarField r{a.width, a.height, std::vector<float>(a.values.size())};
    for (std::size_t i = 0; i < a.values.size(); ++i) {
        const float x = a.values[i], y = b.values[i];
        const bool ok = std::isfinite(x) && std::isfinite(y) && y != 0.0f;
        r.values[i] = ok ? x / y : std::numeric_limits<float>::quiet_NaN();
    }
    return r;
}

std::vector<Tick> ratio_ticks(double max_ratio) {
    std::vector<Tick> ticks;
    const int top = std::min(30, static_cast<int>(std::floor(std::log2(std::max(max_ratio, 1.0)) + 1e-9)));
    const int stride = std::max(1, (top + 3) / 4);  // at most ~9 labels
    for (int k = -top; k <= top; ++k) {
        if (k % stride != 0) continue;
        const std::string power = std::to_string(1L << std::abs(k));
        ticks.push_back({std::ldexp(1.0, k), (k < 0 ? "1/" + power : power) + "x"});
    }
    return ticks;
}

Heatmap render_ratio_map(const ScalarField& numerator, const ScalarField& denominator, const RatioMapOptions& opt) {
    const ScalarField r = ratio_field(numerator, denominator);
    const double m = opt.max_ratio > 1.0 ? opt.max_ratio : 8.0;
    HeatmapOptions h;
    h.title = opt.title;
    h.bar_label = opt.ratio_label;
    h.caption = opt.caption;
    h.colormap = Colormap::BlueWhiteRed;
    h.pixel_scale = opt.pixel_scale;
    h.text_scale = opt.text_scale;
    h.ticks = ratio_ticks(m);
    HeatmapScale scale{1.0 / m, m, ScaleKind::Log};
    for (float v : r.values) {
        if (!std::isfinite(v)) continue;
        if (!(scale.data_min <= v)) scale.data_min = v;
        if (!(scale.data_max >= v)) scale.data_max = v;
    }
    return render_heatmap(r, scale, h);
}

}  // namespace rtc
