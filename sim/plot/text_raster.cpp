// Text rasterization on top of stb_easy_font's quads (see text_raster.h).
#include "sim/plot/text_raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace rtc {
namespace {

// stb_easy_font indexes its tables with (c - 32) and takes a mutable char*;
// give it a private copy restricted to printable ASCII and newlines.
std::string sanitize(std::string_view text) {
    std::string s(text);
    for (char& c : s)
        if (c != '\n' && (c < 32 || c > 126)) c = '?';
    return s;
}

std::vector<std::string> split_lines(const std::string& s) {
    std::vector<std::string> lines(1);
    for (char c : s) {
        if (c == '\n') lines.emplace_back();
        else lines.back() += c;
    }
    return lines;
}

// Each quad vertex: x, y, z as float, then 4 colour bytes.
struct EasyFontVertex {
    float x, y, z;
    unsigned char rgba[4];
};
static_assert(sizeof(EasyFontVertex) == 16);

void draw_line(Image& image, int x, int y, std::string& line, const TextStyle& style) {
    if (line.empty()) return;
    // ~270 bytes per character on average; leave ample head room.
    std::vector<EasyFontVertex> verts(line.size() * 64 + 64);
    const int quads = stb_easy_font_print(0.0f, 0.0f, line.data(), nullptr, verts.data(),
                                          static_cast<int>(verts.size() * sizeof(EasyFontVertex)));
    const int s = std::max(style.scale, 1);
    for (int q = 0; q < quads; ++q) {
        const EasyFontVertex* v = &verts[static_cast<std::size_t>(q) * 4];
        const int x0 = static_cast<int>(std::lround(std::min(v[0].x, v[2].x)));
        const int x1 = static_cast<int>(std::lround(std::max(v[0].x, v[2].x)));
        const int y0 = static_cast<int>(std::lround(std::min(v[0].y, v[2].y)));
        const int y1 = static_cast<int>(std::lround(std::max(v[0].y, v[2].y)));
        image.fill_rect(x + x0 * s, y + y0 * s, (x1 - x0) * s, (y1 - y0) * s, style.color);
    }
}

}  // namespace

int text_width(std::string_view text, int scale) {
    std::string s = sanitize(text);
    return stb_easy_font_width(s.data()) * std::max(scale, 1);
}

int text_height(std::string_view text, int scale) {
    std::string s = sanitize(text);
    return stb_easy_font_height(s.data()) * std::max(scale, 1);
}

void draw_text(Image& image, int x, int y, std::string_view text, const TextStyle& style) {
    const int s = std::max(style.scale, 1);
    int line_y = y;
    for (std::string& line : split_lines(sanitize(text))) {
        const int w = line.empty() ? 0 : stb_easy_font_width(line.data()) * s;
        int lx = x;
        if (style.align == TextAlign::Center) lx = x - w / 2;
        if (style.align == TextAlign::Right) lx = x - w;
        draw_line(image, lx, line_y, line, style);
        line_y += 12 * s;
    }
}

}  // namespace rtc
