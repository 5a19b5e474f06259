// Text into an Image: titles, axis and tick labels, numbers. Glyphs come from
// stb_easy_font (libstb-dev is already a build dependency, and the font is a
// few hundred bytes of segments, no font files to ship): it emits axis-aligned
// quads on an integer grid, which we rasterize as filled rectangles, scaled by
// an integer factor (2x reads well for titles). ASCII only; other bytes are
// drawn as '?'. Lines are 12 units tall; glyphs ascend ~7 units from the top.
#pragma once

#include "sim/plot/image.h"

#include <string_view>

namespace rtc {

enum class TextAlign { Left, Center, Right };

struct TextStyle {
    Rgb color{0, 0, 0};
    int scale = 1;                    // integer magnification, >= 1
    TextAlign align = TextAlign::Left;  // relative to the x given to draw_text
};

// Size in pixels of the text's bounding box at `scale` (multi-line aware).
[[nodiscard]] int text_width(std::string_view text, int scale = 1);
[[nodiscard]] int text_height(std::string_view text, int scale = 1);

// Draws `text` with the top of its first line at y; x is the left edge, the
// centre or the right edge depending on style.align. Clipped to the image.
void draw_text(Image& image, int x, int y, std::string_view text, const TextStyle& style = {});

}  // namespace rtc
