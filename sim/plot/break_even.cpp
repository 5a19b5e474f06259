#include "sim/plot/break_even.h"

#include "sim/plot/text_raster.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rtc {

namespace {

// Okabe & Ito's colour-blind-safe categorical palette (2008), then greys.
constexpr Rgb kPalette[] = {{0, 114, 178},  {230, 159, 0},  {0, 158, 115}, {204, 121, 167},
                            {86, 180, 233}, {213, 94, 0},   {240, 228, 66}, {0, 0, 0}};

Rgb blend(Rgb c, double t) {  // t = 0: white, 1: c
    const auto mix = [t](std::uint8_t v) { return static_cast<std::uint8_t>(std::lround(255.0 + (v - 255.0) * t)); };
    return {mix(c.r), mix(c.g), mix(c.b)};
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

// Diagonal lines on the image's own grid, so that neighbouring cells join
// into one hatched band.
void hatch(Image& img, int x0, int y0, int w, int h) {
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
            if ((x + y) % 5 == 0) img.fill_rect(x, y, 1, 1, {40, 40, 40});
}

}  // namespace

Image render_break_even(const BreakEvenGrid& g, const BreakEvenOptions& o) {
    if (g.nx <= 0 || g.ny <= 0 || g.winner.size() != static_cast<std::size_t>(g.nx * g.ny) ||
        g.margin.size() != g.winner.size())
        throw std::invalid_argument("render_break_even: grid size mismatch");
    const int cp = std::max(1, o.cell_pixels), map_w = g.nx * cp, map_h = g.ny * cp;
    const int left = 70, top = 40, legend_w = 190, bottom = 86;  // three caption lines
    // The legend: its methods, "none runs", the mark and the hatch (small maps: taller than the map).
    const int legend_h = 44 + static_cast<int>(g.methods.size() + 1) * 18 + 20 + 40;
    Image img(left + map_w + 20 + legend_w, top + std::max(map_h + bottom, legend_h), {255, 255, 255});
    draw_text(img, 10, 8, g.title, {{0, 0, 0}, 2});
    const double full = std::log(std::max(o.full_margin, 1.0001));
    for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) {
            const std::size_t i = static_cast<std::size_t>(y * g.nx + x);
            const int w = g.winner[i];
            Rgb c{128, 128, 128};
            if (w >= 0) {
                const double m = std::isfinite(g.margin[i]) ? std::log(std::max(g.margin[i], 1.0)) / full : 1.0;
                c = blend(kPalette[static_cast<std::size_t>(w) % std::size(kPalette)], 0.25 + 0.75 * std::clamp(m, 0.0, 1.0));
            }
            img.fill_rect(left + x * cp, top + (g.ny - 1 - y) * cp, cp, cp, c);
            if (g.uncertain(i)) hatch(img, left + x * cp, top + (g.ny - 1 - y) * cp, cp, cp);
        }
    img.stroke_rect(left - 1, top - 1, map_w + 2, map_h + 2, {0, 0, 0});
    // Five ticks per axis, evenly spaced on the log axes, with tick marks.
    const TextStyle small{{0, 0, 0}, 1, TextAlign::Center};
    constexpr int kTicks = 4;
    for (int k = 0; k <= kTicks; ++k) {
        const double f = static_cast<double>(k) / kTicks;
        const double xv = g.x_lo * std::pow(g.x_hi / g.x_lo, f), yv = g.y_lo * std::pow(g.y_hi / g.y_lo, f);
        const int px = left + map_w * k / kTicks, py = top + map_h - map_h * k / kTicks;
        img.fill_rect(px, top + map_h + 1, 1, 4, {0, 0, 0});
        img.fill_rect(left - 5, py, 4, 1, {0, 0, 0});
        draw_text(img, px, top + map_h + 6, number(xv), small);
        draw_text(img, left - 6, py - 4, number(yv), {{0, 0, 0}, 1, TextAlign::Right});
    }
    // The preset's own point: a black cross with a white halo, and its label.
    const auto to_px = [](double v, double lo, double hi, int span) {
        return static_cast<int>(std::lround(span * std::log(v / lo) / std::log(hi / lo)));
    };
    if (g.has_mark && g.mark_x >= g.x_lo && g.mark_x <= g.x_hi && g.mark_y >= g.y_lo && g.mark_y <= g.y_hi) {
        const int mx = left + to_px(g.mark_x, g.x_lo, g.x_hi, map_w), my = top + map_h - to_px(g.mark_y, g.y_lo, g.y_hi, map_h);
        img.fill_rect(mx - 7, my - 2, 15, 5, {255, 255, 255});
        img.fill_rect(mx - 2, my - 7, 5, 15, {255, 255, 255});
        img.fill_rect(mx - 6, my - 1, 13, 3, {0, 0, 0});
        img.fill_rect(mx - 1, my - 6, 3, 13, {0, 0, 0});
        draw_text(img, mx + 9, my - 12, g.mark_label, {{0, 0, 0}, 1, TextAlign::Left});
    }
    draw_text(img, left + map_w / 2, top + map_h + 22, g.x_label + " (log)", small);
    draw_text(img, 6, top - 14, g.y_label + " (log)", {{0, 0, 0}, 1, TextAlign::Left});
    draw_text(img, 10, top + map_h + 40, g.caption, {{60, 60, 60}, 1, TextAlign::Left});
    // Legend: method colours at full and at a 1.1x margin.
    const int lx = left + map_w + 20;
    draw_text(img, lx, top, "winner (full colour:", {});
    draw_text(img, lx, top + 12, " wins by >= " + number(o.full_margin) + "x;", {});
    draw_text(img, lx, top + 24, " pale: a close call)", {});
    for (std::size_t m = 0; m < g.methods.size(); ++m) {
        const int ly = top + 44 + static_cast<int>(m) * 18;
        const Rgb c = kPalette[m % std::size(kPalette)];
        img.fill_rect(lx, ly, 14, 12, c);
        img.fill_rect(lx + 16, ly, 14, 12, blend(c, 0.25 + 0.75 * std::log(1.1) / full));
        draw_text(img, lx + 36, ly + 2, g.methods[m], {});
    }
    const int ly = top + 44 + static_cast<int>(g.methods.size()) * 18;
    img.fill_rect(lx, ly, 14, 12, {128, 128, 128});
    draw_text(img, lx + 36, ly + 2, "none runs", {});
    if (g.has_mark) {
        img.fill_rect(lx + 1, ly + 23, 13, 3, {0, 0, 0});
        img.fill_rect(lx + 6, ly + 18, 3, 13, {0, 0, 0});
        draw_text(img, lx + 36, ly + 20, "the preset's costs", {});
    }
    if (!g.band_lo.empty()) {  // the interval's effect
        const int hy = ly + 38;
        img.fill_rect(lx, hy, 14, 12, {255, 255, 255});
        hatch(img, lx, hy, 14, 12);
        img.stroke_rect(lx, hy, 14, 12, {40, 40, 40});
        draw_text(img, lx + 20, hy + 2, "winner in doubt: the 90 %", {});
        draw_text(img, lx + 20, hy + 14, " band of its lead over " + std::to_string(g.draws), {});
        draw_text(img, lx + 20, hy + 26, " cost draws reaches 1.0", {});
    }
    if (o.scale <= 1) return img;
    Image big(img.width * o.scale, img.height * o.scale, {255, 255, 255});
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) big.fill_rect(x * o.scale, y * o.scale, o.scale, o.scale, img.get(x, y));
    return big;
}

}  // namespace rtc
